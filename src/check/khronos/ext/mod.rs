//! Extension passes, one file per extension (the Khronos validator's `ext/`).

pub(crate) mod lights;
