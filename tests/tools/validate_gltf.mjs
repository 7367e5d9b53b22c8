// Runs the Khronos glTF validator on each file given on the command line.
// Prints each report; exits 1 if any file has errors (warnings are allowed),
// 2 on bad usage or if the validator is not installed.
// Install: npm ci --prefix tests/tools
import fs from 'node:fs';
import path from 'node:path';
import { createRequire } from 'node:module';

const require = createRequire(import.meta.url);
let validator;
try {
  validator = require('gltf-validator');
} catch (e) {
  console.error('gltf-validator is not installed: run  npm ci --prefix tests/tools  (' + e.message + ')');
  process.exit(2);
}

const files = process.argv.slice(2);
if (files.length === 0) {
  console.error('usage: node validate_gltf.mjs FILE.gltf|FILE.glb...');
  process.exit(2);
}

async function validate(file) {
  const bytes = new Uint8Array(fs.readFileSync(file));
  const report = await validator.validateBytes(bytes, {
    uri: path.basename(file),
    maxIssues: 100,
    externalResourceFunction: (uri) =>
      fs.promises.readFile(path.resolve(path.dirname(file), decodeURIComponent(uri))).then((b) => new Uint8Array(b)),
  });
  console.log(JSON.stringify({ file, issues: report.issues, info: report.info }, null, 2));
  return report.issues.numErrors;
}

let failed = 0;
for (const file of files) {
  try {
    const errors = await validate(file);
    if (errors > 0) {
      console.error(`${file}: ${errors} validation error(s)`);
      failed++;
    }
  } catch (e) {
    console.error(`${file}: validator could not read the file: ${e}`);
    failed++;
  }
}
process.exit(failed ? 1 : 0);
