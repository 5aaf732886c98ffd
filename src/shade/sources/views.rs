//! An asset's buffer views with the buffers they read, for the readers of mesh data (the
//! images stored in views, the surface points).

use crate::document::file::Kept;
use crate::document::uri::{load_uri, ResourceLoader};
use crate::document::{self, BufferData, Container, Node};
use serde_json::Value;

/// A document's buffer views with the buffers they read, loaded once.
pub(super) struct Views<'d> {
    views: Vec<Value>,
    buffers: Vec<Option<BufferData<'d>>>,
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
                    Some(uri) => (load_uri(uri, loader).ok())
                        .map(|bytes| BufferData::Loaded(Kept::Read(bytes))),
                    None if i == 0 && doc.container == Container::Glb => {
                        doc.bin().map(BufferData::Glb)
                    }
                    None => None,
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
        let view = self.views.get(index as usize)?;
        let buffer = (self.buffers)
            .get(view.get("buffer")?.as_u64()? as usize)?
            .as_ref()?;
        let start = view.get("byteOffset").and_then(Value::as_u64).unwrap_or(0) as usize;
        let end = start.checked_add(view.get("byteLength")?.as_u64()? as usize)?;
        buffer.in_memory()?.get(start..end)
    }

    /// A view's byteStride, when it sets one.
    pub(super) fn stride(&self, index: u64) -> Option<usize> {
        let view = self.views.get(index as usize)?;
        Some(view.get("byteStride")?.as_u64()? as usize)
    }
}
