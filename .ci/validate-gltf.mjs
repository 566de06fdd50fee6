// Validates glTF 2.0 files (.gltf with external buffers, or .glb) with the Khronos glTF-Validator.
//
// Usage:
//   (cd SOMEDIR && npm install gltf-validator)      # once, offline-capable from the npm cache
//   GLTF_VALIDATOR_DIR=SOMEDIR node .ci/validate-gltf.mjs FILE.glb FILE.gltf ...
// Without GLTF_VALIDATOR_DIR the package is looked up the usual Node way (node_modules beside or
// above this script). Exit status 0 when no file has errors, 1 otherwise, 2 on usage errors.
// Warnings and infos are printed but do not fail.

import { readFile } from 'node:fs/promises';
import { createRequire } from 'node:module';
import path from 'node:path';

function loadValidator() {
  const dir = process.env.GLTF_VALIDATOR_DIR;
  const require = createRequire(dir ? path.join(path.resolve(dir), 'package.json') : import.meta.url);
  return require('gltf-validator');
}

const files = process.argv.slice(2);
if (files.length === 0) {
  console.error('usage: node .ci/validate-gltf.mjs FILE.gltf|FILE.glb ...');
  process.exit(2);
}
const validator = loadValidator();
let failed = false;
for (const file of files) {
  const bytes = new Uint8Array(await readFile(file));
  const report = await validator.validateBytes(bytes, {
    uri: path.basename(file),
    maxIssues: 100,
    // External buffers (.bin) are resolved relative to the file being validated.
    externalResourceFunction: (uri) =>
      readFile(path.resolve(path.dirname(file), decodeURIComponent(uri))).then((b) => new Uint8Array(b)),
  });
  const { numErrors, numWarnings, numInfos, messages } = report.issues;
  console.log(`${file}: ${numErrors} errors, ${numWarnings} warnings, ${numInfos} infos (glTF-Validator ${report.validatorVersion})`);
  for (const m of messages) {
    const severity = ['error', 'warning', 'info', 'hint'][m.severity] ?? m.severity;
    console.log(`  ${severity} ${m.code} at ${m.pointer ?? m.offset ?? ''}: ${m.message}`);
  }
  if (numErrors > 0) failed = true;
}
process.exit(failed ? 1 : 0);
