//! Images in a format gltfmat reads the header of but does not decode (`--deep`).

use super::{Rule, Run};
use crate::diagnostic::Severity;

pub(super) const RULE: Rule = Rule::new(
    "IMAGE_NOT_DECODED",
    Severity::Info,
    "pixels",
    "With --deep: a KTX2 image in an encoding gltfmat does not transcode, so its pixel rules did not run.",
    DOC,
    Run::CORE,
);

const DOC: &str = "\
## What it does
With `--deep`, reports a KTX2 image that a pixel rule would inspect but gltfmat does not
transcode: a plain Vulkan format (vkFormat other than 0, which KHR_texture_basisu does not
allow) or a Basis Universal HDR encoding, which has no 8-bit form. Basis Universal ETC1S and
UASTC images — what KHR_texture_basisu allows — are transcoded and inspected like PNGs.

## Why
A valid image in such a format is not an undecodable one: reporting IMAGE_UNDECODABLE (an
error) would fail a CI gate on a well-made asset. What was not looked at is said, so that a
clean `--deep` report is not read as a verdict on these texels.

## Example
```json
{\"textures\": [{\"extensions\": {\"KHR_texture_basisu\": {\"source\": 0}}}],
 \"images\": [{\"uri\": \"normal.ktx2\"}]}
```
where `normal.ktx2` holds `VK_FORMAT_R8G8B8A8_UNORM` texels.
";
