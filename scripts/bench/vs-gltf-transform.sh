#!/usr/bin/env bash
# gltfmat upgrade against glTF-Transform's metalRough() (npm @gltf-transform/functions; an
# oracle, never a dependency) on every glTF 2.0 KHR_materials_pbrSpecularGlossiness asset of
# the fixtures and of ../shared/real-world: both outputs compared with the source by
# `gltfmat compare` (same evaluator, same direction set, the source read as the archived
# extension's own model), and both tools timed in the same run, best of five each; gltfmat's
# time includes its own proof (every converted material evaluated) and its output check.
#   scripts/bench/vs-gltf-transform.sh [ASSET…]
source "$(dirname "$0")/common.sh"
if [ ! -d "$bench_dir/node_modules/@gltf-transform/functions" ] || [ ! -d "$bench_dir/node_modules/ndarray-pixels" ]; then
  npm install --prefix "$bench_dir" --no-save --silent gltf-validator gltf-pipeline \
    @gltf-transform/core @gltf-transform/extensions @gltf-transform/functions ndarray-pixels >/dev/null
fi
assets=("$@")
if [ ${#assets[@]} -eq 0 ]; then
  assets=(fixtures/spec-gloss/*.gltf fixtures/spec-gloss/*.glb)
  while IFS= read -r file; do assets+=("$file"); done < <(grep -l KHR_materials_pbrSpecularGlossiness ../shared/real-world/gltf2/*/*/*.gltf 2>/dev/null | sort)
fi
transform() { node "$bench_dir/gltf-transform-metalrough.mjs" "$@"; }
# The worst ΔE2000 over the asset's materials, or why there is none.
worst() {
  # compare exits 1 when a pair differs: its figures are what is wanted here.
  { ./target/release/gltfmat compare "$1" "$2" --format json 2>/dev/null || true; } |
    python3 -c 'import json,sys; r=json.load(sys.stdin); print("%.2f" % max(p["max"] for p in r))' 2>/dev/null || echo "n/a"
}
printf '%-36s %12s %12s %10s %10s %7s\n' asset "gltfmat ΔE" "gl-T ΔE" "gltfmat s" "gl-T s" ratio
for asset in "${assets[@]}"; do
  ours="$work/ours.glb" theirs="$work/theirs.glb"
  rm -f "$ours" "$theirs"
  if ! ./target/release/gltfmat upgrade "$asset" -o "$ours" >/dev/null 2>"$work/ours.err"; then
    printf '%-36s %s\n' "$(basename "$asset")" "gltfmat refused: $(tail -1 "$work/ours.err")"
    continue
  fi
  transform "$asset" "$theirs" >/dev/null 2>&1 || true
  read -r t_ours _ < <(best_of 5 ./target/release/gltfmat upgrade "$asset" -o "$work/out-ours-RUN.glb")
  read -r t_theirs _ < <(best_of 5 node "$bench_dir/gltf-transform-metalrough.mjs" "$asset" "$work/out-theirs-RUN.glb")
  printf '%-36s %12s %12s %10.3f %10.3f %6.1fx\n' "$(basename "$asset")" "$(worst "$asset" "$ours")" \
    "$( [ -f "$theirs" ] && worst "$asset" "$theirs" || echo failed)" "$t_ours" "$t_theirs" "$(echo "$t_theirs / $t_ours" | bc -l)"
done
