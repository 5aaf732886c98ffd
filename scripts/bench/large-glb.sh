#!/usr/bin/env bash
# Times `gltfmat check` against the npm Khronos glTF-Validator on a large generated GLB
# (about 110 MB, 4 M triangles), in the same session; prints time and peak memory ratios.
#   scripts/bench/large-glb.sh [vertices]
source "$(dirname "$0")/common.sh"
vertices=${1:-2000000}
python3 scripts/bench/gen_gltf1.py "$work" "$vertices"
# The 2.0 GLB is the upgrade of the generated 1.0 asset.
./target/release/gltfmat upgrade "$work/big.gltf" -o "$work/big.glb" --no-verify >/dev/null
ls -l "$work/big.glb" | awk '{printf "input: %.0f MB GLB\n", $5 / 1e6}'
cat > "$work/khronos.js" <<'JS'
const v = require('gltf-validator'); const fs = require('fs');
v.validateBytes(new Uint8Array(fs.readFileSync(process.argv[2])), { maxIssues: 0 })
  .then((r) => console.log(`khronos: ${r.issues.numErrors} errors`));
JS
read -r ours_s ours_kb _ < <(best_of 3 ./target/release/gltfmat check "$work/big.glb" --quiet)
read -r theirs_s theirs_kb < <(NODE_PATH=scripts/bench/node_modules best_of 3 node "$work/khronos.js" "$work/big.glb")
printf 'large GLB: gltfmat %.2fs %d MB   khronos(npm) %.2fs %d MB   speed %.1fx   memory %.2f of theirs\n' \
  "$ours_s" $((ours_kb / 1024)) "$theirs_s" $((theirs_kb / 1024)) \
  "$(echo "$theirs_s / $ours_s" | bc -l)" "$(echo "$ours_kb / $theirs_kb" | bc -l)"
