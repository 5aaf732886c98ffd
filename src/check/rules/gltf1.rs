//! glTF 1.0 input: recognised and pointed at `gltfmat upgrade`.

use crate::check::context::Context;

pub const DOC: &str = "\
## What it does
Recognises a glTF 1.0 document (`asset.version` \"1.0\", or a GLB with version 1) and tells the
user to convert it with `gltfmat upgrade`.

## Why
glTF 1.0 is not loadable by today's engines; its objects are keyed by id and its materials
are shader techniques. Reporting hundreds of 2.0 schema errors would hide the one fix.

## Example
```json
{\"asset\": {\"version\": \"1.0\"}, \"materials\": {\"mat\": {\"technique\": \"t\"}}}
```
";

pub fn check(ctx: &mut Context) {
    ctx.emit(
        "GLTF_1_0_ASSET",
        "/asset/version",
        "This is a glTF 1.0 asset. Run `gltfmat upgrade IN -o OUT` to convert it to glTF 2.0.",
    );
}
