// The test page's renderer (test/run.mjs drives it). window.renderView(options) loads a glTF file
// and renders its default camera's view at size x size into an RGBA32F target, without tone mapping
// or colour encoding, and returns the linear radiance, rows bottom up, as base64 of float32s.
//   options: { url, size, mode: 'glints' | 'smooth' | 'core', rectLights }
//   glints: with the plugin; smooth: with the plugin, each layer its smooth target; core: without
//   the plugin (three's own material for the file). rectLights: [X, Y, Z, W, H, L] each, a
//   RectAreaLight as glint's --rect-light places it: W x H, centred at X, Y, Z, facing the centre of
//   the file's bounds, radiance L (white). environment: { url, intensity, map }, `glint env-regions`'s
//   JSON, which lights the file (applyGlintEnvironment) at that intensity, and the whole map's URL
//   (.hdr), the scene's environment.
import * as THREE from 'three';
import { FloatType, RGBAFormat, WebGLRenderTarget, WebGLRenderer } from 'three';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';
import { RectAreaLightUniformsLib } from 'three/addons/lights/RectAreaLightUniformsLib.js';
import { HDRLoader } from 'three/addons/loaders/HDRLoader.js';
import { GLTFMaterialsGlintExtension, MeshGlintMaterial, applyGlintEnvironment, loadGlintDictionary, loadGlintEnvironment } from '../src/index.js';
import { glintStatistics } from './statistics.mjs';

const renderer = new WebGLRenderer({ antialias: false });
RectAreaLightUniformsLib.init();  // three's LTC tables, which its RectAreaLight's diffuse still reads
const dictionary = loadGlintDictionary('../generated/dictionary.gdict');

window.renderView = async ({ url, size, mode, rectLights = [], environment = null }) => {
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
  // glint's --rect-light: its width level (along x of three's lookAt frame), facing the bounds' centre.
  const centre = new THREE.Box3().setFromObject(gltf.scene, true).getCenter(new THREE.Vector3());
  for (const [x, y, z, width, height, radiance] of rectLights) {
    const light = new THREE.RectAreaLight(0xffffff, radiance, width, height);
    light.position.set(x, y, z);
    light.lookAt(centre);
    gltf.scene.add(light);
  }
  const scene = new THREE.Scene();
  scene.add(gltf.scene);
  if (environment) {
    const map = environment.map ? await new HDRLoader().loadAsync(environment.map) : null;
    if (map) map.mapping = THREE.EquirectangularReflectionMapping;
    applyGlintEnvironment(scene, await loadGlintEnvironment(environment.url), { intensity: environment.intensity, map });
  }
  camera.aspect = 1;
  camera.updateProjectionMatrix();
  const target = new WebGLRenderTarget(size, size, { type: FloatType, format: RGBAFormat, depthBuffer: true });
  renderer.setPixelRatio(1);
  renderer.setSize(size, size, false);
  renderer.setRenderTarget(target);
  renderer.setClearColor(0x000000, 0);
  renderer.clear();
  const start = performance.now();
  renderer.render(scene, camera);
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

// three.js's program variants that the layer must compile in and glint through: a three.js sphere
// (uv, no tangents: the frame from the uv's derivatives) with a glint material made by hand, lit by
// one light, in each variant; returns, per variant, the pixels above twice the smooth layer's
// render (test/statistics.mjs's rule) and the object pixels, at size x size.
window.renderVariants = async ({ size }) => {
  const dict = await dictionary;
  const flatNormals = new THREE.DataTexture(new Uint8Array([128, 128, 255, 255]), 1, 1);
  flatNormals.needsUpdate = true;
  const geometry = () => new THREE.SphereGeometry(1, 96, 48);
  const placed = (light) => {
    light.position.set(2, 2, 3);
    return light;
  };
  const lights = {
    point: () => placed(new THREE.PointLight(0xffffff, 30)),
    directional: () => placed(new THREE.DirectionalLight(0xffffff, 3)),
    spot: () => placed(new THREE.SpotLight(0xffffff, 30, 0, Math.PI / 4, 0.2)),
    rectArea: () => {
      const light = placed(new THREE.RectAreaLight(0xffffff, 300, 0.15, 0.15));
      light.lookAt(0, 0, 0);
      return light;
    },
  };
  // An environment's region: a 0.08-radian square
  // about the direction (2, 2, 3), of radiance 300.
  const regionAbout = (centre, half) => {
    const c = new THREE.Vector3(...centre).normalize();
    const u = new THREE.Vector3(0, 1, 0).cross(c).normalize();
    const v = c.clone().cross(u);
    return [[-1, -1], [1, -1], [1, 1], [-1, 1]].map(([a, b]) =>
      c.clone().addScaledVector(u, a * half).addScaledVector(v, b * half).normalize());
  };
  // A loaded glint environment (loadGlintEnvironment's shape) of that one region, no light, no map.
  const environmentRegions = { residual: null, lights: [], regions: [{ corners: regionAbout([2, 2, 3], 0.04), radiance: [300, 300, 300] }] };
  const variants = {
    'no tangents (uv-derivative frame)': {},
    'computed tangents': { tangents: true },
    'normal map (three declares the tangent)': { tangents: true, material: { normalMap: flatNormals } },
    'normal map without tangents': { material: { normalMap: flatNormals } },
    clearcoat: { material: { clearcoat: 1, clearcoatRoughness: 0.1 } },
    sheen: { material: { sheen: 1, sheenRoughness: 0.5 } },
    'coloured cells, multiple scattering': { glint: { colouredCells: true, multipleScattering: true } },
    'glint textures': { glint: { roughnessTexture: flatNormals, logDensityTexture: flatNormals, relativeAreaTexture: flatNormals } },
    'directional light': { light: 'directional' },
    'spot light': { light: 'spot' },
    'rectangle area light': { light: 'rectArea' },
    'environment regions and a rectangle area light': { light: 'rectArea', regions: true },
    instanced: { instanced: true },
    skinned: { skinned: true },
  };
  const camera = new THREE.PerspectiveCamera(40, 1, 0.1, 20);
  camera.position.set(0, 0, 3.2);
  const results = {};
  for (const [name, variant] of Object.entries(variants)) {
    const frames = {};
    for (const smooth of [false, true]) {
      const material = new MeshGlintMaterial({
        color: 0x992222, metalness: 0, roughness: 0.5, ...variant.material,
        glint: { logDensity: 12, uvScale: 8, ndf: 'beckmann', masking: 'v-cavity', multipleScattering: false, ...variant.glint },
      });
      if (variant.glint && variant.glint.logDensityTexture) material.glint.logDensityRange.set(12, 12);
      material.glintDictionary = dict;
      material.glintSmooth = smooth;
      const g = geometry();
      if (variant.tangents) g.computeTangents();
      let mesh;
      if (variant.instanced) {
        mesh = new THREE.InstancedMesh(g, material, 1);
        mesh.setMatrixAt(0, new THREE.Matrix4().makeRotationY(0.7));
      } else if (variant.skinned) {
        const count = g.attributes.position.count;
        g.setAttribute('skinIndex', new THREE.Uint16BufferAttribute(new Uint16Array(4 * count), 4));
        const weights = new Float32Array(4 * count);
        for (let i = 0; i < count; ++i) weights[4 * i] = 1;
        g.setAttribute('skinWeight', new THREE.Float32BufferAttribute(weights, 4));
        mesh = new THREE.SkinnedMesh(g, material);
        const bone = new THREE.Bone();
        mesh.add(bone);
        mesh.bind(new THREE.Skeleton([bone]));
        bone.rotation.y = 0.7;
      } else {
        mesh = new THREE.Mesh(g, material);
      }
      const scene = new THREE.Scene();
      scene.add(mesh, lights[variant.light || 'point']());
      if (variant.regions) applyGlintEnvironment(scene, environmentRegions);
      const target = new THREE.WebGLRenderTarget(size, size, { type: THREE.FloatType });
      renderer.setRenderTarget(target);
      renderer.setClearColor(0x000000, 0);
      renderer.clear();
      renderer.render(scene, camera);
      frames[smooth ? 'smooth' : 'glints'] = new Float32Array(size * size * 4);
      renderer.readRenderTargetPixels(target, 0, 0, size, size, frames[smooth ? 'smooth' : 'glints']);
      renderer.setRenderTarget(null);
      target.dispose();
      material.dispose();
      g.dispose();
    }
    const s = glintStatistics(frames.glints, frames.smooth);
    results[name] = { objectPixels: s.objectPixels, glintPixels: s.glintPixels, meanRatio: s.meanRatio };
  }
  return results;
};
