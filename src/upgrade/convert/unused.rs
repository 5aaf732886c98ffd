//! Textures, images and samplers no material uses are not written: a rebake leaves the
//! original images behind (they would show as UNUSED_OBJECT), and a 1.0 asset may carry
//! textures nothing reads.

use crate::upgrade::builder::Builder;
use crate::upgrade::json::Items;
use crate::upgrade::references::{renumber_texture_members, renumber_textures, texture_indices};
use crate::upgrade::NoteKind;
use serde_json::Value;

impl Builder<'_, '_> {
    pub(in crate::upgrade) fn drop_unused_textures(&mut self) {
        let mut used = Vec::new();
        for material in self
            .arrays
            .get("materials")
            .into_iter()
            .flat_map(Items::iter)
        {
            used.extend(texture_indices(&material));
        }
        let textures = self.keep_used("textures", &used);
        if let Some(materials) = self.arrays.get_mut("materials") {
            materials.update_all(|material| renumber_textures(material, &textures));
        }
        let images = self.keep_used("images", &self.referenced("source"));
        let samplers = self.keep_used("samplers", &self.referenced("sampler"));
        if let Some(textures) = self.arrays.get_mut("textures") {
            textures.update_all(|texture| renumber_texture_members(texture, &images, &samplers));
        }
        let mut index = 0;
        self.images.retain(|_| {
            index += 1;
            images[index - 1].is_some()
        });
    }

    /// Removes the objects of `collection` that `used` (their indices) does not name, noting
    /// each; returns every old index's new one (None: removed).
    fn keep_used(&mut self, collection: &'static str, used: &[usize]) -> Vec<Option<usize>> {
        let mut items = self.arrays.remove(collection).unwrap_or_default();
        let mut is_used = vec![false; items.len()];
        for &i in used {
            if let Some(flag) = is_used.get_mut(i) {
                *flag = true;
            }
        }
        let mut new_index = Vec::with_capacity(items.len());
        let mut dropped = Vec::new();
        let mut kept = 0;
        self.origins
            .renumber(collection, |old| is_used.get(old) == Some(&true));
        items.retain(|old, item| {
            if is_used[old] {
                new_index.push(Some(kept));
                kept += 1;
                return true;
            }
            new_index.push(None);
            dropped.push(
                item.get("name")
                    .and_then(Value::as_str)
                    .unwrap_or("")
                    .to_string(),
            );
            false
        });
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
        self.arrays.insert(collection, items);
        new_index
    }
}

impl Builder<'_, '_> {
    /// The indices the textures' `key` member names.
    fn referenced(&self, key: &str) -> Vec<usize> {
        (self
            .arrays
            .get("textures")
            .into_iter()
            .flat_map(Items::iter))
        .filter_map(|texture| texture.get(key)?.as_u64())
        .map(|i| i as usize)
        .collect()
    }
}
