#!/usr/bin/env python3
"""Writes the glTF 1.0 GLB payloads of the 3D Tiles content under a folder (b3dm, i3dm and the
tiles of cmpt files; an i3dm that names its glTF by URI has none) to OUT, one .glb each, so
that scripts/upgrade-real-world.sh OUT upgrades them. Content from the 3D Tiles 1.0 era
(CesiumGS/3d-tiles-samples before 2018, 3d-tiles-tools' test data) carries glTF 1.0.
  scripts/tile-payloads.py FOLDER OUT
"""
import os
import struct
import sys


def payloads(data, name):
    """(name, GLB bytes) of each tile in `data`: a cmpt's inner tiles in order."""
    magic = data[:4]
    if magic == b'cmpt':
        count, offset, found = struct.unpack('<I', data[12:16])[0], 16, []
        for i in range(count):
            length = struct.unpack('<I', data[offset + 8:offset + 12])[0]
            found += payloads(data[offset:offset + length], f'{name}-{i}')
            offset += length
        return found
    if magic not in (b'b3dm', b'i3dm'):
        return []
    if magic == b'i3dm' and struct.unpack('<I', data[28:32])[0] == 0:
        return []  # gltfFormat 0: the glTF is named by URI
    # The GLB follows the tables; early b3dm headers had other lengths, so find its magic.
    start = data.find(b'glTF', 20)
    return [(name, data[start:])] if start >= 0 else []


def main():
    folder, out = sys.argv[1], sys.argv[2]
    os.makedirs(out, exist_ok=True)
    written = 0
    for root, _, files in sorted(os.walk(folder)):
        for file in sorted(files):
            if not file.lower().endswith(('.b3dm', '.i3dm', '.cmpt')):
                continue
            path = os.path.join(root, file)
            name = os.path.relpath(path, folder).replace(os.sep, '_').rsplit('.', 1)[0]
            for tile, glb in payloads(open(path, 'rb').read(), name):
                if glb[4:8] == struct.pack('<I', 1):
                    open(os.path.join(out, tile + '.glb'), 'wb').write(glb)
                    written += 1
    print(f'{written} glTF 1.0 payload(s) written to {out}')


if __name__ == '__main__':
    main()
