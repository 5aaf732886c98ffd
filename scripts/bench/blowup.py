#!/usr/bin/env -S python3 -u
"""Time and peak memory of gltfmat on every input class that once blew up (issue 13,
findings 11-15), each at N and 10·N. Prints one row per class: seconds and peak RSS at both
sizes and their growth; near-linear means growth ≲ 15× for 10× N.

    python3 scripts/bench/blowup.py [target/release/gltfmat] [--only NAME]

Each input is generated into a scratch folder; nothing here is a test (no assertion on time).
"""
import base64, json, os, struct, subprocess, sys, tempfile, time, zlib

ONLY = sys.argv[sys.argv.index('--only') + 1] if '--only' in sys.argv else None
# The executable: the first argument that is neither an option nor --only's value.
POSITIONAL = [a for i, a in enumerate(sys.argv[1:], 1) if not a.startswith('--') and sys.argv[i - 1] != '--only']
EXE = os.path.abspath(POSITIONAL[0] if POSITIONAL else 'target/release/gltfmat')
WORK = tempfile.mkdtemp(prefix='gltfmat-blowup-')


def asset(**fields):
    return {'asset': {'version': '2.0'}, **fields}


def write(name, doc):
    path = os.path.join(WORK, name)
    with open(path, 'wb') as f:
        f.write(doc if isinstance(doc, bytes) else json.dumps(doc).encode())
    return path


def node_chain(n):
    nodes = [{'children': [i + 1]} for i in range(n - 1)] + [{}]
    return write(f'chain-{n}.gltf', asset(nodes=nodes, scenes=[{'nodes': [0]}]))


def skin_joints(n):
    nodes = [{'children': [i + 1]} for i in range(n - 1)] + [{}]
    return write(f'skin-{n}.gltf', asset(nodes=nodes, skins=[{'joints': list(range(n))}]))


def duplicate_keys(n):
    text = '{"asset":{"version":"2.0"},"extras":{' + ','.join('"k":0' for _ in range(n)) + '}}'
    return write(f'keys-{n}.gltf', text.encode())


def duplicate_scene_nodes(n):
    nodes = [{} for _ in range(n)]
    return write(f'scene-nodes-{n}.gltf', asset(nodes=nodes, scenes=[{'nodes': list(range(n)) + [0]}]))


def meshes_and_nodes(n):
    mesh = {'primitives': [{'attributes': {}}]}
    return write(f'meshes-{n}.gltf', asset(meshes=[mesh] * n, nodes=[{'mesh': i} for i in range(n)]))


def shared_texture(n):
    png = tiny_png()
    images = [{'uri': 'data:image/png;base64,' + base64.b64encode(png).decode()}]
    materials = [{'pbrMetallicRoughness': {'baseColorTexture': {'index': 0}}} if i % 2 else
                 {'normalTexture': {'index': 0}} for i in range(n)]
    return write(f'texture-{n}.gltf', asset(images=images, textures=[{'source': 0}], materials=materials))


def animation_targets(n):
    channels = [{'sampler': 0, 'target': {'node': 0, 'path': 'translation'}} for _ in range(n)]
    data = base64.b64encode(struct.pack('<f', 0) + struct.pack('<3f', 0, 0, 0)).decode()
    doc = asset(
        nodes=[{}],
        buffers=[{'uri': 'data:application/octet-stream;base64,' + data, 'byteLength': 16}],
        bufferViews=[{'buffer': 0, 'byteLength': 4}, {'buffer': 0, 'byteOffset': 4, 'byteLength': 12}],
        accessors=[{'bufferView': 0, 'componentType': 5126, 'count': 1, 'type': 'SCALAR', 'min': [0], 'max': [0]},
                   {'bufferView': 1, 'componentType': 5126, 'count': 1, 'type': 'VEC3'}],
        animations=[{'channels': channels, 'samplers': [{'input': 0, 'output': 1}]}])
    return write(f'channels-{n}.gltf', doc)


def empty_materials(n):
    text = '{"asset":{"version":"2.0"},"materials":[' + ','.join('{}' for _ in range(n)) + ']}'
    return write(f'materials-{n}.gltf', text.encode())


def empty_chunks(n):
    json_chunk = b'{"asset":{"version":"2.0"}}'
    json_chunk += b' ' * (-len(json_chunk) % 4)
    body = struct.pack('<I', len(json_chunk)) + b'JSON' + json_chunk
    body += (struct.pack('<I', 0) + b'XTRA') * n
    return write(f'chunks-{n}.glb', b'glTF' + struct.pack('<II', 2, 12 + len(body)) + body)


def zeros(n):
    return write(f'zeros-{n}.gltf', ('{"asset":{"version":"2.0"},"nodes":[' + ','.join('0' for _ in range(n)) + ']}').encode())


def many_findings(n):
    # One finding per node (a non-unit quaternion), each on its own line.
    nodes = [{'rotation': [1, 1, 1, 1]} for _ in range(n)]
    return write(f'findings-{n}.gltf', json.dumps(asset(nodes=nodes), indent=1).encode())


def many_findings_minified(n):
    # The same findings on one line (a minified file): each snippet once decoded the line.
    nodes = [{'rotation': [1, 1, 1, 1]} for _ in range(n)]
    return write(f'findings-min-{n}.gltf', json.dumps(asset(nodes=nodes)).encode())


def spec_gloss_materials(n):
    # N glTF 2.0 spec-gloss materials for `upgrade`, two of every three alike.
    sg = 'KHR_materials_pbrSpecularGlossiness'
    materials = [{'extensions': {sg: {'diffuseFactor': [0.5, 0.4, 0.3, 1], 'specularFactor': [0.1 + (i % 3) / 10] * 3,
                                      'glossinessFactor': 0.6}}} for i in range(n)]
    return write(f'spec-gloss-{n}.gltf', asset(materials=materials, extensionsUsed=[sg]))


def distinct_materials(n):
    # N materials, each its own roughness and colour, for `compare` of the asset with itself.
    materials = [{'pbrMetallicRoughness': {'roughnessFactor': (i % 997) / 997,
                                           'baseColorFactor': [(i % 101) / 101, 0.5, 0.5, 1]}} for i in range(n)]
    return write(f'distinct-materials-{n}.gltf', asset(materials=materials))


def joint_names(n):
    nodes = {f'j{i}': ({'jointName': f'J{i}', 'children': [f'j{i + 1}']} if i + 1 < n else {'jointName': f'J{i}'})
             for i in range(n)}
    nodes['root'] = {'children': ['j0']}
    doc = {'asset': {'version': '1.0'}, 'nodes': nodes,
           'skins': {'s': {'jointNames': [f'J{i}' for i in range(n)],
                           'inverseBindMatrices': 'ibm', 'bindShapeMatrix': [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]}},
           'buffers': {'b': {'uri': 'data:application/octet-stream;base64,' +
                             base64.b64encode(struct.pack('<16f', *[1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]) * n).decode(),
                             'byteLength': 64 * n}},
           'bufferViews': {'v': {'buffer': 'b', 'byteLength': 64 * n}},
           'accessors': {'ibm': {'bufferView': 'v', 'componentType': 5126, 'count': n, 'type': 'MAT4'}},
           'scenes': {'s': {'nodes': ['root']}}, 'scene': 's'}
    return write(f'joints-{n}.gltf', doc)


def declared_extensions(n):
    """n extensions declared, required and each used once: every lookup once searched the list."""
    names = [f'X_e{i}' for i in range(n)]
    return write(f'extensions-{n}.gltf', asset(extensionsUsed=names, extensionsRequired=names,
                                              nodes=[{'extensions': {name: {}}} for name in names]))


def undeclared_extensions(n):
    """One node with n extension objects no `extensionsUsed` declares: each was taken out of
    the tree by a walk over the object's members."""
    return write(f'undeclared-{n}.gltf', asset(extensionsUsed=['X_a'],
                                               nodes=[{'extensions': {f'X_k{i}': {} for i in range(n)}}]))


def undeclared_extensions_seen_before(n):
    """As undeclared_extensions, but every name is written before (in `extras`, shuffled) and
    the object's keys come in another order: its members are indexed, not found in place."""
    import random
    names = [f'X_k{i}' for i in range(n)]
    random.Random(1).shuffle(names)
    written = names[:]
    random.Random(2).shuffle(written)
    return write(f'undeclared-seen-{n}.gltf', asset(extensionsUsed=['X_a'], extras=names,
                                                    nodes=[{'extensions': {name: {} for name in written}}]))


def gltf1_meshes(n):
    """A 1.0 asset of n meshes, each with its own accessor into one buffer: each repacked
    accessor once summed the lengths of all before it."""
    positions = struct.pack('<9f', 0, 0, 0, 1, 0, 0, 0, 1, 0)
    uri = 'data:application/octet-stream;base64,' + base64.b64encode(positions).decode()
    doc = {'asset': {'version': '1.0'}, 'buffers': {'b': {'uri': uri, 'byteLength': 36}},
           'bufferViews': {'v': {'buffer': 'b', 'byteOffset': 0, 'byteLength': 36, 'target': 34962}},
           'accessors': {f'a{i}': {'bufferView': 'v', 'byteOffset': 0, 'componentType': 5126, 'count': 3, 'type': 'VEC3',
                                   'min': [0, 0, 0], 'max': [1, 1, 0]} for i in range(n)},
           'meshes': {f'm{i}': {'primitives': [{'attributes': {'POSITION': f'a{i}'}, 'mode': 4}]} for i in range(n)},
           'nodes': {f'n{i}': {'meshes': [f'm{i}']} for i in range(n)},
           'scenes': {'s': {'nodes': [f'n{i}' for i in range(n)]}}, 'scene': 's'}
    return write(f'gltf1-meshes-{n}.gltf', doc)


def primitives_of_one_material(n):
    """One textured material drawn by n primitives, each with its own texture coordinates: the
    comparison's mesh reader once looked through the primitives read so far for each one."""
    uvs = b''.join(struct.pack('<6f', 0.1 + i * 1e-7, 0.1, 0.2, 0.1, 0.1, 0.2) for i in range(n))
    data = struct.pack('<9f', 0, 0, 0, 1, 0, 0, 0, 1, 0) + uvs
    uri = 'data:application/octet-stream;base64,' + base64.b64encode(data).decode()
    accessors = [{'bufferView': 0, 'componentType': 5126, 'count': 3, 'type': 'VEC3', 'min': [0, 0, 0], 'max': [1, 1, 0]}]
    accessors += [{'bufferView': 1, 'byteOffset': 24 * i, 'componentType': 5126, 'count': 3, 'type': 'VEC2'} for i in range(n)]
    primitives = [{'attributes': {'POSITION': 0, 'TEXCOORD_0': i + 1}, 'material': 0} for i in range(n)]
    return write(f'primitives-{n}.gltf', asset(
        buffers=[{'uri': uri, 'byteLength': len(data)}],
        bufferViews=[{'buffer': 0, 'byteLength': 36}, {'buffer': 0, 'byteOffset': 36, 'byteLength': len(uvs)}],
        accessors=accessors, images=[{'uri': 'data:image/png;base64,' + base64.b64encode(tiny_png()).decode()}], textures=[{'source': 0}],
        materials=[{'pbrMetallicRoughness': {'baseColorTexture': {'index': 0}}}],
        meshes=[{'primitives': primitives}], nodes=[{'mesh': 0}], scenes=[{'nodes': [0]}], scene=0))


def unknown_extension_bindings(n):
    """One material whose extension the checker does not read holds n texture bindings, each
    on its own texCoord set, and n primitives draw it: the sets they read reach every
    primitive."""
    bindings = {f'layer{i}Texture': {'index': 0, 'texCoord': i} for i in range(n)}
    data = struct.pack('<9f', 0, 0, 0, 1, 0, 0, 0, 1, 0)
    uri = 'data:application/octet-stream;base64,' + base64.b64encode(data).decode()
    primitives = [{'attributes': {'POSITION': 0, 'TEXCOORD_0': 1}, 'material': 0} for _ in range(n)]
    return write(f'unknown-bindings-{n}.gltf', asset(
        extensionsUsed=['VENDOR_materials_layers'],
        buffers=[{'uri': uri, 'byteLength': len(data)}], bufferViews=[{'buffer': 0, 'byteLength': 36}],
        accessors=[{'bufferView': 0, 'componentType': 5126, 'count': 3, 'type': 'VEC3', 'min': [0, 0, 0], 'max': [1, 1, 0]},
                   {'bufferView': 0, 'componentType': 5126, 'count': 3, 'type': 'VEC2'}],
        images=[{'uri': 'data:image/png;base64,' + base64.b64encode(tiny_png()).decode()}], textures=[{'source': 0}],
        materials=[{'extensions': {'VENDOR_materials_layers': bindings}}],
        meshes=[{'primitives': primitives}], nodes=[{'mesh': 0}], scenes=[{'nodes': [0]}], scene=0))


def aliasing_accessors(n):
    """n NORMAL accessors over the same 10^4 zero vectors: n·10^4 findings from a small file."""
    count = 10_000
    data = 'data:application/octet-stream;base64,' + base64.b64encode(bytes(12 * count)).decode()
    accessors = [{'bufferView': 0, 'componentType': 5126, 'count': count, 'type': 'VEC3', 'min': [0, 0, 0], 'max': [0, 0, 0]}]
    accessors += [{'bufferView': 0, 'componentType': 5126, 'count': count, 'type': 'VEC3'} for _ in range(n)]
    primitives = [{'attributes': {'POSITION': 0, 'NORMAL': i + 1}, 'mode': 0} for i in range(n)]
    return write(f'aliasing-{n}.gltf', asset(
        buffers=[{'uri': data, 'byteLength': 12 * count}],
        bufferViews=[{'buffer': 0, 'byteLength': 12 * count, 'byteStride': 12, 'target': 34962}],
        accessors=accessors, meshes=[{'primitives': primitives}], nodes=[{'mesh': 0}], scenes=[{'nodes': [0]}], scene=0))


def folder_of_assets(n):
    """A folder of n small assets, each with a finding: a CI gate's walk of a repository."""
    folder = os.path.join(WORK, f'folder-{n}')
    os.makedirs(folder, exist_ok=True)
    text = json.dumps(asset(nodes=[{'rotation': [1, 1, 1, 1]}] * 50)).encode()
    for i in range(n):
        with open(os.path.join(folder, f'a{i}.gltf'), 'wb') as f:
            f.write(text)
    return folder


def big_png_references(n):
    """One 8192² PNG (a few hundred KB compressed) as n images, each with its material."""
    with open(os.path.join(WORK, 'big.png'), 'wb') as f:
        f.write(big_png(8192))
    images = [{'uri': 'big.png'} for _ in range(n)]
    textures = [{'source': i} for i in range(n)]
    materials = [{'name': f'm{i}', 'pbrMetallicRoughness': {'baseColorTexture': {'index': i}}} for i in range(n)]
    return write(f'png-{n}.gltf', asset(images=images, textures=textures, materials=materials))


def buffers_naming_one_file(n):
    """n buffers naming one 1 MB file, each with its view and accessor: each buffer once read
    the file again and held its own copy."""
    with open(os.path.join(WORK, 'one.bin'), 'wb') as f:
        f.write(bytes(1 << 20))
    buffers = [{'uri': 'one.bin', 'byteLength': 1 << 20} for _ in range(n)]
    views = [{'buffer': i, 'byteLength': 1 << 20} for i in range(n)]
    accessors = [{'bufferView': i, 'componentType': 5126, 'count': (1 << 20) // 12, 'type': 'VEC3'} for i in range(n)]
    return write(f'one-file-{n}.gltf', asset(buffers=buffers, bufferViews=views, accessors=accessors))


def spec_gloss_over_one_image(n, distinct):
    """n spec-gloss materials over one 2048² PNG: each reading its own texture of it (once
    proved one by one), or all one texture with n diffuse factors (each proof held its 16 MB
    per-texel map)."""
    with open(os.path.join(WORK, 'sg.png'), 'wb') as f:
        f.write(big_png(2048))
    textures = 1 if distinct else n
    materials = [{'extensions': {'KHR_materials_pbrSpecularGlossiness': {
        'diffuseTexture': {'index': 0 if distinct else i},
        'diffuseFactor': [1, 1, 1 - i / (10 * n) if distinct else 1, 1]}}} for i in range(n)]
    doc = asset(extensionsUsed=['KHR_materials_pbrSpecularGlossiness'], images=[{'uri': 'sg.png'}] * textures,
                textures=[{'source': i} for i in range(textures)], materials=materials)
    return write(f'sg-{"distinct" if distinct else "alike"}-{n}.gltf', doc)


def png_chunk(kind, data):
    return struct.pack('>I', len(data)) + kind + data + struct.pack('>I', zlib.crc32(kind + data))


def encode_png(size, rows):
    header = struct.pack('>IIBBBBB', size, size, 8, 2, 0, 0, 0)
    return b'\x89PNG\r\n\x1a\n' + png_chunk(b'IHDR', header) + png_chunk(b'IDAT', zlib.compress(rows, 9)) + png_chunk(b'IEND', b'')


def tiny_png():
    return encode_png(1, b'\x00\xff\x00\x00')


def big_png(size):
    return encode_png(size, (b'\x00' + b'\x80' * (3 * size)) * size)


def samplers_sharing_input(n):
    """n samplers of one animation reading one 1000-key input, each driving its own node: the
    input's checks (increasing, bounds) once ran per sampler."""
    keys = 1000
    times = struct.pack(f'<{keys}f', *range(keys))
    values = struct.pack(f'<{3 * keys}f', *([0.0] * 3 * keys))
    data = base64.b64encode(times + values).decode()
    doc = asset(
        nodes=[{} for _ in range(n)],
        buffers=[{'uri': 'data:application/octet-stream;base64,' + data, 'byteLength': len(times) + len(values)}],
        bufferViews=[{'buffer': 0, 'byteLength': len(times)}, {'buffer': 0, 'byteOffset': len(times), 'byteLength': len(values)}],
        accessors=[{'bufferView': 0, 'componentType': 5126, 'count': keys, 'type': 'SCALAR', 'min': [0], 'max': [keys - 1]},
                   {'bufferView': 1, 'componentType': 5126, 'count': keys, 'type': 'VEC3'}],
        animations=[{'channels': [{'sampler': i, 'target': {'node': i, 'path': 'translation'}} for i in range(n)],
                     'samplers': [{'input': 0, 'output': 1} for _ in range(n)]}])
    return write(f'samplers-{n}.gltf', doc)


def gltf1_aliasing_accessors(n):
    """A 1.0 asset of n accessors over one 10^4-vertex bufferView, each its own mesh: the view
    was walked once per accessor."""
    count = 10_000
    positions = struct.pack(f'<{3 * count}f', *([0.0, 1.0, 2.0] * count))
    uri = 'data:application/octet-stream;base64,' + base64.b64encode(positions).decode()
    doc = {'asset': {'version': '1.0'}, 'buffers': {'b': {'uri': uri, 'byteLength': len(positions)}},
           'bufferViews': {'v': {'buffer': 'b', 'byteOffset': 0, 'byteLength': len(positions), 'target': 34962}},
           'accessors': {f'a{i}': {'bufferView': 'v', 'byteOffset': 0, 'componentType': 5126, 'count': count, 'type': 'VEC3',
                                   'min': [0, 1, 2], 'max': [0, 1, 2]} for i in range(n)},
           'meshes': {f'm{i}': {'primitives': [{'attributes': {'POSITION': f'a{i}'}, 'mode': 0}]} for i in range(n)},
           'nodes': {f'n{i}': {'meshes': [f'm{i}']} for i in range(n)},
           'scenes': {'s': {'nodes': [f'n{i}' for i in range(n)]}}, 'scene': 's'}
    return write(f'gltf1-aliasing-{n}.gltf', doc)


def distinct_strings(n):
    """n distinct strings in extras: each held by the tree's string store."""
    text = '{"asset":{"version":"2.0"},"extras":[' + ','.join(f'"s{i:x}"' for i in range(n)) + ']}'
    return write(f'strings-{n}.gltf', text.encode())


def grey_alpha_png(width, height):
    header = struct.pack('>IIBBBBB', width, height, 8, 4, 0, 0, 0)
    rows = (b'\x00' + b'\x80\xff' * width) * height
    return b'\x89PNG\r\n\x1a\n' + png_chunk(b'IHDR', header) + png_chunk(b'IDAT', zlib.compress(rows, 9)) + png_chunk(b'IEND', b'')


def spec_gloss_textures(name, diffuse, specular):
    """A 2.0 spec-gloss material with the given diffuse and spec-gloss PNGs (bytes or None)."""
    images, ext = [], {}
    for key, png in (('diffuseTexture', diffuse), ('specularGlossinessTexture', specular)):
        if png is not None:
            ext[key] = {'index': len(images)}
            images.append({'uri': 'data:image/png;base64,' + base64.b64encode(png).decode()})
    doc = asset(extensionsUsed=['KHR_materials_pbrSpecularGlossiness'], images=images,
                textures=[{'source': i} for i in range(len(images))],
                materials=[{'extensions': {'KHR_materials_pbrSpecularGlossiness': ext}}])
    return write(name, doc)


def grey_alpha_rebake(n):
    """One n-texel square grey+alpha PNG (a few hundred KB at 16384²) as a spec-gloss diffuse."""
    side = int(n ** 0.5)
    return spec_gloss_textures(f'grey-alpha-{n}.gltf', grey_alpha_png(side, side), None)


def crossed_strips(n):
    """A diffuse n×1 and a spec-gloss 1×n: a rebake on the finer grid of both is n²."""
    return spec_gloss_textures(f'strips-{n}.gltf', grey_alpha_png(n, 1), grey_alpha_png(1, n))


def gltf1_draft_shared_textures(n):
    """A 1.0 EXT_materials_pbr spec-gloss material whose diffuse and spec-gloss textures are
    two n-texel PNGs, each also bound by a second material."""
    side = int(n ** 0.5)
    uri = lambda png: 'data:image/png;base64,' + base64.b64encode(png).decode()
    values = lambda gloss: {'diffuseFactor': [0.6, 0.5, 0.4, 1], 'specularFactor': [0.2, 0.2, 0.2], 'glossinessFactor': gloss,
                            'diffuseTexture': 't0', 'specularGlossinessTexture': 't1'}
    doc = {'asset': {'version': '1.0'}, 'extensionsUsed': ['EXT_materials_pbr'],
           'images': {'i0': {'uri': uri(grey_alpha_png(side, side))}, 'i1': {'uri': uri(grey_alpha_png(side, side))}},
           'samplers': {'s': {}}, 'textures': {'t0': {'source': 'i0', 'sampler': 's'}, 't1': {'source': 'i1', 'sampler': 's'}},
           'materials': {f'm{k}': {'extensions': {'EXT_materials_pbr': {'materialModel': 'PBR_specular_glossiness',
                                                                       'values': values(0.5 + k / 10)}}} for k in range(2)},
           'scenes': {'s': {'nodes': []}}, 'scene': 's'}
    return write(f'gltf1-shared-{n}.gltf', doc)


def spec_gloss_sharing_texture(n):
    """n alike spec-gloss materials binding one 1024² diffuse: one rebake serves them all."""
    png = grey_alpha_png(1024, 1024)
    materials = [{'name': f'm{i}', 'extensions': {'KHR_materials_pbrSpecularGlossiness': {
        'diffuseTexture': {'index': 0}, 'specularGlossinessTexture': {'index': 0}, 'specularFactor': [0.2, 0.2, 0.2]}}}
                 for i in range(n)]
    doc = asset(extensionsUsed=['KHR_materials_pbrSpecularGlossiness'],
                images=[{'uri': 'data:image/png;base64,' + base64.b64encode(png).decode()}],
                textures=[{'source': 0}], materials=materials)
    return write(f'sg-sharing-{n}.gltf', doc)


CLASSES = [
    # name, generator, N, command
    ('node chain (11)', node_chain, 10_000, ['check']),
    ('skin joints (11)', skin_joints, 3_000, ['check']),
    ('duplicate keys (11)', duplicate_keys, 10_000, ['check']),
    ('scene node list (11)', duplicate_scene_nodes, 10_000, ['check']),
    ('meshes x nodes (11)', meshes_and_nodes, 3_000, ['check']),
    ('shared texture (11)', shared_texture, 10_000, ['check']),
    ('1.0 joint names (11)', joint_names, 2_000, ['upgrade', '-o', os.path.join(WORK, 'out.glb'), '--force']),
    ('one target, N channels (12)', animation_targets, 10_000, ['check', '--max-issues', '10']),
    ('empty materials (13)', empty_materials, 100_000, ['check', '--max-issues', '10']),
    ('empty GLB chunks (13)', empty_chunks, 100_000, ['check', '--max-issues', '10']),
    ('declared extensions (11)', declared_extensions, 10_000, ['check']),
    ('undeclared extension objects (11)', undeclared_extensions, 100_000, ['check', '--max-issues', '10']),
    ('undeclared extensions, keys seen before (11)', undeclared_extensions_seen_before, 100_000, ['check', '--max-issues', '10']),
    ('1.0 meshes, upgrade (11)', gltf1_meshes, 10_000, ['upgrade', '-o', os.path.join(WORK, 'meshes.glb'), '--force']),
    ('array of zeros (13)', zeros, 1_000_000, ['check', '--max-issues', '10']),
    ('accessors aliasing one view (13)', aliasing_accessors, 100, ['check', '--max-issues', '0']),
    ('human findings (14)', many_findings, 3_000, ['check', '--format', 'human']),
    ('sarif findings (14)', many_findings, 3_000, ['check', '--format', 'sarif']),
    ('human findings, one line', many_findings_minified, 3_000, ['check', '--format', 'human']),
    ('2.0 spec-gloss materials, upgrade with proof', spec_gloss_materials, 10_000, ['upgrade', '-o', os.path.join(WORK, 'sg.glb'), '--force']),
    ('folder of N assets, sarif', folder_of_assets, 1_000, ['check', '--format', 'sarif']),
    ('buffers naming one 1 MB file (15)', buffers_naming_one_file, 100, ['check']),
    ('spec-gloss, own texture of one 2048² PNG, proof (15)', lambda n: spec_gloss_over_one_image(n, False), 10,
     ['upgrade', '-o', os.path.join(WORK, 'sg-alike.glb'), '--force']),
    ('spec-gloss, distinct, one 2048² texture, proof (15)', lambda n: spec_gloss_over_one_image(n, True), 2,
     ['upgrade', '-o', os.path.join(WORK, 'sg-distinct.glb'), '--force']),
    ('8192² PNG, N references (15)', big_png_references, 1, ['render', '--all', '--size', '64', '-o', os.path.join(WORK, 'sheet.png'), '--force']),
    ('N samplers sharing one input (49)', samplers_sharing_input, 3_000, ['check']),
    ('1.0 accessors aliasing one view (49)', gltf1_aliasing_accessors, 300, ['upgrade', '-o', os.path.join(WORK, 'alias.glb'), '--force', '--no-verify']),
    ('repeated keys, json (49)', duplicate_keys, 100_000, ['check', '--format', 'json', '--all-findings']),
    ('distinct strings (49)', distinct_strings, 1_600_000, ['check']),
    ('findings, json (49)', many_findings, 30_000, ['check', '--format', 'json']),
    ('findings, github (49)', many_findings, 30_000, ['check', '--format', 'github']),
    ('findings, sarif (49)', many_findings, 30_000, ['check', '--format', 'sarif']),
    ('findings, human --all-findings (49)', many_findings, 30_000, ['check', '--all-findings']),
    ('grey+alpha PNG rebake, N texels (49)', grey_alpha_rebake, 1 << 20, ['upgrade', '-o', os.path.join(WORK, 'ga.glb'), '--force']),
    ('crossed strips rebake, N wide (49)', crossed_strips, 1638, ['upgrade', '-o', os.path.join(WORK, 'strips.glb'), '--force']),
    ('1.0 draft, shared textures, N texels (49)', gltf1_draft_shared_textures, 1 << 18, ['upgrade', '-o', os.path.join(WORK, 'shared.glb'), '--force']),
    ('N spec-gloss sharing one 1024² (49)', spec_gloss_sharing_texture, 20, ['upgrade', '-o', os.path.join(WORK, 'sharing.glb'), '--force']),
    ('N materials, compare with itself', distinct_materials, 1_000, ['compare', '{input}', '--format', 'json']),
    ('one material, N primitives, compare with itself', primitives_of_one_material, 20_000, ['compare', '{input}', '--format', 'json']),
    ('N bindings in an unknown extension, N primitives', unknown_extension_bindings, 10_000, ['check', '--max-issues', '10']),
]


def size_of(path):
    if os.path.isdir(path):
        return sum(os.path.getsize(os.path.join(path, name)) for name in os.listdir(path))
    return os.path.getsize(path)


def run(command, path):
    rest = [path if arg == '{input}' else arg for arg in command[1:]]
    args = [EXE, command[0], path, '--quiet'] + rest if command[0] == 'check' else [EXE, command[0], path] + rest
    best = None
    for _ in range(3):
        started = time.perf_counter()
        # The report is discarded as it is written: holding a 1 GB report here would time this
        # script's memory, not gltfmat.
        proc = subprocess.run(['/usr/bin/time', '-f', '%M'] + args, stdout=subprocess.DEVNULL,
                              stderr=subprocess.PIPE, timeout=900)
        # Each run writes its output anew (the inputs stay: an input may be a .glb too).
        for out in (command[i + 1] for i, arg in enumerate(command) if arg == '-o'):
            if os.path.exists(out):
                os.remove(out)
        seconds = time.perf_counter() - started
        kb = int(proc.stderr.decode().strip().splitlines()[-1])
        if proc.returncode not in (0, 1):
            return None, None, proc.stderr.decode()[-300:]
        if best is None or seconds < best[0]:
            best = (seconds, kb)
    return best[0], best[1], None


def main():
    sys.stdout.reconfigure(line_buffering=True)
    print(f'{"class":32} {"N":>9} {"s":>7} {"MB":>6} {"10N s":>7} {"MB":>6} {"time x":>7} {"mem x":>6}')
    for name, generate, n, command in CLASSES:
        if ONLY and ONLY not in name:
            continue
        row = []
        for size in (n, 10 * n):
            path = generate(size)
            seconds, kb, failure = run(command, path)
            if failure:
                print(f'{name:32} failed: {failure}')
                break
            row.append((seconds, kb, size_of(path)))
        else:
            (s1, k1, _), (s2, k2, b2) = row
            print(f'{name:32} {n:>9} {s1:7.2f} {k1 / 1024:6.0f} {s2:7.2f} {k2 / 1024:6.0f} {s2 / s1:7.1f} {k2 / k1:6.1f}'
                  f'   (10N input {b2 / 1e6:.1f} MB)')


if __name__ == '__main__':
    main()
