#!/usr/bin/env -S python3 -u
"""Differential check against the Khronos glTF-Validator (npm, an oracle, never a dependency):
mutates the JSON of glTF 2.0 seeds structurally (a value replaced by a numeric extreme, a
wrong type or an empty container; a member deleted; an element appended), runs the validator
and `gltfmat check --profile khronos` on every mutant, and prints how many reports are equal
and the differences by kind, each with one example. Not a test: a way to find where the
Khronos profile departs from the validator on input nobody wrote by hand.

    python3 scripts/differential.py SEEDS_FOLDER [COUNT] [SEED] [target/release/gltfmat] [--edges | --images]

SEEDS_FOLDER is copied to a scratch folder (mutants sit beside their seed, so relative URIs
still resolve); e.g. ../shared/conformance/khronos-glTF-Validator. With --edges the mutations
go where hand-written edge cases and strangers' uploads probe: URIs of every form, data-URI
media types and padding, NaN and infinities in buffer data, animation samplers of 0-2 keys,
strides and offsets, sparse blocks, unknown members and extras on any object. With --images
the seeds are the folder's images (PNG, JPEG, WebP, KTX2) and each mutant is one of them cut
short or with bytes of its header changed, embedded in a buffer view: what a truncated
download or a broken exporter makes, read by each tool's image header reader.
"""
import base64, collections, json, math, os, random, shutil, struct, subprocess, sys, tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
NODE_MODULES = os.path.join(HERE, 'bench', 'node_modules')
EDGES = '--edges' in sys.argv
IMAGES = '--images' in sys.argv
ARGS = [a for a in sys.argv if a not in ('--edges', '--images')]
SEEDS = ARGS[1]
COUNT = int(ARGS[2]) if len(ARGS) > 2 else 300
RNG = random.Random(int(ARGS[3]) if len(ARGS) > 3 else 1)
EXE = os.path.abspath(ARGS[4] if len(ARGS) > 4 else 'target/release/gltfmat')
EXTREMES = [None, 0, -1, 1.5, -0.0, 2**31, 2**32, 2**53, 18446744073709551612, 1e308, -1e308,
            'x', '', True, [], {}, [1, 'a'], [None], {'a': 1}]
KHRONOS = r"""
const v = require('gltf-validator'); const fs = require('fs'); const path = require('path');
(async () => { const out = {};
  for (const f of JSON.parse(fs.readFileSync(0, 'utf8'))) {
    const dir = path.dirname(f);
    try {
      const r = await v.validateBytes(new Uint8Array(fs.readFileSync(f)), { uri: f, maxIssues: 0,
        externalResourceFunction: (u) => new Promise((ok, no) => fs.readFile(path.join(dir, decodeURIComponent(u)), (e, d) => e ? no(e) : ok(new Uint8Array(d)))) });
      out[f] = r.issues.messages.map(m => [m.code, m.pointer !== undefined ? m.pointer : '@' + m.offset]);
    } catch (e) { out[f] = null; }
  }
  console.log(JSON.stringify(out));
})();
"""


def places(value, at=()):
    yield at
    children = value.items() if isinstance(value, dict) else enumerate(value) if isinstance(value, list) else []
    for key, child in children:
        yield from places(child, at + (key,))


def mutate(document):
    for _ in range(RNG.randint(1, 3)):
        candidates = list(places(document))[1:]
        if not candidates:
            break
        at = RNG.choice(candidates)
        parent = document
        for key in at[:-1]:
            parent = parent[key]
        roll = RNG.random()
        if roll < 0.2 and isinstance(parent, dict):
            del parent[at[-1]]
        elif roll < 0.3 and isinstance(parent, list):
            parent.append(RNG.choice(EXTREMES))
        else:
            parent[at[-1]] = RNG.choice(EXTREMES)
    return document


URI_FORMS = ['/abs/x.bin', 'file:///tmp/x.bin', 'http://example.com/x.bin', 'C:\\x.bin', '//host/x.bin',
             'urn:x', '../x.bin', 'a%20b.bin', 'sub\\x.bin', '', '?q', '#f', 'x.bin?q=1#f', '%zz.bin',
             ':x', '1x:y']
MEDIA_TYPES = ['image/png', 'image/jpeg', 'image/webp', 'image/ktx2', 'image/basis', 'image/foo',
               'application/octet-stream', 'application/gltf-buffer', '', 'text/plain']
PNG_1x1 = base64.b64decode('iVBORw0KGgoAAAANSUhEUgAAAAEAAAABCAYAAAAfFcSJAAAADUlEQVR42mP8z8BQDwAEhQGAhKmMIQAAAABJRU5ErkJggg==')


def objects(value):
    """Every JSON object in the document."""
    if isinstance(value, dict):
        yield value
        for child in value.values():
            yield from objects(child)
    elif isinstance(value, list):
        for child in value:
            yield from objects(child)


def data_uri(payload, media, padding):
    text = base64.b64encode(payload).decode()
    text = {'keep': text, 'none': text.rstrip('='), 'extra': text + '=', 'broken': text[:-3]}[padding]
    return f'data:{media};base64,{text}'


def buffer_bytes(document, seed_dir, index):
    """The bytes of buffer `index` (a data URI or a file beside the seed), or None."""
    buffer = (document.get('buffers') or [None])[index] if index < len(document.get('buffers') or []) else None
    uri = buffer.get('uri') if isinstance(buffer, dict) else None
    if not isinstance(uri, str):
        return None
    if uri.startswith('data:') and ',' in uri:
        try:
            return bytearray(base64.b64decode(uri.split(',', 1)[1]))
        except ValueError:
            return None
    try:
        with open(os.path.join(seed_dir, uri), 'rb') as f:
            return bytearray(f.read())
    except OSError:
        return None


def mutate_edges(document, seed_dir):
    """One to three mutations where the validator's edge cases live."""
    for _ in range(RNG.randint(1, 3)):
        kind = RNG.choice(['uri', 'data-uri', 'float', 'sampler', 'stride', 'sparse', 'member'])
        resources = [r for key in ('buffers', 'images') for r in (document.get(key) or []) if isinstance(r, dict)]
        if kind == 'uri' and resources:
            RNG.choice(resources)['uri'] = RNG.choice(URI_FORMS)
        elif kind == 'data-uri' and document.get('images'):
            image = RNG.choice(document['images'])
            if isinstance(image, dict):
                image.pop('bufferView', None)
                image['uri'] = data_uri(PNG_1x1, RNG.choice(MEDIA_TYPES), RNG.choice(['keep', 'none', 'extra', 'broken']))
        elif kind == 'float' and document.get('buffers'):
            data = buffer_bytes(document, seed_dir, 0)
            if data and len(data) >= 4:
                for _ in range(RNG.randint(1, 4)):
                    at = RNG.randrange(0, len(data) // 4) * 4
                    data[at:at + 4] = struct.pack('<f', RNG.choice([math.nan, math.inf, -math.inf, 1e38, -0.0]))
                document['buffers'][0]['uri'] = data_uri(bytes(data), 'application/octet-stream', 'keep')
        elif kind == 'sampler':
            samplers = [s for a in (document.get('animations') or []) if isinstance(a, dict)
                        for s in (a.get('samplers') or []) if isinstance(s, dict)]
            accessors = document.get('accessors') or []
            if samplers:
                sampler = RNG.choice(samplers)
                sampler['interpolation'] = RNG.choice(['LINEAR', 'STEP', 'CUBICSPLINE'])
                index = sampler.get('input')
                if isinstance(index, int) and 0 <= index < len(accessors) and isinstance(accessors[index], dict):
                    accessors[index]['count'] = RNG.choice([0, 1, 2])
        elif kind == 'stride' and document.get('bufferViews'):
            view = RNG.choice(document['bufferViews'])
            if isinstance(view, dict):
                view['byteStride'] = RNG.choice([0, 1, 2, 3, 4, 6, 252, 256])
        elif kind == 'sparse' and document.get('accessors'):
            accessor = RNG.choice(document['accessors'])
            if isinstance(accessor, dict) and isinstance(accessor.get('count'), int) and accessor['count'] > 0:
                n = RNG.randint(1, 3)
                indices = [RNG.choice([0, accessor['count'] - 1, accessor['count'], 2**16]) for _ in range(n)]
                payload = struct.pack(f'<{n}I', *[i % 2**32 for i in indices]) + bytes(64 * n)
                document.setdefault('buffers', []).append({'uri': data_uri(payload, 'application/octet-stream', 'keep'),
                                                           'byteLength': len(payload)})
                b = len(document['buffers']) - 1
                document.setdefault('bufferViews', []).extend([{'buffer': b, 'byteLength': 4 * n},
                                                               {'buffer': b, 'byteOffset': 4 * n, 'byteLength': 64 * n}])
                v = len(document['bufferViews']) - 2
                accessor['sparse'] = {'count': n, 'indices': {'bufferView': v, 'componentType': 5125},
                                      'values': {'bufferView': v + 1}}
        elif kind == 'member':
            target = RNG.choice(list(objects(document)))
            key = RNG.choice(['extras', 'unknownMember', 'range', 'name'])
            target[key] = RNG.choice(EXTREMES)
    return document


IMAGE_TYPES = {'.png': 'image/png', '.jpg': 'image/jpeg', '.jpeg': 'image/jpeg', '.webp': 'image/webp',
               '.ktx2': 'image/ktx2'}
IMAGE_EXTENSIONS = {'image/webp': 'EXT_texture_webp', 'image/ktx2': 'KHR_texture_basisu'}


def mutate_image(data):
    """The image cut short, a few of its first bytes changed, or a run of them replaced or removed."""
    data = bytearray(data)
    head = max(1, min(len(data), 120))
    kind = RNG.random()
    if kind < 0.4:
        return bytes(data[:RNG.randrange(0, min(len(data), 400))])
    if kind < 0.8:
        for _ in range(RNG.randrange(1, 4)):
            data[RNG.randrange(0, min(head, 80))] = RNG.randrange(256)
        return bytes(data)
    at, n = RNG.randrange(0, head), RNG.randrange(1, 8)
    data[at:at + n] = bytes(RNG.randrange(256) for _ in range(n)) if RNG.random() < 0.5 else b''
    return bytes(data)


def image_document(data, media):
    """A glTF whose one image is `data` in a buffer view, its format's extension declared."""
    document = {'asset': {'version': '2.0'},
                'buffers': [{'byteLength': len(data), 'uri': data_uri(data, 'application/octet-stream', 'keep')}],
                'bufferViews': [{'buffer': 0, 'byteLength': len(data)}],
                'images': [{'bufferView': 0, 'mimeType': media}]}
    if not data:
        document = {'asset': {'version': '2.0'}, 'images': [{'uri': f'data:{media};base64,'}]}
    if media in IMAGE_EXTENSIONS:
        document['extensionsUsed'] = [IMAGE_EXTENSIONS[media]]
    return document


def make_mutant(seed, i):
    """Mutant `i` of `seed` (a glTF, or an image with --images) beside it, or None."""
    path = os.path.join(os.path.dirname(seed), f'mutant-{i}.gltf')
    if IMAGES:
        media = IMAGE_TYPES[os.path.splitext(seed)[1].lower()]
        mutant = image_document(mutate_image(open(seed, 'rb').read()), media)
    else:
        try:
            document = json.load(open(seed))
        except (ValueError, UnicodeDecodeError):
            return None
        if not isinstance(document, dict) or str(document.get('asset', {}).get('version')) != '2.0':
            return None
        try:
            mutant = mutate_edges(document, os.path.dirname(seed)) if EDGES else mutate(document)
        except (RecursionError, ValueError):
            # A seed nested deeper than Python recurses (the corpus has some), or a mutation
            # that put a value inside itself: not written.
            return None
    try:
        text = json.dumps(mutant)
    except (RecursionError, ValueError):
        return None
    with open(path, 'w') as f:
        f.write(text)
    return path


def validator_reports(mutants):
    """The validator's findings of each mutant. Its image readers crash the whole process on
    some broken images, so with --images each mutant gets a process of its own."""
    batches = [[m] for m in mutants] if IMAGES else [mutants]
    reports = {}
    for batch in batches:
        run = subprocess.run(['node', '-e', KHRONOS], input=json.dumps(batch), capture_output=True, text=True,
                             env={**os.environ, 'NODE_PATH': NODE_MODULES})
        try:
            reports.update(json.loads(run.stdout))
        except ValueError:
            pass
    return reports


def main():
    if not os.path.isdir(os.path.join(NODE_MODULES, 'gltf-validator')):
        subprocess.run(['npm', 'install', '--prefix', os.path.join(HERE, 'bench'), '--no-save', '--silent',
                        'gltf-validator', 'gltf-pipeline'], check=True, stdout=subprocess.DEVNULL)
    work = tempfile.mkdtemp(prefix='gltfmat-differential-')
    shutil.copytree(SEEDS, work, dirs_exist_ok=True)
    wanted = tuple(IMAGE_TYPES) if IMAGES else ('.gltf',)
    seeds = sorted(os.path.join(d, f) for d, _, names in os.walk(work) for f in names
                   if f.lower().endswith(wanted) and not f.startswith('mutant-'))
    if not seeds:
        shutil.rmtree(work)
        what = 'images (' + ', '.join(IMAGE_TYPES) + ')' if IMAGES else '.gltf files'
        sys.exit(f'differential.py: no {what} to mutate under {SEEDS}')
    mutants = [m for m in (make_mutant(RNG.choice(seeds), i) for i in range(COUNT)) if m]
    khronos = validator_reports(mutants)
    kinds, examples, equal, unchecked = collections.Counter(), {}, 0, 0
    for path in mutants:
        run = subprocess.run([EXE, 'check', path, '--profile', 'khronos', '--format', 'json', '--max-issues', '0'],
                             capture_output=True, text=True)
        if run.returncode not in (0, 1):
            kinds[('exit', run.returncode)] += 1
            examples.setdefault(('exit', run.returncode), (path, run.stderr[-200:]))
            continue
        if khronos.get(path) is None:
            # The validator threw on it (its own crashes on some hostile input): no oracle.
            unchecked += 1
            continue
        ours = collections.Counter((m['code'], m.get('pointer', '@%s' % m.get('offset')))
                                   for m in json.loads(run.stdout)['issues']['messages'])
        theirs = collections.Counter(map(tuple, khronos[path]))
        if ours == theirs:
            equal += 1
            continue
        for side, extra in (('only the validator', theirs - ours), ('only gltfmat', ours - theirs)):
            for finding in extra:
                kinds[(side, finding[0])] += 1
                examples.setdefault((side, finding[0]), (path, finding[1]))
    print(f'{equal} of {len(mutants)} reports equal, {unchecked} the validator could not check (mutants in {work})')
    for kind, n in kinds.most_common():
        print(f'{n:5}  {kind[0]:18} {kind[1]:55} e.g. {examples[kind][0]} {examples[kind][1]}')


if __name__ == '__main__':
    main()
