// The example (example/index.html): a .glb with EXT_materials_glint in three.js, orbiting.
import {
  ACESFilmicToneMapping, Box3, Color, PMREMGenerator, PerspectiveCamera, Scene, Vector3, WebGLRenderer,
} from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';
import { GLTFMaterialsGlintExtension, loadGlintDictionary } from '../src/index.js';

// glint's default ambient light for glTF files (docs/scenes.md): a uniform grey-blue sky.
const AMBIENT = new Color(0.26, 0.3, 0.36);

const canvas = document.createElement('canvas');
document.body.prepend(canvas);
const renderer = new WebGLRenderer({ canvas, antialias: false });
renderer.setPixelRatio(window.devicePixelRatio);
renderer.toneMapping = ACESFilmicToneMapping;

// The ambient light as an environment (three's smooth image-based lighting: no glints from it).
const ambientScene = new Scene();
ambientScene.background = AMBIENT;
const pmrem = new PMREMGenerator(renderer);
const environment = pmrem.fromScene(ambientScene).texture;

const dictionary = loadGlintDictionary('../generated/dictionary.gdict');
const camera = new PerspectiveCamera(45, 1, 0.01, 100);
const controls = new OrbitControls(camera, canvas);
controls.enableDamping = true;
let scene = null;
let glintMaterials = [];

const say = (text) => {
  document.querySelector('#error').textContent = text;
};

async function load(url) {
  say('');
  const loader = new GLTFLoader();
  loader.register((parser) => new GLTFMaterialsGlintExtension(parser, { dictionary }));
  let gltf;
  try {
    gltf = await loader.loadAsync(url);
  } catch (error) {
    say(`${url}: ${error.message}`);
    return;
  }
  scene = new Scene();  // gltf.scene is a Group: a Scene carries the background and environment
  scene.add(gltf.scene);
  scene.background = AMBIENT;
  scene.environment = environment;
  // glint reads glTF's photometric light units at 683 lm/W; three takes them as they are.
  scene.traverse((o) => {
    if (o.isLight) o.intensity /= 683;
  });
  glintMaterials = [];
  scene.traverse((o) => {
    if (o.material && o.material.isMeshGlintMaterial && !glintMaterials.includes(o.material)) glintMaterials.push(o.material);
  });
  for (const material of glintMaterials) material.userData.glintFileLod = material.glint.lod;
  setGlints(document.querySelector('#glints').checked);
  setLod(document.querySelector('#lod').value);
  // Start at the file's default camera (glint's rule: the one named "default", else the first),
  // orbiting about the scene's centre.
  let start = scene.getObjectByName('default');
  if (!start || !start.isCamera) scene.traverse((o) => { if ((!start || !start.isCamera) && o.isCamera) start = o; });
  const centre = new Box3().setFromObject(scene).getCenter(new Vector3());
  if (start && start.isCamera) {
    scene.updateMatrixWorld(true);
    start.getWorldPosition(camera.position);
    start.getWorldQuaternion(camera.quaternion);
    camera.fov = start.fov;
    camera.updateProjectionMatrix();
    // The orbit's centre on the camera's view ray, as far as the scene's centre (glint's viewer).
    const forward = new Vector3(0, 0, -1).applyQuaternion(camera.quaternion);
    controls.target.copy(camera.position).addScaledVector(forward, camera.position.distanceTo(centre));
  } else {
    camera.position.copy(centre).add(new Vector3(0, 1, 4));
    controls.target.copy(centre);
  }
  controls.update();
}

function setGlints(on) {
  for (const material of glintMaterials) {
    material.glintSmooth = !on;  // another program, chosen at the next frame
  }
}

// Every layer's LOD construction (docs/method.md 2.7, 2.8), or the file's own: scroll to dolly and
// compare how the glints hold as the surface recedes.
function setLod(lod) {
  for (const material of glintMaterials) {
    material.glint.lod = lod || material.userData.glintFileLod;  // another program, chosen at the next frame
  }
}

function resize() {
  const width = canvas.clientWidth;
  const height = canvas.clientHeight;
  if (canvas.width !== Math.floor(width * renderer.getPixelRatio()) || canvas.height !== Math.floor(height * renderer.getPixelRatio())) {
    renderer.setSize(width, height, false);
    camera.aspect = width / height;
    camera.updateProjectionMatrix();
  }
}

// The frame time: the mean interval between frames over the last second (the display's refresh
// caps it), and the mean time of the render call itself.
const frameTime = document.querySelector('#frame-time');
let frames = 0;
let renderMs = 0;
let windowStart = performance.now();
function frame() {
  requestAnimationFrame(frame);
  resize();
  controls.update();
  if (!scene) return;
  const start = performance.now();
  renderer.render(scene, camera);
  renderMs += performance.now() - start;
  ++frames;
  const now = performance.now();
  if (now - windowStart > 1000) {
    const interval = (now - windowStart) / frames;
    frameTime.textContent = `frame: ${interval.toFixed(1)} ms (${(1000 / interval).toFixed(0)} fps), render call ${(renderMs / frames).toFixed(1)} ms`;
    frames = 0;
    renderMs = 0;
    windowStart = now;
  }
}

const model = new URLSearchParams(location.search).get('model');
const select = document.querySelector('#model');
if (model) {
  select.add(new Option(model.split('/').pop(), model));
  select.value = model;
}
select.addEventListener('change', () => load(select.value));
document.querySelector('#glints').addEventListener('change', (event) => setGlints(event.target.checked));
document.querySelector('#lod').addEventListener('change', (event) => setLod(event.target.value));
window.glintExample = { loaded: load(select.value) };
requestAnimationFrame(frame);
