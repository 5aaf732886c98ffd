//! URIs that leave the asset's folder (emitted by the resource pass).

use super::{Rule, Run};
use crate::check::pass_codes::URI_OUTSIDE_ASSET_FOLDER;
use crate::diagnostic::khronos;

pub(crate) const RULE: Rule = Rule::documenting(
    URI_OUTSIDE_ASSET_FOLDER,
    "resources",
    "A URI resolves outside the asset's folder (absolute path, `..` escape or symlink) and was not read.",
    DOC,
    Run::CORE,
)
.khronos_name(
    khronos::IO_ERROR,
    "A URI leaving the asset's folder is URI_OUTSIDE_ASSET_FOLDER, not a failed read.",
);

const DOC: &str = "\
## What it does
Reports a buffer or image `uri` that is an absolute path, climbs out of the asset's folder with
`..`, or reaches outside it through a symbolic link. The file is not read. (A URI of another
scheme, `http:` or `file:`, is NON_RELATIVE_URI and is not fetched either.) A path that climbs
out and names its way back in along the folder's own path (`../Textures/a.png` in an asset whose
folder is `Textures`) is where a viewer reads it, inside the folder, and is read from there.

## Why
Assets come from strangers. A validator that follows `../../etc/passwd` or `/home/ci/.ssh/id_rsa`
leaks files into reports and CI logs. glTF resources are relative to the asset, so nothing
legitimate needs to leave its folder. (`--profile khronos` reports this as IO_ERROR.)

## Example
```json
{\"buffers\": [{\"uri\": \"../secrets/key.bin\", \"byteLength\": 16}]}
```
";
