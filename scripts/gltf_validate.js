#!/usr/bin/env node
// Validates glTF files with the Khronos glTF-Validator (npm package gltf-validator), loading
// external .bin and image files from beside each file. Prints one line of counts per file,
// each issue, and a total line; exits 1 when any file has errors (or warnings, with
// --fail-on-warnings), 2 on bad usage. Run it through scripts/gltf_validate.sh, which
// installs the validator and sets NODE_PATH.
'use strict';
const fs = require('fs');
const path = require('path');
const validator = require('gltf-validator');

const SEVERITY = ['error', 'warning', 'info', 'hint'];

async function validateFile(file) {
  const bytes = new Uint8Array(fs.readFileSync(file));
  return validator.validateBytes(bytes, {
    uri: path.basename(file),
    maxIssues: 0,  // report everything
    writeTimestamp: false,
    externalResourceFunction: (uri) =>
      fs.promises.readFile(path.resolve(path.dirname(file), decodeURIComponent(uri)))
        .then((data) => new Uint8Array(data)),
  });
}

async function main() {
  const args = process.argv.slice(2);
  const failOnWarnings = args.includes('--fail-on-warnings');
  const quiet = args.includes('--quiet');  // counts only, no issue lines
  const files = args.filter((a) => !a.startsWith('--'));
  if (files.length === 0) {
    console.error('usage: gltf_validate.js [--fail-on-warnings] [--quiet] FILE.gltf...');
    process.exit(2);
  }
  const total = { errors: 0, warnings: 0, infos: 0, hints: 0 };
  for (const file of files) {
    let report;
    try {
      report = await validateFile(file);
    } catch (error) {
      console.log(`${file}: validator could not read the file: ${error}`);
      total.errors += 1;
      continue;
    }
    const i = report.issues;
    total.errors += i.numErrors;
    total.warnings += i.numWarnings;
    total.infos += i.numInfos;
    total.hints += i.numHints;
    console.log(`${file}: ${i.numErrors} errors, ${i.numWarnings} warnings, ${i.numInfos} infos, ${i.numHints} hints`);
    if (!quiet) {
      for (const m of i.messages) {
        console.log(`  ${SEVERITY[m.severity] || m.severity} ${m.code} at ${m.pointer || '/'}: ${m.message}`);
      }
    }
  }
  console.log(`total (${files.length} files, validator ${validator.version()}): ` +
              `${total.errors} errors, ${total.warnings} warnings, ${total.infos} infos, ${total.hints} hints`);
  if (total.errors > 0 || (failOnWarnings && total.warnings > 0)) process.exit(1);
}

main().catch((error) => {
  console.error(`gltf_validate.js: ${error}`);
  process.exit(2);
});
