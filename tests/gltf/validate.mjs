// The Khronos glTF-Validator (npm gltf-validator, pinned in package.json) on every file glint
// writes: each built-in scene exported by `glint export` as .glb and as .gltf, and the sample
// assets of EXT_materials_glint. Each must have no error and no warning; the validator's infos (an
// extension it does not know, tangents it takes for unused) are listed, not held against the file.
// Each export must carry the glint extension as used, not required. A broken copy of an export
// must give errors, or the check could not fail.
//
//   node validate.mjs GLINT WORK_FOLDER SAMPLES_FOLDER
//
// Exit 77 (ctest: skipped) with one line when the validator is not installed (scripts/deps
// installs it).
import { execFileSync } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';
import { createRequire } from 'node:module';

const [glint, work, samples] = process.argv.slice(2);
if (!glint || !work || !samples) {
  console.error('usage: node validate.mjs GLINT WORK_FOLDER SAMPLES_FOLDER');
  process.exit(2);
}
const require = createRequire(import.meta.url);
let validator;
try {
  validator = require('gltf-validator');
} catch {
  console.log('skipped: gltf-validator is not installed in tests/gltf (scripts/deps installs it with npm ci)');
  process.exit(77);
}

// The JSON of a .gltf, or of a .glb's first chunk (glTF 2.0, "GLB File Format Specification").
function documentOf(bytes) {
  if (bytes.subarray(0, 4).toString('latin1') !== 'glTF') return JSON.parse(bytes.toString('utf8'));
  const length = bytes.readUInt32LE(12);
  return JSON.parse(bytes.subarray(20, 20 + length).toString('utf8'));
}

async function report(file) {
  return validator.validateBytes(new Uint8Array(fs.readFileSync(file)), {
    uri: path.basename(file),
    maxIssues: 0,
    writeTimestamp: false,
    externalResourceFunction: (uri) => Promise.resolve(new Uint8Array(fs.readFileSync(path.join(path.dirname(file), decodeURIComponent(uri))))),
  });
}

// The built-in scenes, as the command lists them in its help.
const help = execFileSync(glint, ['export', '--help'], { encoding: 'utf8' });
const listed = /A built-in scene \(([^)]*)\)/.exec(help);
if (!listed) {
  console.error(`validate.mjs: no list of built-in scenes in \`glint export --help\`:\n${help}`);
  process.exit(1);
}
const scenes = listed[1].split(', ');

fs.rmSync(work, { recursive: true, force: true });
fs.mkdirSync(work, { recursive: true });
const files = [];
const problems = [];
for (const scene of scenes) {
  for (const extension of ['.glb', '.gltf']) {
    const file = path.join(work, scene + extension);
    execFileSync(glint, ['export', scene, '-o', file], { stdio: ['ignore', 'ignore', 'pipe'] });
    files.push(file);
    const document = documentOf(fs.readFileSync(file));
    const layers = (document.materials ?? []).filter((m) => m.extensions?.EXT_materials_glint).length;
    if (layers === 0) problems.push(`${path.basename(file)}: no material carries EXT_materials_glint`);
    if (!(document.extensionsUsed ?? []).includes('EXT_materials_glint')) {
      problems.push(`${path.basename(file)}: EXT_materials_glint is not in extensionsUsed`);
    }
    if (document.extensionsRequired !== undefined) {
      problems.push(`${path.basename(file)}: extensionsRequired is ${JSON.stringify(document.extensionsRequired)}`);
    }
  }
}
for (const name of fs.readdirSync(samples).sort()) {
  if (name.endsWith('.gltf') || name.endsWith('.glb')) files.push(path.join(samples, name));
}

for (const file of files) {
  const { issues } = await report(file);
  const codes = [...new Set(issues.messages.map((m) => m.code))].join(', ');
  console.log(`${path.basename(file)}: ${issues.numErrors} errors, ${issues.numWarnings} warnings, ` +
              `${issues.numInfos} infos${codes ? ` (${codes})` : ''}`);
  for (const m of issues.messages) {
    if (m.severity <= 1) problems.push(`${path.basename(file)}: ${m.code} at ${m.pointer}: ${m.message}`);
  }
}

// The check can fail: an accessor that claims more elements than its buffer view holds.
const broken = path.join(work, 'broken.gltf');
const document = JSON.parse(fs.readFileSync(path.join(work, `${scenes[0]}.gltf`), 'utf8'));
document.accessors[0].count += 1000000;
fs.writeFileSync(broken, JSON.stringify(document));
const brokenErrors = (await report(broken)).issues.numErrors;
console.log(`broken.gltf (an accessor past its buffer view, must have errors): ${brokenErrors} errors`);
if (brokenErrors === 0) problems.push('broken.gltf: the validator found no error in a broken file');

if (problems.length > 0) {
  for (const problem of problems) console.log(`FAILED ${problem}`);
  process.exit(1);
}
console.log(`${files.length} files (${scenes.length} built-in scenes as .glb and .gltf, ${files.length - 2 * scenes.length} samples): ` +
            `0 errors, 0 warnings (gltf-validator ${validator.version()})`);
