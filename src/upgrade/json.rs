//! The upgraded asset's JSON, held as text: every element of a root array, and every other
//! root member, as its own compact text.
//!
//! A `serde_json::Value` costs 80 bytes a value and a map per object, ten times or more the
//! text it stands for. Held as text, the output costs about its own size, and a step that
//! reads or changes one object parses just that object.

use crate::document::Node;
use serde::Serialize;
use serde_json::Value;

/// A JSON array, each element kept as its compact text.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Items(Vec<Box<str>>);

/// One element (or member) as text; a value serde_json cannot write (none of ours: keys
/// are strings, numbers finite) becomes `null` rather than a panic.
fn text_of(value: &impl Serialize) -> Box<str> {
    serde_json::to_string(value)
        .unwrap_or_else(|_| "null".into())
        .into_boxed_str()
}

/// Text this module wrote, as a value again (`null` if it somehow does not parse).
fn value_of(text: &str) -> Value {
    serde_json::from_str(text).unwrap_or(Value::Null)
}

impl Items {
    /// How many elements.
    pub fn len(&self) -> usize {
        self.0.len()
    }

    /// Whether there are none.
    pub fn is_empty(&self) -> bool {
        self.0.is_empty()
    }

    /// Element `index`, parsed.
    pub fn get(&self, index: usize) -> Option<Value> {
        self.0.get(index).map(|text| value_of(text))
    }

    /// The elements, each parsed as it is reached.
    pub fn iter(&self) -> impl ExactSizeIterator<Item = Value> + '_ {
        self.0.iter().map(|text| value_of(text))
    }

    /// The elements as this module wrote them (compact JSON text).
    pub(crate) fn texts(&self) -> impl ExactSizeIterator<Item = &str> + '_ {
        self.0.iter().map(|text| &**text)
    }

    /// Appends `value`; returns its index.
    pub fn push(&mut self, value: &impl Serialize) -> usize {
        self.0.push(text_of(value));
        self.0.len() - 1
    }

    /// Changes element `index` through `change` (nothing when there is no such element).
    pub fn update(&mut self, index: usize, change: impl FnOnce(&mut Value)) {
        if let Some(text) = self.0.get_mut(index) {
            let mut value = value_of(text);
            change(&mut value);
            *text = text_of(&value);
        }
    }

    /// Changes every element through `change`.
    pub fn update_all(&mut self, mut change: impl FnMut(&mut Value)) {
        for index in 0..self.0.len() {
            self.update(index, &mut change);
        }
    }

    /// Keeps the elements `keep` (given each one's old index and value) says to keep.
    pub fn retain(&mut self, mut keep: impl FnMut(usize, &Value) -> bool) {
        let mut index = 0;
        self.0.retain(|text| {
            index += 1;
            keep(index - 1, &value_of(text))
        });
    }

    fn write(&self, out: &mut Vec<u8>, pretty: Option<usize>) {
        if self.0.is_empty() {
            out.extend(b"[]");
            return;
        }
        out.push(b'[');
        for (i, text) in self.0.iter().enumerate() {
            if i > 0 {
                out.push(b',');
            }
            match pretty {
                Some(depth) => {
                    newline(out, depth + 1);
                    write_pretty(text, out, depth + 1);
                }
                None => out.extend(text.as_bytes()),
            }
        }
        if let Some(depth) = pretty {
            newline(out, depth);
        }
        out.push(b']');
    }
}

/// A root member: an array's elements one by one, anything else whole.
#[derive(Debug, Clone, PartialEq)]
enum Member {
    Items(Items),
    Whole(Box<str>),
}

impl Member {
    fn of(value: &Value) -> Member {
        match value {
            Value::Array(elements) => Member::Items(Items(elements.iter().map(text_of).collect())),
            other => Member::Whole(text_of(other)),
        }
    }

    fn of_node(node: Node) -> Member {
        match node.as_array() {
            Some(elements) => Member::Items(Items(elements.iter().map(|e| text_of(&e)).collect())),
            None => Member::Whole(text_of(&node)),
        }
    }

    fn to_value(&self) -> Value {
        match self {
            Member::Items(items) => Value::Array(items.iter().collect()),
            Member::Whole(text) => value_of(text),
        }
    }
}

/// The JSON of an upgraded asset: a root object whose members, and whose arrays' elements,
/// are each held as compact text.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Json {
    members: Vec<(String, Member)>,
}

impl Json {
    /// The root object of `root` (an empty one if it is not an object).
    pub(crate) fn from_node(root: Node) -> Json {
        let members = (root.as_object().into_iter())
            .flat_map(|object| object.iter())
            .map(|(key, value)| (key.to_string(), Member::of_node(value)))
            .collect();
        Json { members }
    }

    fn position(&self, key: &str) -> Option<usize> {
        self.members.iter().position(|(k, _)| k == key)
    }

    /// Root member `key`, parsed.
    pub fn get(&self, key: &str) -> Option<Value> {
        self.members
            .iter()
            .find(|(k, _)| k == key)
            .map(|(_, member)| member.to_value())
    }

    /// The elements of root array `key` (None: no such member, or not an array).
    pub fn items(&self, key: &str) -> Option<&Items> {
        self.members.iter().find_map(|(k, member)| match member {
            Member::Items(items) if k == key => Some(items),
            _ => None,
        })
    }

    /// The whole document as one value (for a caller that wants to walk it freely; costs
    /// what a `Value` costs).
    pub fn to_value(&self) -> Value {
        let members = self.members.iter().map(|(k, m)| (k.clone(), m.to_value()));
        Value::Object(members.collect())
    }

    /// Sets root member `key` to `value` (appended when new, in place when not).
    pub fn insert(&mut self, key: &str, value: &Value) {
        self.set(key, Member::of(value));
    }

    /// Sets root array `key` to `items`.
    pub fn insert_items(&mut self, key: &str, items: Items) {
        self.set(key, Member::Items(items));
    }

    fn set(&mut self, key: &str, member: Member) {
        match self.position(key) {
            Some(i) => self.members[i].1 = member,
            None => self.members.push((key.to_string(), member)),
        }
    }

    /// Root array `key`, made an empty array first when it is missing or not an array.
    pub fn items_mut(&mut self, key: &str) -> &mut Items {
        let i = match self.position(key) {
            Some(i) => i,
            None => {
                self.members
                    .push((key.to_string(), Member::Items(Items::default())));
                self.members.len() - 1
            }
        };
        let member = &mut self.members[i].1;
        if let Member::Whole(_) = member {
            *member = Member::Items(Items::default());
        }
        match member {
            Member::Items(items) => items,
            Member::Whole(_) => unreachable!("made an array just above"),
        }
    }

    /// Root array `key`, when there is one.
    pub fn items_mut_if_array(&mut self, key: &str) -> Option<&mut Items> {
        self.members
            .iter_mut()
            .find_map(|(k, member)| match member {
                Member::Items(items) if k == key => Some(items),
                _ => None,
            })
    }

    /// Removes root member `key`, saying whether there was one.
    pub fn remove(&mut self, key: &str) -> bool {
        let before = self.members.len();
        self.members.retain(|(k, _)| k != key);
        self.members.len() != before
    }

    /// Removes the root members that are `null` and named in `keys`.
    pub(crate) fn remove_nulls(&mut self, keys: &[&str]) {
        self.members.retain(|(k, member)| {
            !(keys.contains(&k.as_str())
                && matches!(member, Member::Whole(text) if &**text == "null"))
        });
    }

    /// The compact text.
    pub fn to_vec(&self) -> Vec<u8> {
        let mut out = Vec::new();
        self.write(&mut out, None);
        out
    }

    /// The text indented two spaces a level, as `serde_json::to_vec_pretty` writes it.
    pub fn to_vec_pretty(&self) -> Vec<u8> {
        let mut out = Vec::new();
        self.write(&mut out, Some(0));
        // The indentation outgrew the compact size reserved: the room doubled on the way.
        out.shrink_to_fit();
        out
    }

    /// Appends the compact text to `out` (a GLB's JSON chunk, written in place).
    pub(crate) fn append_to(&self, out: &mut Vec<u8>) {
        self.write(out, None);
    }

    fn write(&self, out: &mut Vec<u8>, pretty: Option<usize>) {
        out.reserve(self.text_len());
        if self.members.is_empty() {
            out.extend(b"{}");
            return;
        }
        out.push(b'{');
        for (i, (key, member)) in self.members.iter().enumerate() {
            if i > 0 {
                out.push(b',');
            }
            if pretty.is_some() {
                newline(out, 1);
            }
            out.extend(text_of(key).as_bytes());
            out.extend(if pretty.is_some() { &b": "[..] } else { b":" });
            match member {
                Member::Items(items) => items.write(out, pretty.map(|_| 1)),
                Member::Whole(text) if pretty.is_some() => write_pretty(text, out, 1),
                Member::Whole(text) => out.extend(text.as_bytes()),
            }
        }
        if pretty.is_some() {
            newline(out, 0);
        }
        out.push(b'}');
    }

    /// The compact text's length, or a little more (a key's escapes aside): what to reserve
    /// for it.
    pub(crate) fn text_len(&self) -> usize {
        let member = |m: &Member| match m {
            Member::Items(items) => items.0.iter().map(|t| t.len() + 1).sum::<usize>() + 2,
            Member::Whole(text) => text.len(),
        };
        (self.members.iter())
            .map(|(k, m)| k.len() + 4 + member(m))
            .sum::<usize>()
            + 2
    }
}

fn newline(out: &mut Vec<u8>, depth: usize) {
    out.push(b'\n');
    out.resize(out.len() + 2 * depth, b' ');
}

/// `text` pretty-printed as if it stood `depth` levels deep. JSON text holds no raw line
/// break inside a string, so indenting after each line break indents only structure.
fn write_pretty(text: &str, out: &mut Vec<u8>, depth: usize) {
    let pretty = serde_json::to_vec_pretty(&value_of(text)).unwrap_or_default();
    for &byte in &pretty {
        if byte == b'\n' {
            newline(out, depth);
        } else {
            out.push(byte);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;

    fn sample() -> Value {
        json!({"asset": {"version": "2.0"}, "scene": 0, "nodes": [{"name": "a\nb", "children": [1]}, {}],
               "buffers": [], "extras": [[1, 2.5e-300], {"k": []}]})
    }

    #[test]
    fn the_text_is_what_serde_json_writes_compact_and_pretty() {
        let value = sample();
        let tree = crate::document::Tree::parse(&serde_json::to_vec(&value).unwrap()).unwrap();
        let json = Json::from_node(tree.root());
        assert_eq!(json.to_vec(), serde_json::to_vec(&value).unwrap());
        assert_eq!(
            json.to_vec_pretty(),
            serde_json::to_vec_pretty(&value).unwrap()
        );
        assert_eq!(json.to_value(), value);
    }

    #[test]
    fn members_are_changed_in_place_and_appended_when_new() {
        let tree = crate::document::Tree::parse(&serde_json::to_vec(&sample()).unwrap()).unwrap();
        let mut json = Json::from_node(tree.root());
        json.items_mut("nodes")
            .update(1, |node| node["name"] = json!("b"));
        json.insert("scene", &json!(1));
        json.items_mut("meshes").push(&json!({"primitives": []}));
        json.items_mut("scene").push(&json!(2));
        json.remove("extras");
        let mut expected = sample();
        expected["nodes"][1]["name"] = json!("b");
        expected["scene"] = json!([2]);
        expected.as_object_mut().unwrap().remove("extras");
        expected["meshes"] = json!([{"primitives": []}]);
        assert_eq!(json.to_value(), expected);
        assert_eq!(json.items("nodes").unwrap().len(), 2);
        assert_eq!(json.items("asset"), None);
    }
}
