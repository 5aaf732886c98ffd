#!/usr/bin/env bash
# Times gltfmat against the npm Khronos glTF-Validator in the same session and prints ratios of
# wall time and of CPU time (user + system: gltfmat checks files on every core, the validator
# on one), for the Khronos profile and the default one.
#   scripts/bench/vs-khronos.sh [corpus-folder]
# Installs gltf-validator into scripts/bench/node_modules on first use (an oracle, never a dependency).
source "$(dirname "$0")/common.sh"
corpus=${1:-../shared/conformance/khronos-glTF-Validator/test}
mapfile -t files < <(find "$corpus" -name '*.gltf' -o -name '*.glb' | sort)
read -r theirs _ theirs_cpu < <(best_of 3 scripts/bench/khronos-validate.sh "${files[@]}")
for profile in khronos default; do
  read -r ours _ ours_cpu < <(best_of 3 ./target/release/gltfmat check --profile "$profile" --format jsonl --quiet "${files[@]}")
  printf 'corpus: %d files, --profile %s: gltfmat %.3fs (CPU %.2fs)  khronos(npm) %.3fs (CPU %.2fs)  ratio %.1fx wall, %.1fx CPU\n' \
    "${#files[@]}" "$profile" "$ours" "$ours_cpu" "$theirs" "$theirs_cpu" \
    "$(echo "$theirs / $ours" | bc -l)" "$(echo "$theirs_cpu / $ours_cpu" | bc -l)"
done
