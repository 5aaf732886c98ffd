#!/usr/bin/env bash
# Times gltfmat against the npm Khronos glTF-Validator in the same session and prints ratios.
#   bench/vs-khronos.sh [corpus-folder]
# Installs gltf-validator into bench/node_modules on first use (an oracle, never a dependency).
set -euo pipefail
cd "$(dirname "$0")/.."
corpus=${1:-../shared/conformance/khronos-glTF-Validator/test}
cargo build --release -q
source bench/oracles.sh
mapfile -t files < <(find "$corpus" -name '*.gltf' -o -name '*.glb' | sort)
cat > bench/.khronos.js <<'JS'
const v = require('gltf-validator'); const fs = require('fs'); const path = require('path');
(async () => { for (const f of process.argv.slice(2)) {
  const dir = path.dirname(f);
  try {
    await v.validateBytes(new Uint8Array(fs.readFileSync(f)), { uri: f,
      externalResourceFunction: (u) => new Promise((ok, no) => fs.readFile(path.join(dir, decodeURIComponent(u)), (e, d) => e ? no(e) : ok(new Uint8Array(d)))) });
  } catch (e) { /* a broken case: the validator's own failure still counts as its time */ }
} })();
JS
now() { date +%s.%N; }
t0=$(now); ./target/release/gltfmat check --profile khronos --format jsonl --quiet "${files[@]}" >/dev/null || true; t1=$(now)
NODE_PATH=bench/node_modules node bench/.khronos.js "${files[@]}"; t2=$(now)
ours=$(echo "$t1 - $t0" | bc -l); theirs=$(echo "$t2 - $t1" | bc -l)
printf 'corpus: %d files  gltfmat %.3fs  khronos(npm) %.3fs  ratio %.1fx\n' "${#files[@]}" "$ours" "$theirs" "$(echo "$theirs / $ours" | bc -l)"
