// Validates glTF files with Khronos glTF-Validator (npm package gltf-validator):
// one line per file (errors, warnings, infos) and its first errors and warnings;
// exits 1 when a file has an error. Run by scripts/validate-gltf.sh.
const validator = require('gltf-validator');
const fs = require('fs');
const path = require('path');
(async () => {
  let failed = 0;
  for (const file of process.argv.slice(2)) {
    const data = new Uint8Array(fs.readFileSync(file));
    const report = await validator.validateBytes(data, {
      uri: file, maxIssues: 20,
      externalResourceFunction: (uri) => new Promise((res, rej) => {
        try { res(new Uint8Array(fs.readFileSync(path.resolve(path.dirname(file), decodeURIComponent(uri))))); } catch (e) { rej(e.toString()); }
      })
    });
    const i = report.issues;
    console.log(`${path.basename(file)}: ${i.numErrors} errors, ${i.numWarnings} warnings, ${i.numInfos} infos`);
    for (const m of i.messages.filter(m => m.severity <= 1).slice(0, 5)) console.log(`   ${m.severity === 0 ? 'error' : 'warning'} ${m.code}: ${m.message} ${m.pointer || ''}`);
    if (i.numErrors > 0) failed++;
  }
  process.exit(failed ? 1 : 0);
})();
