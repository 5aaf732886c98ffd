#!/usr/bin/env bash
# Times `gltfmat upgrade` against gltf-pipeline (npm; an oracle, never a dependency) on a
# generated glTF 1.0 asset, in the same session, best of five runs each taken in turn, and prints
# the ratio.
# gltfmat runs with --no-verify (gltf-pipeline proves nothing; scripts/bench/verify.sh times the
# proof) but still checks its output before writing it.
#   scripts/bench/vs-pipeline.sh [vertices]     (default 2 000 000 vertices, 4 000 000 triangles, ~176 MB)
source "$(dirname "$0")/common.sh"
vertices=${1:-2000000}
python3 scripts/bench/gen_gltf1.py "$work" "$vertices"
ours_cmd=(./target/release/gltfmat upgrade "$work/big.gltf" -o "$work/out-ours.glb" --no-verify)
theirs_cmd=(node scripts/bench/node_modules/gltf-pipeline/bin/gltf-pipeline.js -i "$work/big.gltf" -o "$work/out-theirs.glb")
# Five runs each, one of each tool in turn: this machine's speed drifts within minutes, and
# runs taken in turn see the same drift, where five of one tool and then five of the other
# may not. Each tool's fastest run (with its peak memory) counts.
for _ in 1 2 3 4 5; do
  best_of 1 "${ours_cmd[@]}" >>"$work/ours.times"
  best_of 1 "${theirs_cmd[@]}" >>"$work/theirs.times"
done
read -r ours ours_kb < <(sort -g "$work/ours.times" | head -1)
read -r theirs theirs_kb < <(sort -g "$work/theirs.times" | head -1)
printf 'upgrade: gltfmat %.2fs %d MB (incl. checking its output)  gltf-pipeline %.2fs %d MB  ratio %.1fx\n' \
  "$ours" $((ours_kb / 1024)) "$theirs" $((theirs_kb / 1024)) "$(echo "$theirs / $ours" | bc -l)"
