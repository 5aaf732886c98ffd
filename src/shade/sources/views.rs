//! An asset's buffer views with the buffers they read, for the readers of mesh data (the
//! images stored in views, the surface points).

use crate::document::file::Kept;
use crate::document::uri::{load_uri, ResourceLoader};
use crate::document::{self, BufferData, Container, Node};
use serde_json::Value;

/// A document's buffer views with the buffers they read, loaded once.
pub(super) struct Views<'d> {
    views: Vec<Value>,
    /// Each buffer's data, or why it cannot be had.
    buffers: Vec<Result<BufferData<'d>, String>>,
}

impl<'d> Views<'d> {
    pub(super) fn of(doc: &'d document::Document, loader: &dyn ResourceLoader) -> Views<'d> {
        let root = doc.root.as_ref().map(|tree| tree.root());
        let list = |key: &str| -> Vec<Value> {
            (root
                .and_then(|r| r.get(key))
                .and_then(Node::as_array)
                .into_iter())
            .flat_map(|a| a.iter())
            .map(Node::to_value)
            .collect()
        };
        let buffers = (list("buffers").iter().enumerate())
            .map(
                |(i, buffer)| match buffer.get("uri").and_then(Value::as_str) {
                    Some(uri) => {
                        load_uri(uri, loader).map(|bytes| BufferData::Loaded(Kept::Read(bytes)))
                    }
                    None if i == 0 && doc.container == Container::Glb => doc
                        .bin()
                        .map(BufferData::Glb)
                        .ok_or_else(|| "the GLB has no BIN chunk".into()),
                    None => Err("it has no uri".into()),
                },
            )
            .collect();
        Views {
            views: list("bufferViews"),
            buffers,
        }
    }

    /// The bytes of buffer view `index`, when its buffer was read and holds them.
    pub(super) fn bytes(&self, index: u64) -> Option<&[u8]> {
        self.read(index).ok()
    }

    /// The bytes of buffer view `index`, or why they cannot be had (which buffer, and why).
    pub(super) fn read(&self, index: u64) -> Result<&[u8], String> {
        let view = (self.views.get(index as usize))
            .ok_or_else(|| format!("bufferView {index} does not exist"))?;
        let number = |key: &str| view.get(key).and_then(Value::as_u64);
        let buffer =
            number("buffer").ok_or_else(|| format!("bufferView {index} names no buffer"))?;
        let data = match self.buffers.get(buffer as usize) {
            Some(Ok(data)) => data,
            Some(Err(why)) => return Err(format!("buffer {buffer}: {why}")),
            None => {
                return Err(format!(
                    "bufferView {index}: buffer {buffer} does not exist"
                ))
            }
        };
        let start = number("byteOffset").unwrap_or(0) as usize;
        let end = (number("byteLength"))
            .and_then(|length| start.checked_add(length as usize))
            .ok_or_else(|| format!("bufferView {index} has no usable byteLength"))?;
        let bytes =
            (data.in_memory()).ok_or_else(|| format!("buffer {buffer} is not held in memory"))?;
        bytes.get(start..end).ok_or_else(|| format!(
            "bufferView {index} (bytes {start}..{end}) runs past the end of buffer {buffer} ({} bytes)",
            bytes.len()
        ))
    }

    /// A view's byteStride, when it sets one.
    pub(super) fn stride(&self, index: u64) -> Option<usize> {
        let view = self.views.get(index as usize)?;
        Some(view.get("byteStride")?.as_u64()? as usize)
    }
}
