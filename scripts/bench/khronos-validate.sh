#!/usr/bin/env bash
# Runs the npm Khronos glTF-Validator (an oracle, never a dependency) on each file and prints
# its error/warning/info counts; exits 1 when any file has an error.
#   scripts/bench/khronos-validate.sh FILE...
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
[ -d "$here/node_modules/gltf-validator" ] || npm install --prefix "$here" --no-save --silent gltf-validator gltf-pipeline >/dev/null
NODE_PATH="$here/node_modules" node - "$@" <<'JS'
const v = require('gltf-validator'); const fs = require('fs'); const path = require('path');
(async () => {
  let failed = false;
  for (const f of process.argv.slice(2)) {
    const dir = path.dirname(f);
    let report;
    try {
      report = await v.validateBytes(new Uint8Array(fs.readFileSync(f)), { uri: f,
        externalResourceFunction: (u) => new Promise((ok, no) => fs.readFile(path.join(dir, decodeURIComponent(u)), (e, d) => e ? no(e) : ok(new Uint8Array(d)))) });
    } catch (e) {
      console.log(`${f}: the validator rejected it: ${e}`);
      failed = true;
      continue;
    }
    const i = report.issues;
    console.log(`${f}: ${i.numErrors} error(s), ${i.numWarnings} warning(s), ${i.numInfos} info(s)`);
    for (const m of i.messages.filter((m) => m.severity <= 1)) console.log(`  ${m.code} ${m.pointer || m.offset}: ${m.message}`);
    if (i.numErrors > 0) failed = true;
  }
  process.exit(failed ? 1 : 0);
})();
JS
