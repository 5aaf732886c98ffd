//! Images whose pixel data cannot be decoded (`--deep`).

use super::{Rule, Run};
use crate::diagnostic::Severity;

pub(super) const RULE: Rule = Rule::new(
    "IMAGE_UNDECODABLE",
    Severity::Error,
    "pixels",
    "With --deep: an image's header is valid but its pixel data cannot be decoded.",
    DOC,
    Run::CORE,
);

const DOC: &str = "\
## What it does
With `--deep`, gltfmat decodes every image a pixel rule needs. This reports an image whose
header reads correctly but whose data does not decode: a corrupt compressed stream, a
truncated file, an unsupported variant of the format. The pointer is the image.

## Why
The Khronos validator reads only image headers, so a PNG whose zlib stream is damaged passes
it and then fails to load (or loads black) in an engine.

## Example
A PNG whose IDAT chunk was cut short by a failed upload.
";
