// EXT_materials_glint for three.js's GLTFLoader (extensions/EXT_materials_glint/README.md): a
// GLTFLoaderPlugin that gives each material carrying the extension a glint layer.
//
//   const dictionary = await loadGlintDictionary('dictionary.gdict');
//   loader.register((parser) => new GLTFMaterialsGlintExtension(parser, { dictionary }));
//
// The loader makes the core material as it would without the extension (MeshPhysicalMaterial, with
// whatever KHR_materials_* it reads: getMaterialType asks for the physical one), and the plugin's
// loadMaterial hook turns it into a MeshGlintMaterial with the layer's parameters and textures.
// loadMaterial rather than getMaterialType + extendMaterialParams because GLTFLoader asks its own
// extensions for the material type first: a material with KHR_materials_clearcoat would get a
// plain MeshPhysicalMaterial.
import { MeshPhysicalMaterial } from 'three';
import { GlintLayer, MeshGlintMaterial } from './material.js';
import { EXTENSION_FIELD, EXTENSION_FIELDS } from './fields.js';

export const EXTENSION_NAME = 'EXT_materials_glint';

// The extension's properties by kind, from its schema (src/fields.js): [name in the file, layer
// field, lower bound, upper bound, exclusive lower bound] for numbers and pairs, [name, field] for
// booleans and textures, [name, field, allowed names] for choices.
const ofKind = (kind) => EXTENSION_FIELDS.filter((f) => f.kind === kind);
const NUMBERS = ofKind('number').map((f) => [f.name, f.field, f.minimum, f.maximum, f.exclusiveMinimum]);
const PAIRS = ofKind('pair').map((f) => [f.name, f.field, f.minimum, f.maximum]);
const BOOLEANS = ofKind('boolean').map((f) => [f.name, f.field]);
const NAMES = ofKind('choice').map((f) => [f.name, f.field, f.choices]);
const TEXTURES = ofKind('texture').map((f) => [f.name, f.field]);
const SEED = EXTENSION_FIELD.patternSeed;
const KNOWN = new Set(['extensions', 'extras', ...EXTENSION_FIELDS.map((f) => f.name)]);

// The layer of one material's extension object, without its textures. A value outside the
// extension's range is refused, not clamped (the README's rule), with an Error naming the
// material and the property.
export function glintLayerFromExtension(extension, coreRoughness, where) {
  const fail = (problem) => {
    throw new Error(`${where}: ${EXTENSION_NAME}.${problem}`);
  };
  if (typeof extension !== 'object' || extension === null || Array.isArray(extension)) {
    throw new Error(`${where}: ${EXTENSION_NAME} must be an object`);
  }
  for (const key of Object.keys(extension)) {
    if (!KNOWN.has(key)) fail(`${key} is not a property of the extension`);
  }
  const layer = new GlintLayer();
  const inRange = (value, low, high, exclusiveLow) =>
    typeof value === 'number' && Number.isFinite(value) && (exclusiveLow ? value > low : value >= low) && value <= high;
  for (const [name, field, low, high, exclusive] of NUMBERS) {
    if (extension[name] === undefined) continue;
    const value = extension[name];
    const range = `${exclusive ? '(' : '['}${low}, ${high}]`;
    if (!inRange(value, low, high, exclusive)) fail(`${name} must be a number in ${range}, got ${JSON.stringify(value)}`);
    // The shader holds 32-bit floats: a value no float holds but 0 (1e-46) would be 0, outside an
    // exclusive minimum of 0, as glint's loader refuses it. Compared with the bounds as floats too,
    // as glint's loader compares them: 0.99 is a float a little above 0.99, and rho's maximum.
    if (!inRange(Math.fround(value), Math.fround(low), Math.fround(high), exclusive)) {
      fail(`${name} ${JSON.stringify(value)} is too small for a 32-bit float and would be 0: ${name} must be in ${range}`);
    }
    layer[field] = value;
  }
  for (const [name, field, low, high] of PAIRS) {
    if (extension[name] === undefined) continue;
    const value = extension[name];
    if (!Array.isArray(value) || value.length !== 2 || !value.every((v) => inRange(v, low, high, false))) {
      fail(`${name} must be two numbers in [${low}, ${high}], got ${JSON.stringify(value)}`);
    }
    layer[field].set(value[0], value[1]);
  }
  if (extension.alpha === undefined) layer.alpha.setScalar(Math.max(coreRoughness * coreRoughness, 0.01));
  for (const [name, field] of BOOLEANS) {
    if (extension[name] === undefined) continue;
    const value = extension[name];
    // true and false; 0 and 1 as tools that keep custom properties write them back (the README).
    if (![true, false, 0, 1].includes(value)) fail(`${name} must be true or false, got ${JSON.stringify(value)}`);
    layer[field] = Boolean(value);
  }
  for (const [name, field, allowed] of NAMES) {
    if (extension[name] === undefined) continue;
    if (!allowed.includes(extension[name])) fail(`${name} must be ${allowed.map((a) => `"${a}"`).join(' or ')}, got ${JSON.stringify(extension[name])}`);
    layer[field] = extension[name];
  }
  if (extension.patternSeed !== undefined) {
    const seed = extension.patternSeed;
    if (!Number.isInteger(seed) || seed < SEED.minimum || seed > SEED.maximum) {
      fail(`patternSeed must be an integer in [${SEED.minimum}, ${SEED.maximum}], got ${JSON.stringify(seed)}`);
    }
    layer.patternSeed = seed;
  }
  return layer;
}

// The glTF texture index of one of the extension's textureInfo objects ({"index": 2}, with
// texCoord, extensions and extras allowed), refused in one line naming the material and the
// property where it is not one, as glint's own loader refuses it. The glint textures are mapped
// with TEXCOORD_0 and without KHR_texture_transform (the extension's rules): either, asked for,
// is a warning.
export function glintTextureIndex(textureInfo, name, textureCount, where) {
  const fail = (problem) => {
    throw new Error(`${where}: ${EXTENSION_NAME}.${name}${problem}`);
  };
  if (typeof textureInfo !== 'object' || textureInfo === null || Array.isArray(textureInfo) || textureInfo.index === undefined) {
    fail(` must be a textureInfo object with an index, got ${JSON.stringify(textureInfo)}`);
  }
  for (const key of Object.keys(textureInfo)) {
    if (!['index', 'texCoord', 'extensions', 'extras'].includes(key)) fail(`: unknown textureInfo member '${key}' (known: index, texCoord, extensions, extras)`);
  }
  if (textureCount === 0) fail(': the file has no textures');
  const index = textureInfo.index;
  if (!Number.isInteger(index) || index < 0 || index >= textureCount) fail(`.index must be an integer in [0, ${textureCount - 1}], got ${JSON.stringify(index)}`);
  for (const key of ['extensions', 'extras']) {
    const member = textureInfo[key];
    if (member !== undefined && (typeof member !== 'object' || member === null || Array.isArray(member))) {
      fail(`.${key} must be an object, got ${JSON.stringify(member)}`);
    }
  }
  const texCoord = textureInfo.texCoord;
  if (texCoord !== undefined && !(Number.isInteger(texCoord) && texCoord >= 0)) fail(`.texCoord must be a non-negative integer, got ${JSON.stringify(texCoord)}`);
  if (texCoord > 0) console.warn(`${where}: ${EXTENSION_NAME}.${name}: textures on a texCoord other than 0 are mapped with TEXCOORD_0`);
  if (textureInfo.extensions && textureInfo.extensions.KHR_texture_transform !== undefined) {
    console.warn(`${where}: ${EXTENSION_NAME}.${name}: KHR_texture_transform is not applied to glint textures, which are mapped with TEXCOORD_0`);
  }
  return index;
}

export class GLTFMaterialsGlintExtension {
  // options.dictionary: the dictionary (loadGlintDictionary) or a promise of it; every glint
  // material draws with it. options.smooth: draw each layer's smooth target instead of its glints.
  constructor(parser, options = {}) {
    this.parser = parser;
    this.name = EXTENSION_NAME;
    this.dictionary = options.dictionary;
    this.smooth = Boolean(options.smooth);
    if (!this.dictionary) throw new Error(`${EXTENSION_NAME}: the plugin needs a dictionary (options.dictionary)`);
  }

  extensionOf(materialIndex) {
    const definition = this.parser.json.materials[materialIndex];
    return definition.extensions && definition.extensions[EXTENSION_NAME] !== undefined ? definition.extensions[EXTENSION_NAME] : null;
  }

  getMaterialType(materialIndex) {
    return this.extensionOf(materialIndex) !== null ? MeshPhysicalMaterial : null;
  }

  loadMaterial(materialIndex) {
    const extension = this.extensionOf(materialIndex);
    if (extension === null) return null;
    const parser = this.parser;
    const definition = parser.json.materials[materialIndex];
    const where = `material ${materialIndex}${definition.name ? ` '${definition.name}'` : ''}`;
    const metallicRoughness = definition.pbrMetallicRoughness || {};
    const coreRoughness = metallicRoughness.roughnessFactor !== undefined ? metallicRoughness.roughnessFactor : 1;
    let layer;
    const textureIndices = [];
    try {
      layer = glintLayerFromExtension(extension, coreRoughness, where);
      const textureCount = Array.isArray(parser.json.textures) ? parser.json.textures.length : 0;
      for (const [name, field] of TEXTURES) {
        if (extension[name] !== undefined) textureIndices.push([name, field, glintTextureIndex(extension[name], name, textureCount, where)]);
      }
    } catch (error) {
      return Promise.reject(error);
    }
    // The glint textures are data: their R channel as stored (no colour space), sampled at
    // TEXCOORD_0 without KHR_texture_transform (the extension's rules): GLTFLoader is given the
    // index alone, so that it applies neither.
    const textures = {};
    const pending = textureIndices.map(([, field, index]) => parser.assignTexture(textures, field, { index }));
    return Promise.all([parser.loadMaterial(materialIndex), Promise.resolve(this.dictionary), ...pending]).then(([core, dictionary]) => {
      // GLTFLoader warns and goes on without a texture it cannot load; a glint layer drawn without
      // its texture would be another material, so the load fails, as glint's own loader does.
      for (const [name, field, index] of textureIndices) {
        if (!textures[field]) throw new Error(`${where}: ${EXTENSION_NAME}.${name}: texture ${index} could not be loaded`);
      }
      for (const [, field] of TEXTURES) layer[field] = textures[field] || null;
      if (layer.lod === 'tree' && !dictionary.hasTreeLevels) {
        // The tree construction reads tree levels, which a dictionary file holds only when written
        // with `glint dict --tree-levels`: the extension lets a renderer without a construction
        // draw it as the paper's.
        console.warn(`${where}: ${EXTENSION_NAME}.lod "tree" is drawn as "paper" (the glint dictionary has no tree levels: glint dict --tree-levels writes them)`);
        layer.lod = 'paper';
      }
      const material = new MeshGlintMaterial().copy(core);
      material.glint = layer;
      material.glintDictionary = dictionary;
      material.glintSmooth = this.smooth;
      parser.associations.set(material, parser.associations.get(core));
      return material;
    });
  }
}
