#!/usr/bin/env python3
"""Writes a large glTF 1.0 asset for the benchmarks: a vertex grid with NORMAL and TEXCOORD_0,
32-bit indices, one FRAUNHOFER_materials_pbr material with a 2048² base colour texture, skinned
to a two-joint skeleton (JOINT/WEIGHT per vertex, weights that do not sum to 1 as COLLADA2GLTF
wrote them, a bindShapeMatrix) whose second joint is animated.
    scripts/bench/gen_gltf1.py WORK_FOLDER VERTICES   → WORK_FOLDER/big.gltf + big.bin + base.png
"""
import array, json, sys, math, struct, zlib
work, n = sys.argv[1], int(sys.argv[2])
side = int(math.isqrt(n))
pos = array.array('f'); nrm = array.array('f'); uv = array.array('f'); jnt = array.array('f'); wgt = array.array('f')
for y in range(side):
    for x in range(side):
        pos.extend((x / side, y / side, 0.0)); nrm.extend((0.0, 0.0, 1.0)); uv.extend((x / side, y / side))
        jnt.extend((0.0, 1.0, 0.0, 0.0)); wgt.extend((0.2 + 0.5 * (1 - x / side), 0.2 + 0.5 * x / side, 0.0, 0.0))
idx = array.array('I')
for y in range(side - 1):
    row = y * side
    for x in range(side - 1):
        a = row + x
        idx.extend((a, a + 1, a + side, a + 1, a + side + 1, a + side))
count = side * side
ibm = array.array('f', [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, -0.5, 0, 0, 1])
times = array.array('f', [0.0, 1.0, 2.0]); rotations = array.array('f', [0, 0, 0, 1, 0, 0, 0.3826834, 0.9238795, 0, 0, 0, 1])
blobs = [idx.tobytes(), pos.tobytes(), nrm.tobytes(), uv.tobytes(), jnt.tobytes(), wgt.tobytes(), ibm.tobytes(), times.tobytes(), rotations.tobytes()]
offsets = [0]
for b in blobs[:-1]:
    offsets.append(offsets[-1] + len(b))
with open(f"{work}/big.bin", "wb") as f:
    for b in blobs: f.write(b)
def png(path, n):
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))
    rows = b"".join(b"\x00" + bytes(((x * 3 + y) & 255, (x ^ y) & 255, (y * 5) & 255)[k] for x in range(n) for k in range(3)) for y in range(n))
    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", n, n, 8, 2, 0, 0, 0))
                + chunk(b"IDAT", zlib.compress(rows, 1)) + chunk(b"IEND", b""))
png(f"{work}/base.png", 2048)
views = {f"v{i}": {"buffer": "b", "byteOffset": o, "byteLength": len(b), **({"target": 34963 if i == 0 else 34962} if i < 6 else {})} for i, (o, b) in enumerate(zip(offsets, blobs))}
acc = {
  "ind": {"bufferView": "v0", "byteOffset": 0, "componentType": 5125, "count": len(idx), "type": "SCALAR", "min": [0], "max": [count - 1]},
  "pos": {"bufferView": "v1", "byteOffset": 0, "byteStride": 12, "componentType": 5126, "count": count, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]},
  "nrm": {"bufferView": "v2", "byteOffset": 0, "byteStride": 12, "componentType": 5126, "count": count, "type": "VEC3", "min": [0, 0, 1], "max": [0, 0, 1]},
  "uv": {"bufferView": "v3", "byteOffset": 0, "byteStride": 8, "componentType": 5126, "count": count, "type": "VEC2", "min": [0, 0], "max": [1, 1]},
  "jnt": {"bufferView": "v4", "byteOffset": 0, "byteStride": 16, "componentType": 5126, "count": count, "type": "VEC4", "min": [0, 1, 0, 0], "max": [0, 1, 0, 0]},
  "wgt": {"bufferView": "v5", "byteOffset": 0, "byteStride": 16, "componentType": 5126, "count": count, "type": "VEC4"},
  "ibm": {"bufferView": "v6", "byteOffset": 0, "componentType": 5126, "count": 2, "type": "MAT4"},
  "time": {"bufferView": "v7", "byteOffset": 0, "componentType": 5126, "count": 3, "type": "SCALAR", "min": [0], "max": [2]},
  "rot": {"bufferView": "v8", "byteOffset": 0, "componentType": 5126, "count": 3, "type": "VEC4"},
}
doc = {"asset": {"version": "1.0"}, "extensionsUsed": ["OES_element_index_uint", "FRAUNHOFER_materials_pbr"],
  "buffers": {"b": {"uri": "big.bin", "byteLength": sum(map(len, blobs))}}, "bufferViews": views, "accessors": acc,
  "materials": {"m": {"extensions": {"FRAUNHOFER_materials_pbr": {"materialModel": "PBR_metal_roughness", "values": {"baseColorFactor": [0.8, 0.2, 0.2, 1], "baseColorTexture": "t", "metallicFactor": 0, "roughnessFactor": 0.5}}}}},
  "textures": {"t": {"source": "img", "sampler": "s"}}, "images": {"img": {"uri": "base.png"}},
  "samplers": {"s": {"magFilter": 9729, "minFilter": 9987, "wrapS": 10497, "wrapT": 10497}},
  "meshes": {"mesh": {"primitives": [{"attributes": {"POSITION": "pos", "NORMAL": "nrm", "TEXCOORD_0": "uv", "JOINT": "jnt", "WEIGHT": "wgt"}, "indices": "ind", "material": "m", "mode": 4}]}},
  "skins": {"skin": {"bindShapeMatrix": [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0.1, 1], "inverseBindMatrices": "ibm", "jointNames": ["root", "tip"]}},
  "animations": {"bend": {"channels": [{"sampler": "r", "target": {"id": "j1", "path": "rotation"}}],
    "samplers": {"r": {"input": "TIME", "output": "rotation", "interpolation": "LINEAR"}}, "parameters": {"TIME": "time", "rotation": "rot"}}},
  "nodes": {"n": {"meshes": ["mesh"], "skin": "skin", "skeletons": ["j0"]},
    "j0": {"jointName": "root", "children": ["j1"]}, "j1": {"jointName": "tip", "translation": [0.5, 0, 0]}},
  "scenes": {"s": {"nodes": ["n", "j0"]}}, "scene": "s"}
json.dump(doc, open(f"{work}/big.gltf", "w"))
print(f"input: {count} vertices, {len(idx) // 3} triangles, {sum(map(len, blobs)) / 1e6:.0f} MB, one 2048² PNG texture, skinned to 2 joints, 1 animation")
