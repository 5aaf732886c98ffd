//! The root arrays an upgrade changes after making them (materials, and the textures,
//! images and samplers they read: renumbered when unused ones are dropped), held as values
//! until the output's JSON is written. Every other array goes to the output store as text
//! once and is not read back.

use super::json::Json;
use crate::document::Node;
use serde_json::Value;

/// A root array the conversion changes: the materials and what they read.
#[derive(Clone, Copy)]
pub(super) enum Array {
    Materials,
    Images,
    Textures,
    Samplers,
}

impl Array {
    /// In the order an array the input lacks is appended to the output's members.
    const ALL: [Array; 4] = [
        Array::Materials,
        Array::Images,
        Array::Textures,
        Array::Samplers,
    ];

    /// The array a root member's key names, if the conversions change it.
    pub(super) fn of(key: &str) -> Option<Array> {
        Array::ALL.into_iter().find(|array| array.key() == key)
    }

    pub(super) fn key(self) -> &'static str {
        match self {
            Array::Materials => "materials",
            Array::Images => "images",
            Array::Textures => "textures",
            Array::Samplers => "samplers",
        }
    }
}

/// The arrays the conversions change, as values: read from a 2.0 input (or made by a 1.0
/// upgrade), changed in place, and written to the output's JSON once, at the end. Each is `None` where the input has no
/// such array (or all of it was dropped).
#[derive(Default)]
pub(super) struct Edited {
    lists: [Option<Vec<Value>>; 4],
}

impl Edited {
    pub(super) fn of(input: Node) -> Edited {
        let values = |array: Array| {
            let list = input.get(array.key()).and_then(Node::as_array);
            list.map(|list| list.iter().map(Node::to_value).collect())
        };
        Edited {
            lists: Array::ALL.map(values),
        }
    }

    pub(super) fn list_mut(&mut self, array: Array) -> &mut Option<Vec<Value>> {
        &mut self.lists[array as usize]
    }

    pub(super) fn all(&self, array: Array) -> impl Iterator<Item = &Value> + '_ {
        self.lists[array as usize].iter().flatten()
    }

    pub(super) fn all_mut(&mut self, array: Array) -> impl Iterator<Item = &mut Value> + '_ {
        self.list_mut(array).iter_mut().flatten()
    }

    /// Element `index` of `array`.
    pub(super) fn get(&self, array: Array, index: usize) -> Option<&Value> {
        self.lists[array as usize].as_ref()?.get(index)
    }

    /// Element `index` of `array`, to change.
    pub(super) fn at(&mut self, array: Array, index: usize) -> Option<&mut Value> {
        self.list_mut(array).as_mut()?.get_mut(index)
    }

    /// Appends `value` to `array` (made if the input has none); returns its index.
    pub(super) fn push(&mut self, array: Array, value: Value) -> usize {
        let list = self.list_mut(array).get_or_insert_with(Vec::new);
        list.push(value);
        list.len() - 1
    }

    /// Takes `array`'s elements out (`None` where there is no such array).
    pub(super) fn take(&mut self, array: Array) -> Option<Vec<Value>> {
        self.list_mut(array).take()
    }

    /// Writes every array to `root`: one the input has is replaced where it stands (removed
    /// if all of it was dropped), one it lacks appended.
    pub(super) fn write(self, input: Node, root: &mut Json) {
        for (array, list) in Array::ALL.into_iter().zip(self.lists) {
            let key = array.key();
            match list {
                Some(list) => root.insert(key, &Value::Array(list)),
                None if input.get(key).and_then(Node::as_array).is_some() => {
                    root.remove(key);
                }
                None => {}
            }
        }
    }
}
