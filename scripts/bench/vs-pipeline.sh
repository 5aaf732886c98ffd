#!/usr/bin/env bash
# Times `gltfmat upgrade` against gltf-pipeline (npm; an oracle, never a dependency) on a
# generated glTF 1.0 asset, in the same session, best of five runs each, and prints the ratio.
# gltfmat runs with --no-verify (gltf-pipeline proves nothing; scripts/bench/verify.sh times the
# proof) but still checks its output before writing it.
#   scripts/bench/vs-pipeline.sh [vertices]     (default 2 000 000 vertices, 4 000 000 triangles, ~176 MB)
source "$(dirname "$0")/common.sh"
vertices=${1:-2000000}
python3 scripts/bench/gen_gltf1.py "$work" "$vertices"
read -r ours ours_kb < <(best_of 5 ./target/release/gltfmat upgrade "$work/big.gltf" -o "$work/out-ours-RUN.glb" --no-verify)
read -r theirs theirs_kb < <(best_of 5 node scripts/bench/node_modules/gltf-pipeline/bin/gltf-pipeline.js -i "$work/big.gltf" -o "$work/out-theirs-RUN.glb")
printf 'upgrade: gltfmat %.2fs %d MB (incl. checking its output)  gltf-pipeline %.2fs %d MB  ratio %.1fx\n' \
  "$ours" $((ours_kb / 1024)) "$theirs" $((theirs_kb / 1024)) "$(echo "$theirs / $ours" | bc -l)"
