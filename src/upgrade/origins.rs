//! Where each output object came from: a JSON pointer into the 1.0 input per output
//! object, for telling a user which input construct an output finding comes from.
//!
//! An upgrade of 10^5 meshes has 4·10^5 output objects: a map of pointer strings to pointer
//! strings would hold two allocations for each. Here each origin is a range of one shared
//! text.

use std::collections::HashMap;
use std::ops::Range;

/// The origins of an upgrade's output objects.
#[derive(Debug, Clone, Default)]
pub(crate) struct Origins {
    /// Every origin, end to end.
    text: String,
    /// Per output collection, each object's origin in `text` (an empty range: none known).
    by_collection: HashMap<&'static str, Vec<Range<usize>>>,
}

impl Origins {
    /// Records that object `index` of `collection` was made from `origin`.
    pub(crate) fn record(&mut self, collection: &'static str, index: usize, origin: &str) {
        let start = self.text.len();
        self.text.push_str(origin);
        let ranges = self.by_collection.entry(collection).or_default();
        if ranges.len() <= index {
            ranges.resize(index + 1, 0..0);
        }
        ranges[index] = start..self.text.len();
    }

    /// The origin of object `index` of `collection`.
    pub(crate) fn get(&self, collection: &str, index: usize) -> Option<&str> {
        let range = self.by_collection.get(collection)?.get(index)?;
        (!range.is_empty()).then(|| &self.text[range.clone()])
    }

    /// Renumbers `collection` after some of its objects were removed: `kept(old index)`
    /// says which stayed (in order).
    pub(crate) fn renumber(&mut self, collection: &str, kept: impl Fn(usize) -> bool) {
        if let Some(ranges) = self.by_collection.get_mut(collection) {
            let mut old = 0;
            ranges.retain(|_| {
                old += 1;
                kept(old - 1)
            });
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_origin_follows_its_object_when_earlier_ones_are_removed() {
        let mut origins = Origins::default();
        origins.record("textures", 0, "/textures/a");
        origins.record("textures", 2, "/textures/c");
        origins.record("meshes", 0, "/meshes/m");
        assert_eq!(origins.get("textures", 1), None);
        origins.renumber("textures", |old| old != 0);
        assert_eq!(origins.get("textures", 0), None);
        assert_eq!(origins.get("textures", 1), Some("/textures/c"));
        assert_eq!(origins.get("meshes", 0), Some("/meshes/m"));
        assert_eq!(origins.get("meshes", 1), None);
    }
}
