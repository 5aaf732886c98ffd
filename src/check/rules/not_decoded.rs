//! Images in a format gltfmat reads the header of but does not decode (`--deep`).

use super::{Rule, Run};
use crate::diagnostic::Severity;

pub const RULE: Rule = Rule::new(
    "IMAGE_NOT_DECODED",
    Severity::Info,
    "pixels",
    "With --deep: a KTX2 image is not decoded by gltfmat, so its pixel rules did not run.",
    DOC,
    Run::CORE,
);

const DOC: &str = "\
## What it does
With `--deep`, reports a KTX2 image (KHR_texture_basisu: Basis Universal ETC1S or UASTC, or a
plain Vulkan format) that a pixel rule would inspect. gltfmat reads KTX2 headers — format,
size, the texture's need for KHR_texture_basisu — but does not transcode the texels, so the
pixel rules say nothing about this image rather than something untrue.

## Why
A valid KTX2 image is not an undecodable one: reporting IMAGE_UNDECODABLE (an error) would
fail a CI gate on a well-made asset. What was not looked at is said, so that a clean `--deep`
report is not read as a verdict on these texels.

## Example
```json
{\"textures\": [{\"extensions\": {\"KHR_texture_basisu\": {\"source\": 0}}}],
 \"images\": [{\"uri\": \"normal.ktx2\"}]}
```
";
