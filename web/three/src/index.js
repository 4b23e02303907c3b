// glint's glint layer for three.js (web/three/README.md).
export { loadGlintDictionary, parseGlintDictionary } from './dictionary.js';
export { applyGlintEnvironment, loadGlintEnvironment } from './environment.js';
export { GlintLayer, MeshGlintMaterial } from './material.js';
export { EXTENSION_NAME, GLTFMaterialsGlintExtension, glintLayerFromExtension } from './plugin.js';
