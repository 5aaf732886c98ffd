#!/usr/bin/env bash
# Times gltfmat against the npm Khronos glTF-Validator in the same session and prints ratios.
#   scripts/bench/vs-khronos.sh [corpus-folder]
# Installs gltf-validator into scripts/bench/node_modules on first use (an oracle, never a dependency).
source "$(dirname "$0")/common.sh"
corpus=${1:-../shared/conformance/khronos-glTF-Validator/test}
mapfile -t files < <(find "$corpus" -name '*.gltf' -o -name '*.glb' | sort)
read -r ours _ < <(best_of 3 ./target/release/gltfmat check --profile khronos --format jsonl --quiet "${files[@]}")
read -r theirs _ < <(best_of 3 scripts/bench/khronos-validate.sh "${files[@]}")
printf 'corpus: %d files  gltfmat %.3fs  khronos(npm) %.3fs  ratio %.1fx\n' "${#files[@]}" "$ours" "$theirs" "$(echo "$theirs / $ours" | bc -l)"
