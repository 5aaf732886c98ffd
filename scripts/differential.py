#!/usr/bin/env -S python3 -u
"""Differential check against the Khronos glTF-Validator (npm, an oracle, never a dependency):
mutates the JSON of glTF 2.0 seeds structurally (a value replaced by a numeric extreme, a
wrong type or an empty container; a member deleted; an element appended), runs the validator
and `gltfmat check --profile khronos` on every mutant, and prints how many reports are equal
and the differences by kind, each with one example. Not a test: a way to find where the
Khronos profile departs from the validator on input nobody wrote by hand.

    python3 scripts/differential.py SEEDS_FOLDER [COUNT] [SEED] [target/release/gltfmat]

SEEDS_FOLDER is copied to a scratch folder (mutants sit beside their seed, so relative URIs
still resolve); e.g. ../shared/conformance/khronos-glTF-Validator.
"""
import collections, json, os, random, shutil, subprocess, sys, tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
NODE_MODULES = os.path.join(HERE, 'bench', 'node_modules')
SEEDS = sys.argv[1]
COUNT = int(sys.argv[2]) if len(sys.argv) > 2 else 300
RNG = random.Random(int(sys.argv[3]) if len(sys.argv) > 3 else 1)
EXE = os.path.abspath(sys.argv[4] if len(sys.argv) > 4 else 'target/release/gltfmat')
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


def main():
    if not os.path.isdir(os.path.join(NODE_MODULES, 'gltf-validator')):
        subprocess.run(['npm', 'install', '--prefix', os.path.join(HERE, 'bench'), '--no-save', '--silent',
                        'gltf-validator', 'gltf-pipeline'], check=True, stdout=subprocess.DEVNULL)
    work = tempfile.mkdtemp(prefix='gltfmat-differential-')
    shutil.copytree(SEEDS, work, dirs_exist_ok=True)
    seeds = [os.path.join(d, f) for d, _, names in os.walk(work) for f in names if f.endswith('.gltf')]
    mutants = []
    for i in range(COUNT):
        seed = RNG.choice(seeds)
        try:
            document = json.load(open(seed))
        except (ValueError, UnicodeDecodeError):
            continue
        if not isinstance(document, dict) or str(document.get('asset', {}).get('version')) != '2.0':
            continue
        path = os.path.join(os.path.dirname(seed), f'mutant-{i}.gltf')
        with open(path, 'w') as f:
            json.dump(mutate(document), f)
        mutants.append(path)
    khronos = json.loads(subprocess.run(['node', '-e', KHRONOS], input=json.dumps(mutants), capture_output=True,
                                        text=True, env={**os.environ, 'NODE_PATH': NODE_MODULES}).stdout)
    kinds, examples, equal = collections.Counter(), {}, 0
    for path in mutants:
        run = subprocess.run([EXE, 'check', path, '--profile', 'khronos', '--format', 'json', '--max-issues', '0'],
                             capture_output=True, text=True)
        if run.returncode not in (0, 1):
            kinds[('exit', run.returncode)] += 1
            examples.setdefault(('exit', run.returncode), (path, run.stderr[-200:]))
            continue
        if khronos.get(path) is None:
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
    print(f'{equal} of {len(mutants)} reports equal (mutants in {work})')
    for kind, n in kinds.most_common():
        print(f'{n:5}  {kind[0]:18} {kind[1]:55} e.g. {examples[kind][0]} {examples[kind][1]}')


if __name__ == '__main__':
    main()
