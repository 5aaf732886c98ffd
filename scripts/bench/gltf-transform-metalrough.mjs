// glTF-Transform's metalRough() (npm @gltf-transform/functions), run as an oracle for
// scripts/bench/vs-gltf-transform.sh: node gltf-transform-metalrough.mjs IN OUT
import { NodeIO } from '@gltf-transform/core';
import { ALL_EXTENSIONS } from '@gltf-transform/extensions';
import { metalRough } from '@gltf-transform/functions';

const [input, output] = process.argv.slice(2);
const io = new NodeIO().registerExtensions(ALL_EXTENSIONS);
const document = await io.read(input);
await document.transform(metalRough());
await io.write(output, document);
