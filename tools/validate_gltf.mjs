// Validates glTF files with the Khronos glTF validator (npm gltf-validator, pinned in
// tools/package.json): prints each report's summary and its issues, exits 1 when any file
// has errors (or cannot be read), 0 otherwise. Usage: node tools/validate_gltf.mjs FILE...
import fs from "node:fs";
import path from "node:path";
import validator from "gltf-validator";

const files = process.argv.slice(2);
if (files.length === 0) {
  console.error("usage: node validate_gltf.mjs FILE.glb|FILE.gltf...");
  process.exit(2);
}

const severityNames = ["error", "warning", "info", "hint"];
let failed = false;
for (const file of files) {
  let report;
  try {
    const bytes = new Uint8Array(fs.readFileSync(file));
    report = await validator.validateBytes(bytes, {
      uri: path.basename(file),
      maxIssues: 100,
      externalResourceFunction: (uri) =>
        fs.promises.readFile(path.resolve(path.dirname(file), decodeURIComponent(uri))).then((b) => new Uint8Array(b)),
    });
  } catch (error) {
    console.error(`${file}: cannot validate: ${error}`);
    failed = true;
    continue;
  }
  const issues = report.issues;
  console.log(
    `${file}: ${issues.numErrors} errors, ${issues.numWarnings} warnings, ${issues.numInfos} infos, ` +
      `${issues.numHints} hints (glTF validator ${report.validatorVersion})`
  );
  for (const message of issues.messages) {
    console.log(`  ${severityNames[message.severity] ?? message.severity}: ${message.code} ${message.pointer ?? ""} ${message.message}`);
  }
  if (issues.numErrors > 0) failed = true;
}
process.exit(failed ? 1 : 0);
