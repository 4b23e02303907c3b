// Bad input to the package, in node (ctest -R ThreeWeb): a damaged dictionary file and out-of-range
// extension values must each be refused with one line that names the file or the material and the
// problem. The dictionary is one `glint dict` writes, then damaged byte by byte. So must a glint
// environment (`glint env-regions`) that is missing, not one, or without its residual map.
//   node test/bad-input.mjs --glint PATH
// Exits 77 with one line when the npm packages are missing (ctest's SKIP_RETURN_CODE).
import { execFileSync } from 'node:child_process';
import http from 'node:http';
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
const { loadGlintDictionary, parseGlintDictionary } = await import('../src/dictionary.js');
const { GLTFMaterialsGlintExtension, glintLayerFromExtension } = await import('../src/plugin.js');
const { MeshGlintMaterial } = await import('../src/material.js');
const { loadGlintEnvironment } = await import('../src/environment.js');
const { MeshPhysicalMaterial } = await import('three');

let failures = 0;
function check(ok, what) {
  if (!ok) ++failures;
  console.log(`${ok ? 'ok' : 'FAILED'}: ${what}`);
}
async function expectRejected(what, promise, expected) {
  let message = null;
  try {
    await promise;
  } catch (error) {
    message = error.message;
  }
  check(message !== null && message.includes(expected) && !message.includes('\n'), `${what}: ${message === null ? 'accepted' : message}`);
}
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
  expectRefused('relativeArea 1e-46', layer({ relativeArea: 1e-46 }),
                'EXT_materials_glint.relativeArea 1e-46 is too small for a 32-bit float and would be 0: relativeArea must be in (0, 1]');
  check(layer({ rho: -1e-46 })().rho === -1e-46, 'rho -1e-46 is read (0 is in its range)');
  expectRefused('randomColors "yes"', layer({ randomColors: 'yes' }), 'EXT_materials_glint.randomColors must be true or false');
  expectRefused('ndf "phong"', layer({ ndf: 'phong' }), 'EXT_materials_glint.ndf must be "beckmann" or "ggx"');
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
                     defaults.logDensity === 17 && defaults.ndf === 'ggx' && defaults.masking === 'smith';
  if (!defaultsOk) ++failures;
  console.log(`${defaultsOk ? 'ok' : 'FAILED'}: defaults (alpha = roughness^2, logDensity 17, GGX, Smith) and randomColors 1 as true`);

  // The extension's textureInfo objects, checked as glint's own loader checks them, before
  // GLTFLoader sees them; GLTFLoader is given the index alone (no texCoord, no transform).
  const assigned = [];
  const loadTextured = (extension, { textureCount = 3, loads = true } = {}) => {
    const parser = {
      json: {
        materials: [{ name: 'car paint', extensions: { EXT_materials_glint: extension } }],
        textures: textureCount ? new Array(textureCount).fill({ source: 0 }) : undefined,
      },
      loadMaterial: async () => new MeshPhysicalMaterial(),
      assignTexture: async (textures, field, textureInfo) => {
        assigned.push(textureInfo);
        if (loads) textures[field] = { isTexture: true, index: textureInfo.index };
      },
      associations: new Map(),
    };
    return new GLTFMaterialsGlintExtension(parser, { dictionary }).loadMaterial(0);
  };
  await expectRejected('a texture in a file without textures', loadTextured({ roughnessTexture: { index: 5 } }, { textureCount: 0 }),
                       `${where}: EXT_materials_glint.roughnessTexture: the file has no textures`);
  await expectRejected('a texture given as a number', loadTextured({ roughnessTexture: 0 }),
                       `${where}: EXT_materials_glint.roughnessTexture must be a textureInfo object with an index, got 0`);
  await expectRejected('a texture index past the last texture', loadTextured({ logDensityTexture: { index: 99 } }),
                       `${where}: EXT_materials_glint.logDensityTexture.index must be an integer in [0, 2], got 99`);
  await expectRejected('a texCoord "x"', loadTextured({ relativeAreaTexture: { index: 1, texCoord: 'x' } }),
                       'EXT_materials_glint.relativeAreaTexture.texCoord must be a non-negative integer, got "x"');
  await expectRejected('an unknown textureInfo member', loadTextured({ roughnessTexture: { index: 1, scale: 2 } }),
                       "EXT_materials_glint.roughnessTexture: unknown textureInfo member 'scale'");
  await expectRejected('textureInfo extensions that are no object', loadTextured({ roughnessTexture: { index: 1, extensions: 5 } }),
                       'EXT_materials_glint.roughnessTexture.extensions must be an object, got 5');
  await expectRejected('a texture GLTFLoader cannot load', loadTextured({ roughnessTexture: { index: 2 } }, { loads: false }),
                       `${where}: EXT_materials_glint.roughnessTexture: texture 2 could not be loaded`);
  assigned.length = 0;
  const textureWarnings = [];
  console.warn = (line) => textureWarnings.push(String(line));
  let textured = null;
  try {
    textured = await loadTextured({ roughnessTexture: { index: 2, texCoord: 1, extensions: { KHR_texture_transform: { scale: [2, 2] } } } });
  } finally {
    console.warn = warn;
  }
  check(textured.glint.roughnessTexture && textured.glint.roughnessTexture.index === 2 && assigned.length === 1 &&
        JSON.stringify(assigned[0]) === '{"index":2}' && textureWarnings.length === 2 &&
        textureWarnings[0].includes('texCoord other than 0') && textureWarnings[1].includes('KHR_texture_transform is not applied'),
        `a good texture reaches GLTFLoader as its index alone, texCoord and the transform each one warning (${textureWarnings.join(' | ')})`);

  // A MeshGlintMaterial made by hand: alpha's default is the core roughness squared whether or not
  // other layer fields are given; a key that is not a layer field, or an unknown ndf or masking,
  // is refused in one line.
  const byHand = new MeshGlintMaterial({ roughness: 0.7, glint: { logDensity: 13, uvScale: 4 } });
  const givenAlpha = new MeshGlintMaterial({ roughness: 0.7, glint: { alpha: [0.3, 0.2] } });
  check(Math.abs(byHand.glint.alpha.x - 0.49) < 1e-12 && Math.abs(byHand.glint.alpha.y - 0.49) < 1e-12 && byHand.glint.logDensity === 13 &&
        givenAlpha.glint.alpha.x === 0.3 && givenAlpha.glint.alpha.y === 0.2,
        `a layer given by hand takes alpha = roughness^2 unless given (${byHand.glint.alpha.x}; ${givenAlpha.glint.alpha.x}, ${givenAlpha.glint.alpha.y})`);
  expectRefused('a layer field spelt as the extension spells it', () => new MeshGlintMaterial({ glint: { randomColors: true } }),
                "glint-three: 'randomColors' is not a GlintLayer field (fields: alpha, rho, ");
  expectRefused('alpha as one number', () => new MeshGlintMaterial({ glint: { alpha: 0.3 } }), 'glint-three: GlintLayer.alpha must be a Vector2 or two numbers, got 0.3');
  const misspelt = new MeshGlintMaterial({ name: 'misspelt', glint: { ndf: 'beckman' }, glintDictionary: dictionary });
  expectRefused('a MeshGlintMaterial with ndf "beckman"', () => misspelt.onBeforeCompile({ uniforms: {} }),
                "glint-three: material 'misspelt': ndf must be 'ggx', 'beckmann', got \"beckman\"");

  // A compiled-in field changed after the first frame chooses another program at the next (three
  // looks at the program cache key only when the material's version changes); a number does not.
  const live = new MeshGlintMaterial({ glintDictionary: dictionary });
  live.onBeforeRender();
  const version = live.version;
  live.glint.logDensity = 20;
  live.onBeforeRender();
  const afterNumber = live.version;
  live.glint.ndf = 'beckmann';
  live.onBeforeRender();
  const afterNdf = live.version;
  live.onBeforeRender();
  check(afterNumber === version && afterNdf === version + 1 && live.version === afterNdf && live.customProgramCacheKey().startsWith('glint:beckmann:'),
        `changing ndf asks three for another program once, changing a number does not (versions ${version}, ${afterNumber}, ${afterNdf}, ${live.version})`);

  // The layer's fields as the repository's schema gives them (which glint's own test holds equal to
  // what glint writes from its table): GlintLayer's defaults are the schema's, and the plugin
  // accepts each range's ends and refuses a value just past them. A default or range written into
  // the package by hand, and changed in one place only, fails here.
  {
    const schemaFile = path.resolve(packageRoot, '..', '..', 'extensions', 'EXT_materials_glint', 'schema',
                                    'material.EXT_materials_glint.schema.json');
    const schema = JSON.parse(readFileSync(schemaFile, 'utf8'));
    const { GlintLayer } = await import('../src/material.js');
    const layer = new GlintLayer();
    const layerName = { densityRandomization: 'densityRandomisation', randomColors: 'colouredCells' };
    const valueOf = (v) => (v && v.isVector2 ? [v.x, v.y] : v);
    for (const [name, property] of Object.entries(schema.properties)) {
      if (property.default === undefined) continue;
      const field = layerName[name] || name;
      check(JSON.stringify(valueOf(layer[field])) === JSON.stringify(property.default),
            `GlintLayer.${field} defaults to the schema's ${name} default ${JSON.stringify(property.default)} (got ${JSON.stringify(valueOf(layer[field]))})`);
    }
    const accepts = (fields) => {
      try {
        glintLayerFromExtension(fields, 0.5, 'schema range');
        return true;
      } catch (error) {
        return false;
      }
    };
    for (const [name, property] of Object.entries(schema.properties)) {
      const range = property.type === 'array' ? property.items : property;
      if (range.maximum === undefined) continue;
      const low = range.exclusiveMinimum !== undefined ? range.exclusiveMinimum : range.minimum;
      const wrap = (v) => (property.type === 'array' ? { [name]: [v, v] } : { [name]: v });
      // Just past an end: a step of a millionth of the range's span (an integer's: 1), within a
      // double's precision at every end of the schema's ranges.
      const step = property.type === 'integer' ? 1 : Math.min(1e-6 * (range.maximum - low), 1e-6 * Math.max(Math.abs(range.maximum), 1e-30));
      const atEnds = (range.exclusiveMinimum === undefined ? accepts(wrap(low)) : !accepts(wrap(low))) && accepts(wrap(range.maximum));
      const pastEnds = !accepts(wrap(low - step)) && !accepts(wrap(range.maximum + step * (range.maximum > 1e30 ? 1e30 : 1)));
      check(atEnds && pastEnds, `the plugin's ${name} range is the schema's (${range.exclusiveMinimum !== undefined ? '(' : '['}${low}, ${range.maximum}])`);
    }
    for (const [name, property] of Object.entries(schema.properties)) {
      if (!property.enum) continue;
      const every = property.enum.every((choice) => accepts({ [name]: choice }));
      check(every && !accepts({ [name]: `${property.enum[0]}-not` }), `the plugin's ${name} names are the schema's (${property.enum.join(', ')})`);
    }
  }

  // A dictionary that cannot be fetched: its failure comes where the dictionary is used, and not
  // also as an unhandled rejection. And glint environments: missing, not JSON, JSON of another
  // kind, one whose residual map is missing.
  const environments = {
    '/broken.json': '{"regions": [',
    '/other.json': '{"asset": {"version": "2.0"}}',
    '/orphan.json': '{"lights": [], "regions": [], "residual": "orphan.exr"}',
    '/cornerless.json': '{"lights": [], "regions": [{"radiance": [1, 1, 1]}], "residual": "r.exr"}',
    '/crowded.json': JSON.stringify({ lights: [], residual: 'r.exr',
                                      regions: Array(17).fill({ corners: [[0, 0], [0.1, 0], [0.1, 0.1], [0, 0.1]], radiance: [1, 1, 1] }) }),
  };
  const server = http.createServer((request, response) => {
    if (environments[request.url]) {
      response.writeHead(200, { 'Content-Type': 'application/json' });
      response.end(environments[request.url]);
      return;
    }
    response.writeHead(404);
    response.end();
  });
  await new Promise((resolve) => server.listen(0, '127.0.0.1', resolve));
  const unhandled = [];
  const onUnhandled = (reason) => unhandled.push(String(reason));
  process.on('unhandledRejection', onUnhandled);
  try {
    const url = `http://127.0.0.1:${server.address().port}/missing.gdict`;
    const missing = loadGlintDictionary(url);
    await new Promise((resolve) => setTimeout(resolve, 300));
    check(unhandled.length === 0, `an unfetchable dictionary that nothing uses is no unhandled rejection (${unhandled.join(' | ') || 'none'})`);
    await expectRejected('a dictionary the server does not have, when used', missing, `${url}: cannot fetch the glint dictionary (HTTP 404)`);
    const base = `http://127.0.0.1:${server.address().port}`;
    await expectRejected('a glint environment the server does not have', loadGlintEnvironment(`${base}/missing.json`),
                         `${base}/missing.json: cannot fetch the glint environment (HTTP 404)`);
    await expectRejected('a glint environment that is not JSON', loadGlintEnvironment(`${base}/broken.json`),
                         `${base}/broken.json: not a glint environment (`);
    await expectRejected('JSON that is not a glint environment', loadGlintEnvironment(`${base}/other.json`),
                         `${base}/other.json: not a glint environment (no regions, lights and residual; write it with glint env-regions)`);
    await expectRejected('a region without corners', loadGlintEnvironment(`${base}/cornerless.json`),
                         `${base}/cornerless.json: region 0 needs 4 corners (2 numbers each) and radiance (3 numbers)`);
    await expectRejected('more regions than a program draws', loadGlintEnvironment(`${base}/crowded.json`),
                         `${base}/crowded.json: 17 regions, more than the 16 a program draws (glint env-regions --regions)`);
    await expectRejected('a glint environment without its residual map', loadGlintEnvironment(`${base}/orphan.json`),
                         `${base}/orphan.exr: cannot load the residual map (`);
  } finally {
    process.off('unhandledRejection', onUnhandled);
    server.close();
  }
} finally {
  rmSync(folder, { recursive: true, force: true });
}
console.log(failures ? `three.js bad-input test: ${failures} check(s) failed` : 'three.js bad-input test: passed');
process.exit(failures ? 1 : 0);
