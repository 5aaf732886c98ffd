#!/usr/bin/env bash
# Times `gltfmat upgrade` (upgrade + rebake + check + its ΔE proof) and `gltfmat compare`
# (source against its upgrade) on a generated glTF 1.0 asset with five 2048² textures (two
# metal-rough materials, one spec-gloss), best of 5 runs each (this machine's timings vary by
# a third from run to run).
#   scripts/bench/verify.sh [size]
source "$(dirname "$0")/common.sh"
size=${1:-2048}
python3 - "$work" "$size" "$(pwd)" <<'PY'
import json, struct, sys, zlib, shutil, math
work, n, repo = sys.argv[1], int(sys.argv[2]), sys.argv[3]
def png(path, channels, pixel):
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))
    rows = []
    for y in range(n):
        row = bytearray(b"\x00")
        for x in range(0, n, 64):
            row += bytes(pixel(x, y)) * 64
        rows.append(bytes(row))
    kind = {3: 2, 4: 6}[channels]
    data = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", n, n, 8, kind, 0, 0, 0)) \
        + chunk(b"IDAT", zlib.compress(b"".join(rows), 1)) + chunk(b"IEND", b"")
    open(f"{work}/{path}", "wb").write(data)
wave = lambda x, y: int(127 + 120 * math.sin(x / 97.0) * math.cos(y / 53.0))
png("base.png", 3, lambda x, y: (wave(x, y), 90, 200 - wave(x, y) // 2))
png("mr.png", 3, lambda x, y: (wave(x, y), 255 - wave(x, y), 0))
png("base2.png", 3, lambda x, y: (200, wave(x, y), 60))
png("diffuse.png", 3, lambda x, y: (wave(x, y), wave(y, x), 120))
png("sg.png", 4, lambda x, y: (40, 40 + wave(x, y) // 8, 40, 255 - wave(x, y) // 2))
box = json.load(open(f"{repo}/fixtures/gltf1/pbr-mr-textured-fraunhofer.gltf"))
shutil.copy(f"{repo}/fixtures/gltf1/box.bin", f"{work}/box.bin")
box["images"] = {k: {"uri": f"{k}.png"} for k in ["base", "mr", "base2", "diffuse", "sg"]}
box["textures"] = {f"t_{k}": {"sampler": "sampler_0", "source": k} for k in box["images"]}
ext = "FRAUNHOFER_materials_pbr"
box["materials"] = {
  "metal": {"extensions": {ext: {"materialModel": "PBR_metal_roughness", "values": {"baseColorTexture": "t_base", "metallicRoughnessTexture": "t_mr"}}}},
  "plain": {"extensions": {ext: {"materialModel": "PBR_metal_roughness", "values": {"baseColorTexture": "t_base2", "metallicFactor": 0.0, "roughnessFactor": 0.5}}}},
  "gloss": {"extensions": {ext: {"materialModel": "PBR_specular_glossiness", "values": {"diffuseTexture": "t_diffuse", "specularGlossinessTexture": "t_sg", "specularFactor": [0.5, 0.5, 0.5]}}}},
}
json.dump(box, open(f"{work}/big.gltf", "w"))
PY
# The proof's verdicts are printed; a failed one is a warning here (--verify would refuse).
./target/release/gltfmat upgrade "$work/big.gltf" -o "$work/upgraded.glb" | grep -E "^proof|^warning|wrote"
read -r verify_s verify_kb _ < <(best_of 5 ./target/release/gltfmat upgrade "$work/big.gltf" -o "$work/out-RUN.glb")
read -r compare_s compare_kb _ < <(best_of 5 ./target/release/gltfmat compare "$work/big.gltf" "$work/upgraded.glb")
printf 'five %d² textures, best of 5: upgrade with its proof %.2fs (%d MB), compare %.2fs (%d MB)\n' \
  "$size" "$verify_s" "$((verify_kb / 1024))" "$compare_s" "$((compare_kb / 1024))"
