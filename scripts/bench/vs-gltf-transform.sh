#!/usr/bin/env bash
# gltfmat upgrade against glTF-Transform's metalRough() (npm @gltf-transform/functions; an
# oracle, never a dependency) on every glTF 2.0 KHR_materials_pbrSpecularGlossiness asset of
# the fixtures and of ../shared/real-world: both outputs compared with the source by
# `gltfmat compare` (same evaluator, same direction set, the source read as the archived
# extension's own model), and both tools timed in the same run, best of five each; gltfmat's
# time includes its own proof (every converted material evaluated) and its output check.
#   scripts/bench/vs-gltf-transform.sh [ASSET…]
#   scripts/bench/vs-gltf-transform.sh --generated [SIZE] [noise]   (a quad with SIZE² textures,
#     2048 by default; with `noise` their texels are random, so that nothing repeats)
#   scripts/bench/vs-gltf-transform.sh --real   (two quads, each reading one real 2048² image of
#     ../shared as its diffuse and its specular-glossiness texture: Cesium's milk truck atlas,
#     flat regions and detail; and a JPEG, whose texels all differ)
source "$(dirname "$0")/common.sh"
if [ ! -d "$bench_dir/node_modules/@gltf-transform/functions" ] || [ ! -d "$bench_dir/node_modules/ndarray-pixels" ]; then
  npm install --prefix "$bench_dir" --no-save --silent gltf-validator gltf-pipeline \
    @gltf-transform/core @gltf-transform/extensions @gltf-transform/functions ndarray-pixels >/dev/null
fi
assets=("$@")
# `quad OUT DIFFUSE SPECGLOSS FACTORS`: a spec-gloss quad reading the two images (files beside
# OUT), with FACTORS (JSON members) in its extension.
quad() {
  python3 - "$@" <<'PY'
import base64, json, struct, sys
out, diffuse, specgloss, factors = sys.argv[1:]
quad = struct.pack("<12f", 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0) + struct.pack("<12f", *[0, 0, 1] * 4) \
    + struct.pack("<8f", 0, 1, 1, 1, 1, 0, 0, 0) + struct.pack("<6H", 0, 1, 2, 0, 2, 3)
views = [(0, 48, 34962), (48, 48, 34962), (96, 32, 34962), (128, 12, 34963)]
asset = {
  "asset": {"version": "2.0"}, "extensionsUsed": ["KHR_materials_pbrSpecularGlossiness"],
  "buffers": [{"byteLength": len(quad), "uri": "data:application/octet-stream;base64," + base64.b64encode(quad).decode()}],
  "bufferViews": [{"buffer": 0, "byteOffset": o, "byteLength": l, "target": t} for o, l, t in views],
  "accessors": [
    {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]},
    {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC3"},
    {"bufferView": 2, "componentType": 5126, "count": 4, "type": "VEC2"},
    {"bufferView": 3, "componentType": 5123, "count": 6, "type": "SCALAR"}],
  "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2}, "indices": 3, "material": 0}]}],
  "nodes": [{"mesh": 0}], "scenes": [{"nodes": [0]}], "scene": 0,
  "images": [{"uri": diffuse}, {"uri": specgloss}], "textures": [{"source": 0}, {"source": 1}],
  "materials": [{"extensions": {"KHR_materials_pbrSpecularGlossiness": {
    "diffuseTexture": {"index": 0}, "specularGlossinessTexture": {"index": 1},
    **json.loads("{" + factors + "}")}}}],
}
json.dump(asset, open(out, "w"))
PY
}
if [ "${1:-}" = "--generated" ]; then
  # A quad whose diffuse and specular-glossiness textures vary in every texel (smooth waves
  # and sharp steps), so that neither tool's work shrinks to flat runs.
  python3 - "$work" "${2:-2048}" "${3:-}" <<'PY'
import math, random, struct, sys, zlib
work, n, noise = sys.argv[1], int(sys.argv[2]), sys.argv[3] == "noise"
def png(path, channels, pixel):
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))
    rows = b"".join(b"\x00" + bytes(v for x in range(n) for v in pixel(x, y)) for y in range(n))
    kind = {3: 2, 4: 6}[channels]
    open(f"{work}/{path}", "wb").write(b"\x89PNG\r\n\x1a\n"
        + chunk(b"IHDR", struct.pack(">IIBBBBB", n, n, 8, kind, 0, 0, 0))
        + chunk(b"IDAT", zlib.compress(rows, 1)) + chunk(b"IEND", b""))
wave = lambda x, y: int(127 + 120 * math.sin(x / 37.0) * math.cos(y / 23.0))
step = lambda x, y: 60 * (((x >> 4) + (y >> 4)) & 1)
if noise:
    texels = random.Random(1).randbytes(2 * n * n)
    wave = lambda x, y: texels[2 * (y * n + x)]
    step = lambda x, y: 20 * (texels[2 * (y * n + x) + 1] & 3)
png("diffuse.png", 3, lambda x, y: (wave(x, y), 80 + step(x, y), 200 - wave(x, y) // 2))
png("specgloss.png", 4, lambda x, y: (30 + step(x, y) // 2, 40 + wave(x, y) // 8, 40, 255 - wave(y, x) // 2))
PY
  quad "$work/specgloss-${2:-2048}.gltf" diffuse.png specgloss.png '"glossinessFactor": 0.9'
  assets=("$work/specgloss-${2:-2048}.gltf")
fi
if [ "${1:-}" = "--real" ]; then
  cp ../shared/real-world/gltf1/sample-models/CesiumMilkTruck/glTF/CesiumMilkTruck.png "$work/atlas.png"
  cp ../shared/real-world/gltf2/blender-io/24_animation_pointer/Normal_map_example.jpg "$work/jpeg.jpg"
  for image in atlas.png jpeg.jpg; do
    quad "$work/${image%.*}-2048.gltf" "$image" "$image" '"specularFactor": [0.25, 0.25, 0.25], "glossinessFactor": 0.8'
  done
  assets=("$work/atlas-2048.gltf" "$work/jpeg-2048.gltf")
fi
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
