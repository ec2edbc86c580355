// Khronos' glTF validator over glTF files (.glb or .gltf): prints each file's counts and its errors
// and warnings, and exits 1 when any file has an error or a warning.
// Usage: node validate_gltf.js NODE_MODULES_DIR FILE...
'use strict';
const fs = require('fs');
const path = require('path');

const validator = require(path.join(process.argv[2], 'gltf-validator'));

async function main(files) {
  let failed = false;
  for (const file of files) {
    const report = await validator.validateBytes(new Uint8Array(fs.readFileSync(file)), { uri: path.basename(file) });
    const { numErrors, numWarnings, numInfos, numHints } = report.issues;
    console.log(`${file}: ${numErrors} errors, ${numWarnings} warnings, ${numInfos} infos, ${numHints} hints`);
    for (const issue of report.issues.messages)
      if (issue.severity <= 1) console.log(`  ${issue.severity === 0 ? 'error' : 'warning'} ${issue.code} at ${issue.pointer}: ${issue.message}`);
    failed = failed || numErrors > 0 || numWarnings > 0;
  }
  return failed ? 1 : 0;
}

main(process.argv.slice(3)).then(
  (status) => process.exit(status),
  (error) => {
    console.error(error);
    process.exit(1);
  },
);
