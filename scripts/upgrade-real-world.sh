#!/usr/bin/env bash
# Upgrades every glTF 1.0 input under a folder (default ../shared/real-world/gltf1) to .glb and
# to .gltf, then counts the outputs' errors in `gltfmat check` and in the npm Khronos
# glTF-Validator (an oracle, never a dependency). Prints one line per refusal and per output
# with errors, then the totals; exits 1 when an output has an error.
#   scripts/upgrade-real-world.sh [FOLDER]
source "$(dirname "$0")/bench/common.sh"
folder="${1:-../shared/real-world/gltf1}"
written=() refused=0 inputs=0
while IFS= read -r -d '' input; do
  inputs=$((inputs + 1))
  stem="$work/$(echo "${input#"$folder"/}" | tr '/ ' '__')"
  for ext in glb gltf; do
    mkdir -p "$stem.$ext.d"
    out="$stem.$ext.d/out.$ext"
    if ./target/release/gltfmat upgrade "$input" -o "$out" >"$stem.$ext.log" 2>&1; then
      written+=("$out")
    else
      refused=$((refused + 1))
      echo "refused ($ext): $(grep -m1 '^gltfmat: ' "$stem.$ext.log")"
    fi
  done
done < <(find "$folder" -type f \( -iname '*.gltf' -o -iname '*.glb' \) -print0 | sort -z)
ours_errors=0
for out in "${written[@]}"; do
  n=$(./target/release/gltfmat check --format json "$out" | python3 -c 'import json,sys; print(json.load(sys.stdin)["issues"]["numErrors"])')
  [ "$n" = 0 ] || echo "gltfmat check: $n error(s) in $out"
  ours_errors=$((ours_errors + n))
done
khronos=$(scripts/bench/khronos-validate.sh "${written[@]}" || true)
echo "$khronos" | grep -E '^\S.*: [1-9][0-9]* error' || true
khronos_errors=$(echo "$khronos" | sed -nE 's/.*: ([0-9]+) error\(s\).*/\1/p' | paste -sd+ - | bc)
with_errors=$(echo "$khronos" | grep -cE ': [1-9][0-9]* error|rejected it' || true)
echo "inputs $inputs; outputs written ${#written[@]} of $((inputs * 2)) ($refused refused);" \
  "errors: gltfmat check $ours_errors, npm Khronos validator $khronos_errors ($with_errors output(s) with errors)"
[ "$ours_errors" = 0 ] && [ "$with_errors" = 0 ]
