// Drives the page (web/page) in the system's headless chromium for tests/test_web.cpp and
// scripts/web-bench: serves the built site and the job's folder on 127.0.0.1, runs the job's steps
// in the page and writes their results into the job's folder, with report.json saying what each
// step gave, every error the page logged or threw, and when its first frame was drawn (ms from
// the start of loading).
//   node tests/web/drive.mjs SITE_DIR JOB_DIR swiftshader|llvmpipe
// JOB_DIR/job.json: {"steps": [...]}, each step one of
//   {"kind": "kernel", "inputs": "in.bin", "count": N, "filtered": false, "output": "out.bin"}
//   {"kind": "scene", "name": "sphere", "width": 128, "height": 128, "output": "sphere.rgba"}
//     (and "brdf": "cook-torrance" or "zirr-kaplanyan", glint by default; "quality": a cost tier
//     chosen in the page's quality list, exact by default; the step reports the page's
//     anti-aliasing choice after it and the WebAssembly memory's size in bytes)
//   {"kind": "time", "name": "sphere", "width": 256, "height": 256, "frames": 5}
//   {"kind": "drop", "file": "broken.gltf"}  (with "output", "width", "height": then a frame of it, read)
//   {"kind": "sliders", "name": "sphere", "width": 64, "height": 64}
//   {"kind": "screenshot", "output": "page.png", "scene": "sphere"}
import { readFile, writeFile } from 'node:fs/promises';
import { createServer } from 'node:http';
import path from 'node:path';
import puppeteer from 'puppeteer-core';

const [siteDir, jobDir, backend] = process.argv.slice(2);
if (!siteDir || !jobDir || !['swiftshader', 'llvmpipe'].includes(backend)) {
  console.error('usage: node drive.mjs SITE_DIR JOB_DIR swiftshader|llvmpipe');
  process.exit(2);
}

// Chromium's WebGL2 without a GPU: SwiftShader, or Mesa llvmpipe through ANGLE's EGL backend.
const BACKEND_FLAGS = {
  swiftshader: ['--use-angle=swiftshader', '--enable-unsafe-swiftshader'],
  llvmpipe: ['--use-gl=angle', '--use-angle=gl-egl', '--ignore-gpu-blocklist'],
};

const TYPES = { '.html': 'text/html', '.js': 'text/javascript', '.wasm': 'application/wasm', '.png': 'image/png' };

function serve(root) {
  const server = createServer(async (request, response) => {
    const file = path.join(root, decodeURIComponent(new URL(request.url, 'http://x').pathname));
    if (!file.startsWith(root)) {
      response.writeHead(403).end();
      return;
    }
    try {
      const body = await readFile(file);
      response.writeHead(200, { 'Content-Type': TYPES[path.extname(file)] || 'application/octet-stream' }).end(body);
    } catch {
      response.writeHead(404).end();
    }
  });
  return new Promise((resolve) => server.listen(0, '127.0.0.1', () => resolve(server)));
}

const job = JSON.parse(await readFile(path.join(jobDir, 'job.json'), 'utf8'));
const server = await serve(path.resolve(siteDir));
const address = `http://127.0.0.1:${server.address().port}`;
const browser = await puppeteer.launch({
  executablePath: process.env.GLINT_CHROMIUM || '/usr/bin/chromium',
  headless: true,
  args: ['--headless=new', '--no-sandbox', ...BACKEND_FLAGS[backend]],
});
const report = { backend, consoleErrors: [], pageErrors: [], steps: [] };
try {
  const page = await browser.newPage();
  page.on('console', (message) => {
    if (message.type() === 'error') report.consoleErrors.push(message.text());
  });
  page.on('pageerror', (error) => report.pageErrors.push(String(error && error.message)));
  await page.setViewport({ width: 900, height: 620 });
  await page.goto(`${address}/index.html`, { waitUntil: 'load' });
  await page.evaluate(() => window.glint.ready);
  // The first frame, drawn on the next animation frame after the page is ready.
  report.firstFrameAt = await page.evaluate(async () => {
    while (window.glint.page.firstFrameAt === null) await new Promise((resolve) => setTimeout(resolve, 20));
    return window.glint.page.firstFrameAt;
  });

  for (const step of job.steps) {
    if (step.kind === 'kernel') {
      const inputs = (await readFile(path.join(jobDir, step.inputs))).toString('base64');
      const output = await page.evaluate((base64, count, filtered) => {
        const bytes = Uint8Array.from(atob(base64), (c) => c.charCodeAt(0));
        const values = window.glint.page.renderer.evaluateKernel(new Float32Array(bytes.buffer), count, filtered);
        let text = '';
        const out = new Uint8Array(values.buffer);
        for (let i = 0; i < out.length; i += 0x8000) text += String.fromCharCode(...out.subarray(i, i + 0x8000));
        return btoa(text);
      }, inputs, step.count, Boolean(step.filtered));
      await writeFile(path.join(jobDir, step.output), Buffer.from(output, 'base64'));
      report.steps.push({ kind: 'kernel', output: step.output });
    } else if (step.kind === 'scene' || step.kind === 'time') {
      const result = await page.evaluate((name, width, height, frames, read, brdf, quality) => {
        const { page: p, loadBuiltin, drawFrame } = window.glint;
        p.width = document.querySelector('#view').width = width;
        p.height = document.querySelector('#view').height = height;
        p.renderer.setBrdf(brdf);
        const tiers = document.querySelector('#quality');
        tiers.value = quality;
        tiers.dispatchEvent(new Event('change'));
        loadBuiltin(name);
        const ms = [];
        for (let i = 0; i < frames; ++i) {
          drawFrame();
          ms.push(p.frameMs);
        }
        let pixels = '';
        if (read) {
          const rgba = p.renderer.readFrame(width, height);
          for (let i = 0; i < rgba.length; i += 0x8000) pixels += String.fromCharCode(...rgba.subarray(i, i + 0x8000));
        }
        return { ms, pixels: btoa(pixels), error: document.querySelector('#error').textContent,
                 antiAliasing: document.querySelector('#aa').value, memoryBytes: p.renderer.memoryBytes() };
      }, step.name, step.width, step.height, step.frames || 1, step.kind === 'scene', step.brdf || 'glint',
      step.quality || 'exact');
      if (step.kind === 'scene') await writeFile(path.join(jobDir, step.output), Buffer.from(result.pixels, 'base64'));
      report.steps.push({ kind: step.kind, name: step.name, ms: result.ms, error: result.error,
                          antiAliasing: result.antiAliasing, memoryBytes: result.memoryBytes });
    } else if (step.kind === 'drop') {
      // A real drop event on the page, carrying the file as a user's drag would.
      const bytes = (await readFile(path.join(jobDir, step.file))).toString('base64');
      const result = await page.evaluate(async (base64, name, width, height) => {
        const before = window.glint.page.sceneName;
        const error = document.querySelector('#error');
        const errorBefore = error.textContent;
        const data = Uint8Array.from(atob(base64), (c) => c.charCodeAt(0));
        const transfer = new DataTransfer();
        transfer.items.add(new File([data], name));
        document.body.dispatchEvent(new DragEvent('drop', { dataTransfer: transfer, bubbles: true, cancelable: true }));
        // Until the page says something new or shows another scene (5 s at most).
        for (let i = 0; i < 100 && error.textContent === errorBefore && window.glint.page.sceneName === before; ++i) {
          await new Promise((resolve) => setTimeout(resolve, 50));
        }
        await new Promise((resolve) => requestAnimationFrame(() => requestAnimationFrame(resolve)));
        let pixels = '';
        if (width > 0) {
          const { page: p, drawFrame } = window.glint;
          p.width = document.querySelector('#view').width = width;
          p.height = document.querySelector('#view').height = height;
          drawFrame();
          const rgba = p.renderer.readFrame(width, height);
          for (let i = 0; i < rgba.length; i += 0x8000) pixels += String.fromCharCode(...rgba.subarray(i, i + 0x8000));
        }
        return { error: error.textContent, before, after: window.glint.page.sceneName, pixels: btoa(pixels) };
      }, bytes, path.basename(step.file), step.output ? step.width : 0, step.height || 0);
      const { pixels, ...said } = result;
      if (step.output) await writeFile(path.join(jobDir, step.output), Buffer.from(pixels, 'base64'));
      report.steps.push({ kind: 'drop', file: step.file, ...said });
    } else if (step.kind === 'sliders') {
      // Each slider of the page's glint material and light moved as a user would (an input event),
      // one at a time from the scene as loaded: whether the frame changed.
      const result = await page.evaluate((name, width, height) => {
        const { page: p, loadBuiltin, drawFrame } = window.glint;
        const frame = () => {
          drawFrame();
          return p.renderer.readFrame(width, height);
        };
        p.width = document.querySelector('#view').width = width;
        p.height = document.querySelector('#view').height = height;
        const changed = {};
        for (const input of document.querySelectorAll('#material-controls input, #light-controls input')) {
          loadBuiltin(name);
          const before = frame();
          const label = input.parentElement.textContent.trim();
          input.value = Number(input.min) + 0.3 * (Number(input.max) - Number(input.min));
          input.dispatchEvent(new Event('input'));
          const after = frame();
          changed[label] = before.some((v, i) => v !== after[i]);
        }
        return { changed, error: document.querySelector('#error').textContent };
      }, step.name, step.width, step.height);
      report.steps.push({ kind: 'sliders', name: step.name, ...result });
    } else if (step.kind === 'screenshot') {
      await page.evaluate((name) => {
        const { page: p, loadBuiltin, drawFrame } = window.glint;
        p.width = document.querySelector('#view').width = 512;
        p.height = document.querySelector('#view').height = 512;
        loadBuiltin(name);
        drawFrame();
      }, step.scene);
      await page.screenshot({ path: path.join(jobDir, step.output) });
      report.steps.push({ kind: 'screenshot', output: step.output });
    } else {
      throw new Error(`unknown step kind '${step.kind}'`);
    }
  }
} catch (error) {
  report.failure = String(error && error.stack || error);
} finally {
  await browser.close();
  server.close();
}
await writeFile(path.join(jobDir, 'report.json'), JSON.stringify(report, null, 1));
if (report.failure) {
  console.error(`drive.mjs: ${report.failure}`);
  process.exit(1);
}
