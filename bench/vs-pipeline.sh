#!/usr/bin/env bash
# Times `gltfmat upgrade` against gltf-pipeline (npm; an oracle, never a dependency) on a
# generated glTF 1.0 asset, in the same session, and prints the ratio.
#   bench/vs-pipeline.sh [vertices]     (default 2 000 000 vertices, 4 000 000 triangles, ~110 MB)
source "$(dirname "$0")/common.sh"
vertices=${1:-2000000}
python3 bench/gen_gltf1.py "$work" "$vertices"
now() { date +%s.%N; }
t0=$(now); ./target/release/gltfmat upgrade "$work/big.gltf" -o "$work/ours.glb" >/dev/null; t1=$(now)
node bench/node_modules/gltf-pipeline/bin/gltf-pipeline.js -i "$work/big.gltf" -o "$work/theirs.glb" >/dev/null; t2=$(now)
ours=$(echo "$t1 - $t0" | bc -l); theirs=$(echo "$t2 - $t1" | bc -l)
printf 'upgrade: gltfmat %.2fs (incl. checking its output)  gltf-pipeline %.2fs  ratio %.1fx\n' "$ours" "$theirs" "$(echo "$theirs / $ours" | bc -l)"
