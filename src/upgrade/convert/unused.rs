//! Textures, images and samplers no material uses are not written: a rebake leaves the
//! original images behind (they would show as UNUSED_OBJECT), and a 1.0 asset may carry
//! textures nothing reads.

use crate::upgrade::builder::Builder;
use crate::upgrade::edited::Array;
use crate::upgrade::references::{renumber_texture_members, renumber_textures, texture_indices};
use crate::upgrade::NoteKind;
use serde_json::Value;

impl Builder<'_, '_> {
    pub(in crate::upgrade) fn drop_unused_textures(&mut self) {
        let mut used = Vec::new();
        for material in self.edited.all(Array::Materials) {
            used.extend(texture_indices(material));
        }
        let textures = self.keep_used(Array::Textures, &used);
        for material in self.edited.all_mut(Array::Materials) {
            renumber_textures(material, &textures);
        }
        let images = self.keep_used(Array::Images, &self.referenced("source"));
        let samplers = self.keep_used(Array::Samplers, &self.referenced("sampler"));
        for texture in self.edited.all_mut(Array::Textures) {
            renumber_texture_members(texture, &images, &samplers);
        }
        let mut index = 0;
        self.images.retain(|_| {
            index += 1;
            images[index - 1].is_some()
        });
    }

    /// Removes the objects of `array` that `used` (their indices) does not name, noting
    /// each; returns every old index's new one (None: removed).
    fn keep_used(&mut self, array: Array, used: &[usize]) -> Vec<Option<usize>> {
        let collection = array.key();
        let items = self.edited.take(array).unwrap_or_default();
        let mut is_used = vec![false; items.len()];
        for &i in used {
            if let Some(flag) = is_used.get_mut(i) {
                *flag = true;
            }
        }
        let mut new_index = Vec::with_capacity(items.len());
        let mut dropped = Vec::new();
        let mut kept = Vec::with_capacity(items.len());
        self.origins
            .renumber(collection, |old| is_used.get(old) == Some(&true));
        for (old, item) in items.into_iter().enumerate() {
            if is_used[old] {
                new_index.push(Some(kept.len()));
                kept.push(item);
                continue;
            }
            new_index.push(None);
            let name = item.get("name").and_then(Value::as_str).unwrap_or("");
            dropped.push(name.to_string());
        }
        for name in dropped {
            self.note(
                format!("/{collection}"),
                NoteKind::Dropped,
                format!(
                    "{} '{name}' not written: nothing in the output uses it.",
                    &collection[..collection.len() - 1]
                ),
            );
        }
        *self.edited.list_mut(array) = Some(kept);
        new_index
    }

    /// The indices the textures' `key` member names.
    fn referenced(&self, key: &str) -> Vec<usize> {
        (self.edited.all(Array::Textures))
            .filter_map(|texture| texture.get(key)?.as_u64())
            .map(|i| i as usize)
            .collect()
    }
}
