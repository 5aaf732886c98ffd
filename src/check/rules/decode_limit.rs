//! Images too large to decode within gltfmat's limits (`--deep`).

use super::{Rule, Run};
use crate::diagnostic::Severity;

pub(super) const RULE: Rule = Rule::new(
    "IMAGE_DECODE_LIMIT",
    Severity::Info,
    "pixels",
    "With --deep: an image exceeds the decoding limits, so its pixel rules were skipped.",
    DOC,
    Run::CORE,
);

const DOC: &str = "\
## What it does
With `--deep`, reports an image that is wider or taller than 16384 texels or whose decoding
would allocate more than 512 MiB. Its pixel rules are skipped; header rules still apply.

## Why
gltfmat checks files from strangers: a 100-byte PNG can claim to be 100 000 × 100 000 texels
(a decompression bomb). Memory stays bounded whatever the header claims.

## Example
A PNG whose IHDR says 65535 × 65535.
";
