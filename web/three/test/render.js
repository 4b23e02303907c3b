// The test page's renderer (test/run.mjs drives it): window.renderView(options) loads a glTF file
// and renders its default camera's view at size x size into an RGBA32F target, without tone mapping
// or colour encoding, and returns the linear radiance, rows bottom up, as base64 of float32s.
//   options: { url, size, mode: 'glints' | 'smooth' | 'core' }
//   glints: with the plugin; smooth: with the plugin, each layer its smooth target; core: without
//   the plugin (three's own material for the file).
import { FloatType, RGBAFormat, WebGLRenderTarget, WebGLRenderer } from 'three';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';
import { GLTFMaterialsGlintExtension, loadGlintDictionary } from '../src/index.js';

const renderer = new WebGLRenderer({ antialias: false });
const dictionary = loadGlintDictionary('../generated/dictionary.gdict');

window.renderView = async ({ url, size, mode }) => {
  const loader = new GLTFLoader();
  if (mode !== 'core') {
    loader.register((parser) => new GLTFMaterialsGlintExtension(parser, { dictionary, smooth: mode === 'smooth' }));
  }
  const gltf = await loader.loadAsync(url);
  // glint's view: the camera named "default", else the first in node order (glint's rule).
  let camera = gltf.scene.getObjectByName('default');
  if (!camera || !camera.isCamera) gltf.scene.traverse((o) => { if (!camera && o.isCamera) camera = o; });
  if (!camera || !camera.isCamera) throw new Error(`${url}: no camera`);
  // glint reads glTF's photometric light units at 683 lm/W (candela / 683 = W/sr); three.js takes
  // the numbers as they are.
  gltf.scene.traverse((o) => {
    if (o.isLight) o.intensity /= 683;
  });
  camera.aspect = 1;
  camera.updateProjectionMatrix();
  const target = new WebGLRenderTarget(size, size, { type: FloatType, format: RGBAFormat, depthBuffer: true });
  renderer.setPixelRatio(1);
  renderer.setSize(size, size, false);
  renderer.setRenderTarget(target);
  renderer.setClearColor(0x000000, 0);
  renderer.clear();
  const start = performance.now();
  renderer.render(gltf.scene, camera);
  const pixels = new Float32Array(size * size * 4);
  renderer.readRenderTargetPixels(target, 0, 0, size, size, pixels);
  const ms = performance.now() - start;
  renderer.setRenderTarget(null);
  target.dispose();
  const materials = new Set();
  gltf.scene.traverse((o) => {
    if (o.material) materials.add(o.material.isMeshGlintMaterial ? 'MeshGlintMaterial' : o.material.type);
  });
  const bytes = new Uint8Array(pixels.buffer);
  let text = '';
  for (let i = 0; i < bytes.length; i += 0x8000) text += String.fromCharCode(...bytes.subarray(i, i + 0x8000));
  return { pixels: btoa(text), ms, materials: [...materials], lights: gltf.scene.getObjectsByProperty('isLight', true).map((l) => l.type) };
};
window.ready = true;
