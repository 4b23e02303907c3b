// A picture of the example page (README.md's): headless chromium (WebGL2 on Mesa llvmpipe through
// ANGLE) at SIZE x SIZE pixels, the car paint once loaded and drawn for a second; then prints the
// page's frame-time line with the glints and with the smooth lobe (the "glints" box unticked), and
// with the glints again under each level-of-detail construction of the menu.
//   node tools/screenshot.mjs OUT.png [SIZE]      (after npm run build)
import path from 'node:path';
import puppeteer from 'puppeteer-core';
import { serve } from './serve.mjs';

const [output, size = '384'] = process.argv.slice(2);
if (!output) {
  console.error('usage: node tools/screenshot.mjs OUT.png [SIZE]');
  process.exit(2);
}
const server = await serve(0);
const browser = await puppeteer.launch({
  executablePath: process.env.GLINT_CHROMIUM || '/usr/bin/chromium',
  headless: true,
  args: ['--headless=new', '--no-sandbox', '--use-gl=angle', '--use-angle=gl-egl', '--ignore-gpu-blocklist'],
});
try {
  const page = await browser.newPage();
  const errors = [];
  page.on('pageerror', (error) => errors.push(error.message));
  await page.setViewport({ width: Number(size), height: Number(size) });
  await page.goto(`http://127.0.0.1:${server.address().port}/example/`, { waitUntil: 'load' });
  await page.evaluate(() => window.glintExample.loaded);
  // Until the frame-time line has its first measurement (a second of frames).
  await page.waitForFunction(() => document.querySelector('#frame-time').textContent !== 'frame: -', { timeout: 120000 });
  const error = await page.evaluate(() => document.querySelector('#error').textContent);
  if (error || errors.length) throw new Error(error || errors.join('; '));
  await page.screenshot({ path: path.resolve(output) });
  console.log(`glint-three: wrote ${output}`);
  // A fresh measurement (the page's line covers the last second) with glints, then without.
  const measure = async () => {
    const before = await page.evaluate(() => document.querySelector('#frame-time').textContent);
    await page.waitForFunction((b) => document.querySelector('#frame-time').textContent !== b, { timeout: 120000 }, before);
    const first = await page.evaluate(() => document.querySelector('#frame-time').textContent);
    await page.waitForFunction((b) => document.querySelector('#frame-time').textContent !== b, { timeout: 120000 }, first);
    return page.evaluate(() => document.querySelector('#frame-time').textContent);
  };
  console.log(`glints, ${size}x${size}: ${await measure()}`);
  await page.click('#glints');
  console.log(`smooth lobe, ${size}x${size}: ${await measure()}`);
  await page.click('#glints');
  for (const lod of ['paper', 'consistent', 'tree']) {
    await page.select('#lod', lod);
    console.log(`glints, lod ${lod}, ${size}x${size}: ${await measure()}`);
  }
  if (errors.length) throw new Error(errors.join('; '));
} finally {
  await browser.close();
  server.close();
}
