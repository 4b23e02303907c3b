// The glint dictionary (docs/dictionary.md) as a three.js DataTexture, read from a `.gdict` file
// that `glint dict` writes: the kernel's dictionary hook (src/glint/kernel/prelude.h) reads it with
// texelFetch. The file's binary16 texels go to the GPU as they are (no conversion), each texel k of
// a marginal paired with texel k + 1 (0 past the last) in an RG16F texel, so that one fetch serves
// the kernel's linear interpolation, as glint's own renderers lay it out
// (shaders/glint_dictionary_gl.glsl); the pairs run row after row through a texture
// DICTIONARY_TEXTURE_WIDTH texels wide (WebGL2 has no buffer textures).
import { DataTexture, DataUtils, FloatType, HalfFloatType, NearestFilter, RGBAFormat, RGFormat } from 'three';

export const DICTIONARY_TEXTURE_WIDTH = 2048;  // the hook's GLSL divides by it with a shift (11 bits)

const HEADER_BYTES = 64;
const MAGIC = 'GLINTDIC';

// CRC-32 (IEEE 802.3, the zlib checksum the file carries).
let crcTable = null;
function crc32(bytes) {
  if (!crcTable) {
    crcTable = new Uint32Array(256);
    for (let n = 0; n < 256; ++n) {
      let c = n;
      for (let k = 0; k < 8; ++k) c = c & 1 ? 0xedb88320 ^ (c >>> 1) : c >>> 1;
      crcTable[n] = c >>> 0;
    }
  }
  let crc = 0xffffffff;
  for (let i = 0; i < bytes.length; ++i) crc = crcTable[(crc ^ bytes[i]) & 0xff] ^ (crc >>> 8);
  return (crc ^ 0xffffffff) >>> 0;
}

// A binary16 value's sign, exponent and mantissa: finite and non-negative?
function halfIsFiniteNonNegative(bits) {
  return (bits & 0x8000) === 0 ? (bits & 0x7c00) !== 0x7c00 : (bits & 0x7fff) === 0;  // -0 is allowed
}

// The dictionary of a .gdict file's bytes. `name` says which file in the error messages: each
// problem is one Error whose message names the file and the problem, checked in the file format's
// order (docs/dictionary.md, "File format"). Stored tree levels (version 2) are taken as they are:
// glint's own loader checks that they are level 0's means, this one only their checksum and values.
export function parseGlintDictionary(buffer, name = 'dictionary') {
  const bytes = new Uint8Array(buffer);
  const fail = (problem) => {
    throw new Error(`${name}: ${problem}`);
  };
  if (bytes.length < HEADER_BYTES) fail(`too short for a glint dictionary (${bytes.length} bytes)`);
  const view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
  if (String.fromCharCode(...bytes.subarray(0, 8)) !== MAGIC) fail('not a glint dictionary (bad magic)');
  const version = view.getUint32(8, true);
  if (version !== 1 && version !== 2) fail(`unsupported format version ${version}`);
  if (view.getUint32(12, true) !== HEADER_BYTES) fail('corrupt header (header size)');
  if (crc32(bytes.subarray(0, 60)) !== view.getUint32(60, true)) fail('corrupt header (checksum mismatch)');
  const numLevels = view.getUint32(16, true);
  const numDistributions = view.getUint32(20, true);
  const texelsPerDistribution = view.getUint32(24, true);
  const alpha = view.getFloat32(28, true);
  if (!(numLevels >= 1 && numLevels <= 16)) fail(`unsupported number of levels ${numLevels}`);
  if (!(numDistributions >= 1 && numDistributions <= 4096)) fail(`unsupported number of distributions ${numDistributions}`);
  if (!(texelsPerDistribution >= 2 && texelsPerDistribution <= 4096)) fail(`unsupported texels per distribution ${texelsPerDistribution}`);
  if (!(alpha >= 0.01 && alpha <= 2)) fail(`unsupported dictionary roughness ${alpha}`);
  if (view.getUint32(48, true) !== 1) fail('unsupported texel format (binary16 expected)');
  // Version 2 holds the tree levels after the L levels (`glint dict --tree-levels`): the kernel's
  // tables L .. 2L - 2, which the tree LOD construction reads (glintTreeTableLevel).
  const hasTreeLevels = version === 2;
  const numTables = hasTreeLevels ? 2 * numLevels - 1 : numLevels;
  const count = numTables * numDistributions * texelsPerDistribution;
  const payloadBytes = view.getUint32(52, true);
  if (payloadBytes !== 2 * count || bytes.length !== HEADER_BYTES + payloadBytes) fail('corrupt payload (size)');
  const payload = bytes.subarray(HEADER_BYTES);
  if (crc32(payload) !== view.getUint32(56, true)) fail('corrupt payload (checksum mismatch)');

  const height = Math.ceil(count / DICTIONARY_TEXTURE_WIDTH);
  const pairs = new Uint16Array(2 * DICTIONARY_TEXTURE_WIDTH * height);
  for (let i = 0; i < count; ++i) {
    const texel = view.getUint16(HEADER_BYTES + 2 * i, true);
    if (!halfIsFiniteNonNegative(texel)) fail(`texel ${i} is negative or not finite`);
    pairs[2 * i] = texel;
    if (i % texelsPerDistribution !== 0) pairs[2 * i - 1] = texel;  // texel k + 1 of the previous pair
  }
  const texture = new DataTexture(pairs, DICTIONARY_TEXTURE_WIDTH, height, RGFormat, HalfFloatType);
  texture.minFilter = NearestFilter;
  texture.magFilter = NearestFilter;
  texture.generateMipmaps = false;
  texture.flipY = false;
  texture.needsUpdate = true;
  return { numLevels, numDistributions, texelsPerDistribution, alpha, hasTreeLevels, texture };
}

// The dictionary at `url` (fetched): a promise of { numLevels, numDistributions,
// texelsPerDistribution, alpha, hasTreeLevels, texture }. Its failure is reported where it is
// used (the load of a file with glint materials, or an await), not also as an unhandled
// rejection: a page that loads no glint material needs no dictionary.
export function loadGlintDictionary(url) {
  const dictionary = (async () => {
    const response = await fetch(url);
    if (!response.ok) throw new Error(`${url}: cannot fetch the glint dictionary (HTTP ${response.status})`);
    return parseGlintDictionary(await response.arrayBuffer(), String(url));
  })();
  dictionary.catch(() => {});
  return dictionary;
}

// The cumulative tables that glints under area lights integrate the marginals with
// (docs/dictionary.md, "Cumulative tables"), built on first use, as glint's own renderers build them
// (glint::Dictionary::buildCumulativeTables): per marginal and texel k, (C[k], M[k], p[k], p[k+1]),
// the integrals of the linearly interpolated marginal and of the slope times it from slope 0 to
// texel k's slope, summed in double from the binary16 texels and kept as 32-bit floats, then the
// texel pair; an RGBA32F texture DICTIONARY_TEXTURE_WIDTH texels wide, laid out like the pairs.
// Programs lit by a RectAreaLight read it (hook glintDictionaryCumulativeTexel, src/shader.js).
export function glintCumulativeTexture(dictionary) {
  if (dictionary.cumulativeTexture) return dictionary.cumulativeTexture;
  const pairs = dictionary.texture.image.data;  // binary16 (p[k], p[k + 1]) per texel
  const count = pairs.length / 2;
  const texels = dictionary.texelsPerDistribution;
  // The kernel's glintDictionaryDomain (4 sigma_d = 2 sqrt 2 alpha_d), in 32-bit float as it computes it.
  const domain = Math.fround(Math.fround(2.82842712) * Math.fround(dictionary.alpha));
  const spacing = domain / texels;
  const table = new Float32Array(4 * count);
  for (let row = 0; row + texels <= count; row += texels) {
    let mass = 0;
    let moment = 0;
    for (let k = 0; k < texels; ++k) {
      const i = row + k;
      const a = DataUtils.fromHalfFloat(pairs[2 * i]);
      const next = DataUtils.fromHalfFloat(pairs[2 * i + 1]);  // 0 past the marginal's last texel
      table[4 * i] = mass;
      table[4 * i + 1] = moment;
      table[4 * i + 2] = a;
      table[4 * i + 3] = next;
      const rise = next - a;
      mass += spacing * (a + 0.5 * rise);
      moment += spacing * spacing * (k * (a + 0.5 * rise) + 0.5 * a + rise / 3);
    }
  }
  const texture = new DataTexture(table, DICTIONARY_TEXTURE_WIDTH, count / DICTIONARY_TEXTURE_WIDTH, RGBAFormat, FloatType);
  texture.minFilter = NearestFilter;
  texture.magFilter = NearestFilter;
  texture.generateMipmaps = false;
  texture.flipY = false;
  texture.needsUpdate = true;
  dictionary.cumulativeTexture = texture;
  return texture;
}
