const v = require('gltf-validator'); const fs = require('fs'); const path = require('path');
(async () => { for (const f of process.argv.slice(2)) {
  const dir = path.dirname(f);
  try {
    await v.validateBytes(new Uint8Array(fs.readFileSync(f)), { uri: f,
      externalResourceFunction: (u) => new Promise((ok, no) => fs.readFile(path.join(dir, decodeURIComponent(u)), (e, d) => e ? no(e) : ok(new Uint8Array(d)))) });
  } catch (e) { /* a broken case: the validator's own failure still counts as its time */ }
} })();
