// The page's controls around the WebAssembly renderer (web/src/glint_web.cpp): scene, BRDF,
// anti-aliasing and cost-tier choices, the desktop viewer's sliders, orbit and zoom by mouse, touch and wheel,
// glTF files dropped on the page. Frames are drawn only when something changed.
'use strict';

const SCENES = ['sphere', 'parquet', 'carpaint', 'showroom', 'grazing-smooth', 'grazing-rough', 'arctic', 'atrium', 'car'];
const RADIANS_PER_PIXEL = 0.01;  // as the desktop viewer's orbit

const $ = (selector) => document.querySelector(selector);
const query = new URLSearchParams(location.search);

function showError(message) { $('#error').textContent = message; }

// The wasm functions, each failing one throwing Error with glint_error()'s line.
async function loadRenderer() {
  const module = await createGlint();
  const call = (name, returns, args) => module.cwrap(name, returns, args);
  const error = call('glint_error', 'string', []);
  const checked = (name, args) => {
    const f = call(name, 'number', args);
    return (...values) => { if (f(...values) !== 0) throw new Error(error()); };
  };
  // Copies bytes into wasm memory for the call, then frees them.
  const withBytes = (bytes, use) => {
    const pointer = module._malloc(Math.max(bytes.length, 1));
    module.HEAPU8.set(bytes, pointer);
    try { return use(pointer); } finally { module._free(pointer); }
  };
  const loadDictionary = checked('glint_load_dictionary', ['number', 'number']);
  const loadGltf = checked('glint_load_gltf', ['number', 'number', 'string']);
  const readFrame = checked('glint_read_frame', ['number']);
  const evaluateKernel = checked('glint_evaluate_kernel', ['number', 'number', 'number', 'number']);
  return {
    start: checked('glint_start', ['string']),
    loadDictionary: (bytes) => withBytes(bytes, (p) => loadDictionary(p, bytes.length)),
    loadBuiltin: checked('glint_load_builtin', ['string']),
    loadGltf: (bytes, name) => withBytes(bytes, (p) => loadGltf(p, bytes.length, name)),
    render: checked('glint_render', ['number', 'number']),
    finish: call('glint_finish', null, []),
    readFrame: (width, height) => {
      const size = width * height * 4;
      const pointer = module._malloc(size);
      try {
        readFrame(pointer);
        return module.HEAPU8.slice(pointer, pointer + size);
      } finally { module._free(pointer); }
    },
    evaluateKernel: (inputs, count, filtered) => {
      const bytes = new Uint8Array(inputs.buffer, inputs.byteOffset, inputs.byteLength);
      const out = module._malloc(count * 16);
      try {
        withBytes(bytes, (p) => evaluateKernel(p, count, filtered ? 1 : 0, out));
        return module.HEAPF32.slice(out / 4, out / 4 + count * 4);
      } finally { module._free(out); }
    },
    setBrdf: checked('glint_set_brdf', ['string']),
    setAntiAliasing: checked('glint_set_antialiasing', ['string']),
    setQuality: checked('glint_set_quality', ['string']),
    antiAliasing: call('glint_antialiasing', 'string', []),
    memoryBytes: () => module.HEAPU8.length,  // the WebAssembly memory, which grows and never shrinks
    setExposure: call('glint_set_exposure', null, ['number']),
    glintMaterial: call('glint_glint_material', 'number', ['number']),
    materialName: call('glint_material_name', 'string', ['number']),
    getMaterial: call('glint_get_material', 'number', ['number', 'number']),
    setMaterial: call('glint_set_material', null, ['number', 'number', 'number']),
    lightCount: call('glint_light_count', 'number', []),
    getLight: call('glint_get_light', 'number', ['number', 'number']),
    setLight: call('glint_set_light', null, ['number', 'number', 'number']),
    orbit: call('glint_orbit', null, ['number', 'number']),
    zoom: call('glint_zoom', null, ['number']),
    resetCamera: call('glint_reset_camera', null, []),
  };
}

const page = {
  renderer: null,
  sceneName: '',
  frameMs: 0,
  pending: false,
  firstFrameAt: null,
  // The canvas's drawing size: its attributes (512 x 512), or ?size=WxH.
  width: $('#view').width,
  height: $('#view').height,
};

// Draws the next frame when the browser is ready for one.
function redraw() {
  if (page.pending || !page.renderer) return;
  page.pending = true;
  requestAnimationFrame(() => {
    page.pending = false;
    try {
      drawFrame();
    } catch (e) {
      showError(e.message);
    }
  });
}

// One frame, timed to its end on the GPU (glint_finish waits for it).
function drawFrame() {
  const start = performance.now();
  page.renderer.render(page.width, page.height);
  page.renderer.finish();
  page.frameMs = performance.now() - start;
  // When the page's first frame was drawn, in ms from the start of its loading.
  if (page.firstFrameAt === null) page.firstFrameAt = performance.now();
  $('#status').textContent = `${page.sceneName}: ${page.width}x${page.height}, ${page.frameMs.toFixed(0)} ms a frame`;
}

function fillSelect(select, names) {
  select.replaceChildren(...names.map((name, i) => new Option(name, String(i))));
}

function showValue(input) {
  const value = Number(input.value);
  input.previousElementSibling.textContent = Math.abs(value) >= 10 ? value.toFixed(1) : value.toFixed(3);
}

// A fieldset of sliders editing one of the renderer's controls (a glint material's or a light's):
// `chooser` picks which, get and set read and write a field. Returns the function that reads the
// chosen one's fields into the sliders.
function controlSliders(fieldset, chooser, get, set) {
  const inputs = [...$(fieldset).querySelectorAll('input')];
  const sync = () => {
    const chosen = Number($(chooser).value);
    $(fieldset).disabled = !(chosen >= 0);
    for (const input of inputs) {
      if (chosen >= 0) input.value = get(chosen, Number(input.dataset.field));
      showValue(input);
    }
  };
  for (const input of inputs) {
    input.addEventListener('input', () => {
      set(Number($(chooser).value), Number(input.dataset.field), Number(input.value));
      showValue(input);
      redraw();
    });
  }
  $(chooser).addEventListener('change', sync);
  return sync;
}

// After a scene is loaded: its glint materials and lights in the choosers.
function sceneLoaded(name) {
  const r = page.renderer;
  page.sceneName = name;
  const materials = [];
  for (let k = 0, m; (m = r.glintMaterial(k)) >= 0; ++k) materials.push([m, r.materialName(m) || `material ${m}`]);
  $('#material').replaceChildren(...materials.map(([m, label]) => new Option(label, String(m))));
  if (!materials.length) $('#material').replaceChildren(new Option('no glint material', '-1'));
  const lights = Array.from({ length: r.lightCount() }, (_, i) => `light ${i}`);
  fillSelect($('#light'), lights);
  if (!lights.length) $('#light').replaceChildren(new Option('no light', '-1'));
  // Intensity up to ten times the light's own, as in the desktop viewer.
  const strength = lights.length ? r.getLight(Number($('#light').value), 2) : 0;
  $('#light-controls input[data-field="2"]').max = strength > 0 ? 10 * strength : 100;
  page.syncMaterialSliders();
  page.syncLightSliders();
  showError('');
  redraw();
}

function loadBuiltin(name) {
  page.renderer.loadBuiltin(name);
  $('#scene').value = name;
  sceneLoaded(name);
}

// A glTF file dropped on the page; on failure the previous scene stays and the error is shown.
async function loadDropped(file) {
  try {
    const bytes = new Uint8Array(await file.arrayBuffer());
    page.renderer.loadGltf(bytes, file.name);
    if (![...$('#scene').options].some((o) => o.value === file.name)) $('#scene').add(new Option(file.name, file.name));
    $('#scene').value = file.name;
    sceneLoaded(file.name);
  } catch (e) {
    showError(`${file.name}: ${e.message}`);
    $('#scene').value = page.sceneName;
  }
}

function wireControls() {
  const r = page.renderer;
  fillSelect($('#scene'), SCENES);
  for (const option of $('#scene').options) option.value = option.textContent;
  $('#scene').addEventListener('change', (e) => {
    if (!SCENES.includes(e.target.value)) return;  // a dropped file stays as loaded
    try { loadBuiltin(e.target.value); } catch (error) { showError(error.message); }
  });
  $('#brdf').addEventListener('change', (e) => { r.setBrdf(e.target.value); redraw(); });
  $('#aa').addEventListener('change', (e) => { r.setAntiAliasing(e.target.value); redraw(); });
  // A cost tier sets the anti-aliasing too (and the footprint and cascades, which have no control).
  $('#quality').addEventListener('change', (e) => {
    r.setQuality(e.target.value);
    $('#aa').value = r.antiAliasing();
    redraw();
  });
  $('#exposure').addEventListener('input', (e) => { r.setExposure(Number(e.target.value)); showValue(e.target); redraw(); });
  showValue($('#exposure'));
  page.syncMaterialSliders = controlSliders('#material-controls', '#material', r.getMaterial, r.setMaterial);
  page.syncLightSliders = controlSliders('#light-controls', '#light', r.getLight, r.setLight);

  // Orbit with one pointer (mouse or finger), zoom with two (pinch) or the wheel.
  const canvas = $('#view');
  const pointers = new Map();
  const spread = () => {
    const [a, b] = [...pointers.values()];
    return Math.hypot(a.x - b.x, a.y - b.y);
  };
  canvas.addEventListener('pointerdown', (e) => {
    canvas.setPointerCapture(e.pointerId);
    pointers.set(e.pointerId, { x: e.clientX, y: e.clientY });
  });
  canvas.addEventListener('pointermove', (e) => {
    const last = pointers.get(e.pointerId);
    if (!last) return;
    if (pointers.size === 1) {
      r.orbit(-(e.clientX - last.x) * RADIANS_PER_PIXEL, (e.clientY - last.y) * RADIANS_PER_PIXEL);
      pointers.set(e.pointerId, { x: e.clientX, y: e.clientY });
    } else if (pointers.size === 2) {
      const before = spread();
      pointers.set(e.pointerId, { x: e.clientX, y: e.clientY });
      const after = spread();
      if (before > 0 && after > 0) r.zoom(before / after);
    }
    redraw();
  });
  const release = (e) => pointers.delete(e.pointerId);
  canvas.addEventListener('pointerup', release);
  canvas.addEventListener('pointercancel', release);
  canvas.addEventListener('wheel', (e) => {
    e.preventDefault();
    r.zoom(Math.pow(0.9, -Math.sign(e.deltaY)));
    redraw();
  }, { passive: false });
  canvas.addEventListener('dblclick', () => { r.resetCamera(); redraw(); });

  document.addEventListener('dragover', (e) => e.preventDefault());
  document.addEventListener('drop', (e) => {
    e.preventDefault();
    const file = e.dataTransfer && e.dataTransfer.files[0];
    if (file) loadDropped(file);
  });
}

// The page's start: WebGL2, the dictionary written by `glint dict`, the first scene.
async function start() {
  const size = /^(\d+)x(\d+)$/.exec(query.get('size') || '');
  if (size) {
    page.width = $('#view').width = Number(size[1]);
    page.height = $('#view').height = Number(size[2]);
  }
  page.renderer = await loadRenderer();
  page.renderer.start('#view');
  const response = await fetch('dictionary.gdict');
  if (!response.ok) throw new Error(`dictionary.gdict: ${response.status} ${response.statusText}`);
  page.renderer.loadDictionary(new Uint8Array(await response.arrayBuffer()));
  wireControls();
  loadBuiltin(SCENES.includes(query.get('scene')) ? query.get('scene') : 'sphere');
}

// For the tests (tests/web/drive.mjs): the renderer, and the page's own steps.
window.glint = {
  ready: start().catch((e) => { showError(e.message); throw e; }),
  page,
  drawFrame,
  loadBuiltin,
};
