//! Duplicate keys in one JSON object.

use super::{Rule, Run};
use crate::check::context::Context;
use crate::diagnostic::Severity;
use crate::document::json;

pub(super) const RULE: Rule = Rule::new(
    "JSON_DUPLICATE_KEY",
    Severity::Warning,
    "json",
    "A key appears twice in one JSON object; engines disagree on which value wins.",
    DOC,
    Run::document(check),
);

const DOC: &str = "\
## What it does
Reports an object key that appears more than once in the same JSON object: one finding per
key and object, at its first repeat, saying how many times it appears.

## Why
The glTF 2.0 spec says keys SHOULD be unique. JSON parsers disagree on which copy wins (most keep
the last, some the first), so the same file loads differently in different engines. The
Khronos validator does not detect it: its parser silently keeps the last value.

## Example
```json
{\"materials\": [{\"name\": \"a\", \"doubleSided\": true, \"doubleSided\": false}]}
```
";

fn check(ctx: &mut Context) {
    // The parse saw every key: a text without a repeat is not read again.
    if ctx
        .document
        .root
        .as_ref()
        .is_some_and(|tree| !tree.repeats_keys())
    {
        return;
    }
    for duplicate in json::duplicate_keys(ctx.document.json_text()) {
        ctx.emit(
            RULE.code(),
            duplicate.pointer,
            format!(
                "Duplicate key ({} times in this object): parsers disagree on which value wins (the last one was used).",
                duplicate.occurrences
            ),
        );
    }
}
