// MeshGlintMaterial: three.js's MeshPhysicalMaterial whose specular lobe, for point, spot,
// directional and rectangle area lights and an environment's regions (src/environment.js), is
// glint's procedural glint layer (Chermain et al. 2020), the layer's
// parameters those of EXT_materials_glint (extensions/EXT_materials_glint/README.md), evaluated by
// glint's kernel (src/shader.js). Everything else is MeshPhysicalMaterial's own.
import { DataTexture, MeshPhysicalMaterial, MeshStandardMaterial, RGBAFormat, UnsignedByteType, Vector2 } from 'three';
import { glintCumulativeTexture } from './dictionary.js';
import { EXTENSION_FIELD } from './fields.js';
import { LAYER_NAME_CHOICES, addGlintLayerToShader } from './shader.js';

// A glint layer's parameters, named as the kernel's GlintMaterial (kernel/glint_material.h) is:
// this object is the value of the shader's `uniform GlintMaterial glintMaterial`. Defaults are
// the extension's, from its schema (src/fields.js); alpha's is the core roughness squared
// (MeshGlintMaterial sets it), here that of three's default roughness 0.5.
const defaultOf = (name) => EXTENSION_FIELD[name].default;
export class GlintLayer {
  constructor() {
    this.alpha = new Vector2(0.25, 0.25);  // the target's roughness along the tangent and the bitangent
    this.rho = defaultOf('rho');           // slope correlation
    this.logDensity = defaultOf('logDensity');  // ln(microfacets per unit glint-uv area)
    this.relativeArea = defaultOf('relativeArea');  // the share of cells with microfacets
    this.densityRandomisation = defaultOf('densityRandomization');
    this.maxAnisotropy = defaultOf('maxAnisotropy');
    this.patternSeed = defaultOf('patternSeed');  // an unsigned 32-bit integer
    this.logDensityRange = new Vector2(...defaultOf('logDensityRange'));  // what logDensityTexture's 0 and 1 map to
    this.uvScale = defaultOf('uvScale');   // glint uv = TEXCOORD_0 * uvScale
    this.ndf = defaultOf('ndf');           // 'ggx' or 'beckmann'
    this.masking = defaultOf('masking');   // 'smith' or 'v-cavity'
    this.colouredCells = defaultOf('randomColors');  // EXT_materials_glint's randomColors
    this.multipleScattering = defaultOf('multipleScattering');
    this.lod = defaultOf('lod');           // 'paper', 'consistent' (docs/method.md 2.7) or 'tree' (2.8: needs a
                                           // dictionary with tree levels, `glint dict --tree-levels`)
    this.roughnessTexture = null;          // three Textures, their R channel read as data
    this.logDensityTexture = null;
    this.relativeAreaTexture = null;
  }

  // The uniform struct's fields that are not parameters: flags as the kernel's uints. ndf,
  // masking, colouredCells, multipleScattering and lod are compiled in (the program's variant).
  get hasLogDensityTexture() {
    return this.logDensityTexture ? 1 : 0;
  }

  get enabled() {
    return 1;
  }

  // From another GlintLayer or from an object of some of its fields; a key that is not a field
  // (a misspelling, or the extension's spelling of one: randomColors for colouredCells) is
  // refused in one line rather than left unread. alpha and logDensityRange take a Vector2 or a
  // number pair.
  copy(source) {
    for (const key of Object.keys(source)) {
      if (!Object.prototype.hasOwnProperty.call(this, key)) {
        throw new Error(`glint-three: '${key}' is not a GlintLayer field (fields: ${Object.keys(this).join(', ')})`);
      }
      const value = source[key];
      if (this[key] && this[key].isVector2) {
        if (value && value.isVector2) this[key] = value.clone();
        else if (Array.isArray(value) && value.length === 2) this[key] = new Vector2(value[0], value[1]);
        else throw new Error(`glint-three: GlintLayer.${key} must be a Vector2 or two numbers, got ${JSON.stringify(value)}`);
      } else {
        this[key] = value;
      }
    }
    return this;
  }

  clone() {
    return new GlintLayer().copy(this);
  }
}

// The kernel's struct has uints where the layer has booleans or names; the shader overrides those
// from its compile-time variant, but every field of a struct uniform needs a value.
function structValue(layer) {
  return {
    get alpha() { return layer.alpha; },
    get rho() { return layer.rho; },
    get logDensity() { return layer.logDensity; },
    get relativeArea() { return layer.relativeArea; },
    get densityRandomisation() { return layer.densityRandomisation; },
    get maxAnisotropy() { return layer.maxAnisotropy; },
    get patternSeed() { return layer.patternSeed >>> 0; },
    get logDensityRange() { return layer.logDensityRange; },
    get uvScale() { return layer.uvScale; },
    get hasLogDensityTexture() { return layer.hasLogDensityTexture; },
    ndf: 0,
    masking: 0,
    colouredCells: 0,
    multipleScattering: 0,
    get enabled() { return layer.enabled; },
    lod: 0,
    padding1: 0,
    padding2: 0,
  };
}

// A glint texture's stand-in where the layer has none: R = 1 (the factor of an absent texture).
const WHITE = new DataTexture(new Uint8Array([255, 255, 255, 255]), 1, 1, RGBAFormat, UnsignedByteType);
WHITE.needsUpdate = true;

export class MeshGlintMaterial extends MeshPhysicalMaterial {
  // parameters: MeshPhysicalMaterial's, and
  //   glint: a GlintLayer (or an object of its fields),
  //   glintDictionary: the dictionary (loadGlintDictionary, src/dictionary.js), needed to draw,
  //   glintSmooth: true draws the layer's smooth target (the lobe the glints converge to) instead
  //     of the glints.
  constructor(parameters = {}) {
    super();
    this.isMeshGlintMaterial = true;  // its type stays 'MeshPhysicalMaterial': three picks the program by type
    this.glint = new GlintLayer();
    this.glintDictionary = null;
    this.glintSmooth = false;
    this.glintEnvironment = null;  // the scene's glint environment as last drawn (applyGlintEnvironment)
    this._glintResidual = null;  // the residual map this material took as its envMap
    this.defines.USE_UV = '';  // vUv, the glint uv's source, in every program
    const { glint, ...rest } = parameters;
    this.setValues(rest);
    if (glint instanceof GlintLayer) {
      this.glint = glint;
    } else {
      // alpha's default is the core roughness squared (the extension's), unless given.
      this.glint.alpha.setScalar(Math.max(this.roughness * this.roughness, 0.01));
      if (glint) this.glint.copy(glint);
    }
    const material = this;
    this.glintUniforms = {
      glintMaterial: { get value() { return material.glintStruct; } },
      glintDictionaryTexels: { get value() { return material.glintDictionary ? material.glintDictionary.texture : null; } },
      glintDictionaryShape: {
        get value() {
          const d = material.glintDictionary;
          return d ? [d.numLevels, d.numDistributions, d.texelsPerDistribution] : [1, 1, 2];
        },
      },
      glintDictionaryAlpha: { get value() { return material.glintDictionary ? material.glintDictionary.alpha : 0.5; } },
      // Read only by programs lit by RectAreaLights or regions, which build the tables on first use.
      glintCumulativeTexels: { get value() { return material.glintDictionary ? glintCumulativeTexture(material.glintDictionary) : null; } },
      glintRegionCorner: { get value() { return material.glintEnvironment.corners; } },
      glintRegionRadiance: { get value() { return material.glintEnvironment.radiances; } },
      glintRoughnessMap: { get value() { return material.glint.roughnessTexture || WHITE; } },
      glintLogDensityMap: { get value() { return material.glint.logDensityTexture || WHITE; } },
      glintRelativeAreaMap: { get value() { return material.glint.relativeAreaTexture || WHITE; } },
    };
  }

  get glintStruct() {
    if (!this._glintStruct || this._glintStructLayer !== this.glint) {
      this._glintStruct = structValue(this.glint);
      this._glintStructLayer = this.glint;
    }
    return this._glintStruct;
  }

  get glintVariant() {
    return {
      ndf: this.glint.ndf,
      masking: this.glint.masking,
      colouredCells: Boolean(this.glint.colouredCells),
      multipleScattering: Boolean(this.glint.multipleScattering),
      lod: this.glint.lod,
      smooth: Boolean(this.glintSmooth),
      environmentRegions: this.glintEnvironment ? this.glintEnvironment.radiances.length : 0,
    };
  }

  onBeforeCompile(shader) {
    if (!this.glintDictionary) {
      throw new Error(`glint-three: material '${this.name}' has no glint dictionary (set material.glintDictionary)`);
    }
    for (const [field, names] of Object.entries(LAYER_NAME_CHOICES)) {
      if (!names.includes(this.glint[field])) {
        throw new Error(`glint-three: material '${this.name}': ${field} must be ${names.map((n) => `'${n}'`).join(', ')}, got ${JSON.stringify(this.glint[field])}`);
      }
    }
    if (this.glint.lod === 'tree' && !this.glintDictionary.hasTreeLevels) {
      throw new Error(`glint-three: material '${this.name}' asks for lod 'tree', whose tree levels its dictionary lacks (write it with glint dict --tree-levels)`);
    }
    Object.assign(shader.uniforms, this.glintUniforms);
    addGlintLayerToShader(shader, this.glintVariant);
  }

  customProgramCacheKey() {
    const v = this.glintVariant;
    return `glint:${v.ndf}:${v.masking}:${v.colouredCells}:${v.multipleScattering}:${v.lod}:${v.smooth}:${v.environmentRegions}`;
  }

  // three chooses a material's program again only when its version changes (needsUpdate): a
  // compiled-in field changed since the last frame (ndf, masking, colouredCells,
  // multipleScattering, lod, glintSmooth, the scene's environment regions) asks for that here,
  // before three picks the program.
  onBeforeRender(renderer, scene) {
    const environment = (scene && scene.userData && scene.userData.glintEnvironment) || null;
    this.glintEnvironment = environment;
    // The residual map, which lacks the regions' light, as this material's envMap (one it was given
    // stays): three compiles envMap programs apart, so a change asks for the program again.
    const residual = environment ? environment.residual : null;
    const ownEnvMap = this.envMap !== null && this.envMap !== this._glintResidual;  // one it was given stays
    if (!ownEnvMap) {
      if (this.envMap !== residual) {
        this.envMap = residual;
        this.needsUpdate = true;
      }
      this.envMapIntensity = environment ? environment.intensity : 1;
    }
    this._glintResidual = residual;
    const key = this.customProgramCacheKey();
    if (this._glintProgramKey !== undefined && this._glintProgramKey !== key) this.needsUpdate = true;
    this._glintProgramKey = key;
  }

  // From another MeshGlintMaterial, or from a MeshPhysicalMaterial or MeshStandardMaterial (the
  // core material a glTF loader made), whose layer then stays this one's.
  copy(source) {
    if (source.isMeshPhysicalMaterial) super.copy(source);
    else MeshStandardMaterial.prototype.copy.call(this, source);
    this.defines = { ...this.defines, STANDARD: '', PHYSICAL: '', USE_UV: '' };
    if (source.isMeshGlintMaterial) {
      this.glint = source.glint.clone();
      this.glintDictionary = source.glintDictionary;
      this.glintSmooth = source.glintSmooth;
    }
    return this;
  }
}
