//! External resources of an asset that has no folder to read them from (emitted by the
//! resource pass).

use super::{Rule, Run};
use crate::check::pass_codes::EXTERNAL_RESOURCE_NOT_READ;

pub(crate) const RULE: Rule = Rule::documenting(
    EXTERNAL_RESOURCE_NOT_READ,
    "resources",
    "An external buffer or image was not read, so it was not checked: the asset came without a folder (stdin, or bytes in memory).",
    DOC,
    Run::CORE,
);

const DOC: &str = "\
## What it does
Reports each relative `uri` of a buffer or image when the asset was given without a folder to
resolve it in: read from stdin without `--stdin-filename`, or checked from bytes in memory
with no resource loader. Nothing that depends on the resource (its length, accessor data,
image headers, pixel rules) was checked.

## Why
A gate that silently skips half an asset passes assets it never looked at. Saying so tells the
user to name the input (`--stdin-filename PATH`) so its resources are read beside it.

## Example
`cat scene.gltf | gltfmat check -` where scene.gltf names `scene.bin`.
";
