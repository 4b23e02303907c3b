// Bad input to the package, in node (ctest -R ThreeWeb): a damaged dictionary file and out-of-range
// extension values must each be refused with one line that names the file or the material and the
// problem. The dictionary is one `glint dict` writes, then damaged byte by byte.
//   node test/bad-input.mjs --glint PATH
// Exits 77 with one line when the npm packages are missing (ctest's SKIP_RETURN_CODE).
import { execFileSync } from 'node:child_process';
import { crc32 } from 'node:zlib';
import { existsSync, mkdtempSync, readFileSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

const packageRoot = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..');
if (!existsSync(path.join(packageRoot, 'node_modules', 'three'))) {
  console.log('three.js test skipped: three is not installed in web/three (scripts/deps runs npm ci there)');
  process.exit(77);
}
const { build, findGlint } = await import('../tools/build.mjs');
const at = process.argv.indexOf('--glint');
const glint = findGlint(at > 0 ? process.argv[at + 1] : undefined);
build(glint);  // the plugin's module imports the material's, which imports the generated kernel
const { parseGlintDictionary } = await import('../src/dictionary.js');
const { GLTFMaterialsGlintExtension, glintLayerFromExtension } = await import('../src/plugin.js');
const { MeshGlintMaterial } = await import('../src/material.js');
const { MeshPhysicalMaterial } = await import('three');

let failures = 0;
function expectRefused(what, action, expected) {
  let message = null;
  try {
    action();
  } catch (error) {
    message = error.message;
  }
  const ok = message !== null && message.includes(expected) && !message.includes('\n');
  if (!ok) ++failures;
  console.log(`${ok ? 'ok' : 'FAILED'}: ${what}: ${message === null ? 'accepted' : message}`);
}

const folder = mkdtempSync(path.join(tmpdir(), 'glint-three-bad-'));
try {
  const file = path.join(folder, 'd.gdict');
  execFileSync(glint, ['dict', '-o', file, '--levels', '4', '--distributions', '8', '--texels', '16'], { stdio: 'ignore' });
  const good = readFileSync(file);
  const dictionary = parseGlintDictionary(good, 'd.gdict');
  const shapeOk = dictionary.numLevels === 4 && dictionary.numDistributions === 8 && dictionary.texelsPerDistribution === 16;
  if (!shapeOk) ++failures;
  console.log(`${shapeOk ? 'ok' : 'FAILED'}: a good file reads as 4 levels, 8 distributions, 16 texels`);
  // The texel pairs: texel k and k + 1 of a marginal, 0 past its last texel.
  const pairs = dictionary.texture.image.data;
  const half = (i) => good.readUint16LE(64 + 2 * i);
  const pairsOk = pairs[0] === half(0) && pairs[1] === half(1) && pairs[2 * 15] === half(15) && pairs[2 * 15 + 1] === 0 &&
                  pairs[2 * 16] === half(16);
  if (!pairsOk) ++failures;
  console.log(`${pairsOk ? 'ok' : 'FAILED'}: texel pairs (k, k + 1), 0 past a marginal's last texel`);

  const damaged = (change) => {
    const bytes = Buffer.from(good);
    change(bytes);
    return bytes;
  };
  expectRefused('a truncated file', () => parseGlintDictionary(good.subarray(0, 40), 'd.gdict'), 'd.gdict: too short');
  expectRefused('another file', () => parseGlintDictionary(damaged((b) => b.write('NOTADICT', 0)), 'd.gdict'), 'd.gdict: not a glint dictionary');
  expectRefused('a damaged header', () => parseGlintDictionary(damaged((b) => { b[20] ^= 1; }), 'd.gdict'), 'd.gdict: corrupt header (checksum mismatch)');
  expectRefused('a damaged payload', () => parseGlintDictionary(damaged((b) => { b[100] ^= 1; }), 'd.gdict'), 'd.gdict: corrupt payload (checksum mismatch)');
  expectRefused('a payload cut short', () => parseGlintDictionary(good.subarray(0, good.length - 2), 'd.gdict'), 'd.gdict: corrupt payload (size)');

  const where = "material 0 'car paint'";
  const layer = (extension) => () => glintLayerFromExtension(extension, 0.5, where);
  expectRefused('logDensity 120', layer({ logDensity: 120 }), `${where}: EXT_materials_glint.logDensity must be a number in [0, 100], got 120`);
  expectRefused('relativeArea 0', layer({ relativeArea: 0 }), 'EXT_materials_glint.relativeArea must be a number in (0, 1]');
  expectRefused('uvScale 1e-50', layer({ uvScale: 1e-50 }), 'EXT_materials_glint.uvScale must be a number in [1.401298464324817e-45, ');
  expectRefused('one alpha', layer({ alpha: [0.3] }), 'EXT_materials_glint.alpha must be two numbers');
  expectRefused('randomColors "yes"', layer({ randomColors: 'yes' }), 'EXT_materials_glint.randomColors must be true or false');
  expectRefused('ndf "phong"', layer({ ndf: 'phong' }), 'EXT_materials_glint.ndf must be "ggx" or "beckmann"');
  expectRefused('a misspelt property', layer({ logDenisty: 14 }), 'EXT_materials_glint.logDenisty is not a property');
  expectRefused('patternSeed -1', layer({ patternSeed: -1 }), 'EXT_materials_glint.patternSeed must be an integer');
  // lod "tree": drawn with a dictionary that holds tree levels (`glint dict --tree-levels`, format
  // version 2); with one that does not, the plugin draws it as "paper" with one warning line naming
  // the material, and a MeshGlintMaterial asked for it directly refuses to compile.
  const treeFile = path.join(folder, 'tree.gdict');
  execFileSync(glint, ['dict', '--tree-levels', '-o', treeFile, '--levels', '4', '--distributions', '8', '--texels', '16'], { stdio: 'ignore' });
  const treeBytes = readFileSync(treeFile);
  const withTree = parseGlintDictionary(treeBytes, 'tree.gdict');
  // Tables 0..3 are the levels (the same bytes as the version-1 file's), 4..6 the tree levels.
  const treePairs = withTree.texture.image.data;
  const tableTexels = 8 * 16;
  const treeHalf = (i) => treeBytes.readUint16LE(64 + 2 * i);
  const treeShapeOk = withTree.hasTreeLevels === true && dictionary.hasTreeLevels === false && withTree.numLevels === 4 &&
                      treePairs.length >= 2 * 7 * tableTexels && treeHalf(100) === half(100) &&
                      treePairs[2 * 4 * tableTexels] === treeHalf(4 * tableTexels) &&
                      treePairs[2 * (7 * tableTexels - 1)] === treeHalf(7 * tableTexels - 1) && treePairs[2 * (7 * tableTexels - 1) + 1] === 0;
  if (!treeShapeOk) ++failures;
  console.log(`${treeShapeOk ? 'ok' : 'FAILED'}: a --tree-levels file reads with its 3 tree levels after the 4 levels, a plain one without`);
  // A version-2 header over a version-1 payload (the header's checksum remade): the size is wrong.
  const relabelled = Buffer.from(good);
  relabelled.writeUint32LE(2, 8);
  relabelled.writeUint32LE(crc32(relabelled.subarray(0, 60)), 60);
  expectRefused('a version-2 header over the levels alone', () => parseGlintDictionary(relabelled, 'd.gdict'), 'd.gdict: corrupt payload (size)');
  const treeLayer = glintLayerFromExtension({ lod: 'tree' }, 0.5, where);
  const readOk = treeLayer.lod === 'tree';
  if (!readOk) ++failures;
  console.log(`${readOk ? 'ok' : 'FAILED'}: lod "tree" reads as "tree"`);
  const loadTree = async (dictionaryForPlugin) => {
    const parser = {
      json: { materials: [{ name: 'car paint', extensions: { EXT_materials_glint: { lod: 'tree' } } }] },
      loadMaterial: async () => new MeshPhysicalMaterial(),
      assignTexture: async () => {},
      associations: new Map(),
    };
    return new GLTFMaterialsGlintExtension(parser, { dictionary: dictionaryForPlugin }).loadMaterial(0);
  };
  const warnings = [];
  const warn = console.warn;
  console.warn = (line) => warnings.push(String(line));
  let drawnWithTree = null;
  let drawnWithout = null;
  try {
    drawnWithTree = await loadTree(withTree);
    const warnedBefore = warnings.length;
    drawnWithout = await loadTree(dictionary);
    const fallbackOk = warnedBefore === 0 && drawnWithTree.glint.lod === 'tree' && drawnWithout.glint.lod === 'paper' &&
                       warnings.length === 1 && warnings[0].startsWith(`${where}: EXT_materials_glint.lod "tree" is drawn as "paper" (the glint dictionary has no tree levels`);
    if (!fallbackOk) ++failures;
    console.log(`${fallbackOk ? 'ok' : 'FAILED'}: the plugin draws lod "tree" with tree levels, as "paper" with one warning without (${warnings.join(' | ')})`);
  } finally {
    console.warn = warn;
  }
  const direct = new MeshGlintMaterial({ name: 'direct', glint: { lod: 'tree' }, glintDictionary: dictionary });
  const misnamed = new MeshGlintMaterial({ name: 'misnamed', glint: { lod: 'Tree' }, glintDictionary: withTree });
  expectRefused('a MeshGlintMaterial with lod "Tree"', () => misnamed.onBeforeCompile({ uniforms: {} }),
                "glint-three: material 'misnamed': lod must be 'paper', 'consistent', 'tree', got \"Tree\"");
  expectRefused('a MeshGlintMaterial with lod "tree" and no tree levels', () => direct.onBeforeCompile({ uniforms: {} }),
                "glint-three: material 'direct' asks for lod 'tree', whose tree levels its dictionary lacks (write it with glint dict --tree-levels)");
  expectRefused('lod "fast"', layer({ lod: 'fast' }), 'EXT_materials_glint.lod must be "paper" or "consistent" or "tree", got "fast"');
  const defaults = glintLayerFromExtension({ randomColors: 1 }, 0.5, where);
  const defaultsOk = defaults.alpha.x === 0.25 && defaults.alpha.y === 0.25 && defaults.colouredCells === true &&
                     defaults.logDensity === 27 && defaults.ndf === 'ggx' && defaults.masking === 'smith';
  if (!defaultsOk) ++failures;
  console.log(`${defaultsOk ? 'ok' : 'FAILED'}: defaults (alpha = roughness^2, logDensity 27, GGX, Smith) and randomColors 1 as true`);
} finally {
  rmSync(folder, { recursive: true, force: true });
}
console.log(failures ? `three.js bad-input test: ${failures} check(s) failed` : 'three.js bad-input test: passed');
process.exit(failures ? 1 : 0);
