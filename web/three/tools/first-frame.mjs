// Time from page start to the first frame with glints on the example page (README, "Example"), one
// fresh headless chromium per run (fresh profile: no program cache), Mesa's shader cache off.
//   node tools/first-frame.mjs ROUNDS NAME=FOLDER ...
// Each round runs every variant once (order alternating), with the page's generated/ served from
// FOLDER (a folder that tools/build.mjs wrote, e.g. generated itself: `current=generated`).
import { createRequire } from 'node:module';
import { loadavg } from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
const packageRoot = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..');
const require = createRequire(path.join(packageRoot, 'package.json'));
const puppeteer = require('puppeteer-core');
const { serve } = await import('./serve.mjs');
const [runs = '5', ...specs] = process.argv.slice(2);
const variants = specs.map((s) => s.split('=')).map(([label, folder]) => [label, path.resolve(folder)]);
if (!variants.length) {
  console.error('usage: node tools/first-frame.mjs ROUNDS NAME=FOLDER ...');
  process.exit(2);
}
const SIZE = 384;

// Injected before the page's scripts: marks the shaders that hold the kernel, the programs they
// are attached to, and records the first draw with such a program, the rAF callback it was in,
// and the time the next animation frame starts (the glint frame was handed on).
const probe = () => {
  const t = (window.__glintTiming = { kernelShaders: 0, glintPrograms: 0, linkChecks: [] });
  const P = WebGL2RenderingContext.prototype;
  const kernelShaders = new WeakSet();
  const glintPrograms = new WeakSet();
  let current = null;
  let inFrame = false;
  let frameStart = 0;
  const shaderSource = P.shaderSource;
  P.shaderSource = function (shader, source) {
    if (source.includes('shader kernel: the whole kernel as glsl-es')) {
      kernelShaders.add(shader);
      t.kernelShaders++;
      t.kernelSourceChars = source.length;
      if (t.firstKernelShaderSource === undefined) t.firstKernelShaderSource = performance.now();
    }
    return shaderSource.call(this, shader, source);
  };
  const attachShader = P.attachShader;
  P.attachShader = function (program, shader) {
    if (kernelShaders.has(shader)) { glintPrograms.add(program); t.glintPrograms++; }
    return attachShader.call(this, program, shader);
  };
  const getProgramParameter = P.getProgramParameter;
  P.getProgramParameter = function (program, pname) {
    const before = performance.now();
    const r = getProgramParameter.call(this, program, pname);
    if (glintPrograms.has(program) && pname === this.LINK_STATUS) t.linkChecks.push({ at: performance.now(), waited: performance.now() - before, ok: r });
    return r;
  };
  const useProgram = P.useProgram;
  P.useProgram = function (program) { current = program; return useProgram.call(this, program); };
  const mark = () => {
    if (t.firstGlintDraw === undefined && current && glintPrograms.has(current)) {
      t.firstGlintDraw = performance.now();
      t.glintFrameStart = inFrame ? frameStart : undefined;
      t.pendingFrameEnd = true;
    }
  };
  for (const name of ['drawArrays', 'drawElements', 'drawArraysInstanced', 'drawElementsInstanced', 'drawRangeElements']) {
    const f = P[name];
    P[name] = function (...a) { mark(); return f.apply(this, a); };
  }
  const raf = window.requestAnimationFrame.bind(window);
  window.requestAnimationFrame = (cb) => raf((ts) => {
    const now = performance.now();
    if (t.pendingFrameEnd && t.nextFrameStart === undefined && t.glintFrameEnd !== undefined) t.nextFrameStart = now;
    inFrame = true; frameStart = now;
    try { cb(ts); } finally {
      inFrame = false;
      if (t.pendingFrameEnd && t.glintFrameEnd === undefined) t.glintFrameEnd = performance.now();
    }
  });
};

const results = [];
{
  for (let round = 0; round < Number(runs); ++round) for (const [label, module] of (round % 2 ? [...variants].reverse() : variants)) {
    const run = round;
    const server = await serve(0, { '/generated': module });
    const browser = await puppeteer.launch({
      executablePath: '/usr/bin/chromium',
      headless: true,
      args: ['--headless=new', '--no-sandbox', '--use-gl=angle', '--use-angle=gl-egl', '--ignore-gpu-blocklist'],
      env: { ...process.env, MESA_SHADER_CACHE_DISABLE: 'true' },
    });
    try {
      const page = await browser.newPage();
      const errors = [];
      page.on('pageerror', (e) => errors.push(e.message));
      await page.setViewport({ width: SIZE, height: SIZE });
      await page.evaluateOnNewDocument(probe);
      await page.goto(`http://127.0.0.1:${server.address().port}/example/`, { waitUntil: 'load' });
      await page.waitForFunction(() => window.__glintTiming && window.__glintTiming.nextFrameStart !== undefined, { timeout: 300000, polling: 50 });
      const t = await page.evaluate(() => window.__glintTiming);
      const nav = await page.evaluate(() => JSON.parse(JSON.stringify(performance.getEntriesByType('navigation')[0])));
      const err = await page.evaluate(() => document.querySelector('#error').textContent);
      if (err || errors.length) throw new Error(err || errors.join('; '));
      const r = {
        run, loadavg1: loadavg()[0].toFixed(2), kernelShaders: t.kernelShaders, glintPrograms: t.glintPrograms, kernelSourceChars: t.kernelSourceChars,
        domContentLoaded: nav.domContentLoadedEventEnd, load: nav.loadEventEnd,
        firstKernelShaderSource: t.firstKernelShaderSource, firstLink: t.linkChecks[0] && t.linkChecks[0].at,
        linkWait: t.linkChecks[0] && t.linkChecks[0].waited,
        glintFrameStart: t.glintFrameStart, firstGlintDraw: t.firstGlintDraw, glintFrameEnd: t.glintFrameEnd, nextFrameStart: t.nextFrameStart,
      };
      results.push({ label, ...r });
      console.log(`${label} ${run}: ` + Object.entries(r).map(([k, v]) => `${k}=${typeof v === 'number' && !Number.isInteger(v) ? v.toFixed(0) : v}`).join(' '));
    } finally {
      await browser.close();
      server.close();
    }
  }
}
const stat = (label, key) => {
  const v = results.filter((r) => r.label === label).map((r) => r[key]).sort((a, b) => a - b);
  return `${key}: median ${v[Math.floor(v.length / 2)].toFixed(0)} ms, range ${v[0].toFixed(0)}-${v[v.length - 1].toFixed(0)}`;
};
for (const r of results) { r.frame = r.firstGlintDraw - r.glintFrameStart; r.threePrep = r.firstKernelShaderSource - r.glintFrameStart; r.compile = r.firstGlintDraw - r.firstKernelShaderSource; }
for (const [label] of variants) for (const key of ['load', 'nextFrameStart', 'frame', 'threePrep', 'compile']) console.log(`${label} ${stat(label, key)}`);
