//! JSON text → `serde_json::Value`, each array and object allocated at its exact size.
//!
//! serde_json's own `Value` deserializer grows every array and object as it reads it: an
//! object of one member holds room for four (with `preserve_order`, 4 × 104 bytes plus a hash
//! table) and an array up to twice its length. A document's tree is most of the memory a
//! check uses, so on a file of many small objects (10^5 materials) the growth room alone
//! is about half of it. Here each container's members are gathered first and then moved
//! into a container made for exactly that many; the values are the ones serde_json would
//! build (same numbers, same last-wins duplicate keys at the first key's place).
//!
//! A tree costs about 80 bytes per value whatever the text spends on it, so a document of
//! 10^7 zeros (20 MB) takes 800 MB. The number of values is therefore bounded: past
//! [`MAX_VALUES`] parsing stops with an error at that value's place, instead of memory growing
//! with whatever a stranger uploads.

use serde::de::{self, DeserializeSeed, Deserializer, MapAccess, SeqAccess, Visitor};
use serde_json::{Map, Number, Value};
use std::cell::Cell;
use std::fmt;

/// The most values one document's tree holds (about 1.3 GB). Real glTF JSON stays far below:
/// 10^5 nodes with a name, a mesh and a full transform are about 2·10^6 values.
pub const MAX_VALUES: usize = 1 << 24;

/// Parses JSON text into a tree whose containers have no spare capacity, of at most
/// [`MAX_VALUES`] values.
pub fn from_slice(text: &[u8]) -> serde_json::Result<Value> {
    from_slice_within(text, MAX_VALUES)
}

fn from_slice_within(text: &[u8], max_values: usize) -> serde_json::Result<Value> {
    let mut deserializer = serde_json::Deserializer::from_slice(text);
    let left = Cell::new(max_values);
    let value = ExactValue { left: &left }.deserialize(&mut deserializer)?;
    deserializer.end()?;
    Ok(value)
}

/// An object of exactly the gathered members (a repeated key keeps its first place and its
/// last value, as serde_json's).
fn exact_object(gathered: Vec<(String, Value)>) -> Value {
    let mut object = Map::with_capacity(gathered.len());
    for (key, value) in gathered {
        object.insert(key, value);
    }
    Value::Object(object)
}

/// The same value with no spare room in its arrays and objects: for trees built member by
/// member (a converted material), which otherwise keep their growth room for good.
pub(crate) fn tighten(value: Value) -> Value {
    match value {
        Value::Array(elements) => {
            let mut array: Vec<Value> = elements.into_iter().map(tighten).collect();
            array.shrink_to_fit();
            Value::Array(array)
        }
        Value::Object(members) => {
            let mut object = Map::with_capacity(members.len());
            for (key, value) in members {
                object.insert(key, tighten(value));
            }
            Value::Object(object)
        }
        scalar => scalar,
    }
}

/// A `Value` whose arrays and objects are allocated at their final size, counted against the
/// values the document has `left`.
#[derive(Clone, Copy)]
struct ExactValue<'b> {
    left: &'b Cell<usize>,
}

impl ExactValue<'_> {
    /// Counts one more value, or fails once the budget is spent.
    fn spend<E: de::Error>(self) -> Result<(), E> {
        let left = self.left.get().checked_sub(1).ok_or_else(|| {
            E::custom(format_args!(
                "more than {MAX_VALUES} values, the most gltfmat reads in one document"
            ))
        })?;
        self.left.set(left);
        Ok(())
    }
}

impl<'de> DeserializeSeed<'de> for ExactValue<'_> {
    type Value = Value;

    fn deserialize<D: Deserializer<'de>>(self, deserializer: D) -> Result<Value, D::Error> {
        deserializer.deserialize_any(self)
    }
}

impl<'de> Visitor<'de> for ExactValue<'_> {
    type Value = Value;

    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str("any JSON value")
    }

    fn visit_bool<E>(self, value: bool) -> Result<Value, E>
    where
        E: de::Error,
    {
        self.spend()?;
        Ok(Value::Bool(value))
    }

    fn visit_i64<E>(self, value: i64) -> Result<Value, E>
    where
        E: de::Error,
    {
        self.spend()?;
        Ok(Value::Number(value.into()))
    }

    fn visit_u64<E>(self, value: u64) -> Result<Value, E>
    where
        E: de::Error,
    {
        self.spend()?;
        Ok(Value::Number(value.into()))
    }

    fn visit_f64<E>(self, value: f64) -> Result<Value, E>
    where
        E: de::Error,
    {
        self.spend()?;
        // As serde_json's own visitor: a number with no finite f64 is null.
        Ok(Number::from_f64(value).map_or(Value::Null, Value::Number))
    }

    fn visit_str<E>(self, value: &str) -> Result<Value, E>
    where
        E: de::Error,
    {
        self.spend()?;
        Ok(Value::String(value.to_owned()))
    }

    fn visit_string<E>(self, value: String) -> Result<Value, E>
    where
        E: de::Error,
    {
        self.spend()?;
        Ok(Value::String(value))
    }

    fn visit_unit<E>(self) -> Result<Value, E>
    where
        E: de::Error,
    {
        self.spend()?;
        Ok(Value::Null)
    }

    fn visit_seq<A: SeqAccess<'de>>(self, mut elements: A) -> Result<Value, A::Error> {
        self.spend()?;
        let mut array = Vec::new();
        while let Some(element) = elements.next_element_seed(self)? {
            array.push(element);
        }
        array.shrink_to_fit();
        Ok(Value::Array(array))
    }

    fn visit_map<A: MapAccess<'de>>(self, mut members: A) -> Result<Value, A::Error> {
        self.spend()?;
        let mut gathered: Vec<(String, Value)> = Vec::new();
        while let Some(key) = members.next_key::<String>()? {
            gathered.push((key, members.next_value_seed(self)?));
        }
        Ok(exact_object(gathered))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn builds_the_value_serde_json_builds() {
        let text = br#"{"b":[1,-2,3.5,1e300,-0.0,"s\u00e9",true,null,{}],"a":{"k":1,"k":2,"j":[]},"c":18446744073709551615}"#;
        let exact = from_slice(text).unwrap();
        let reference: Value = serde_json::from_slice(text).unwrap();
        assert_eq!(exact, reference);
        // Same member order, duplicate key kept at its first place with the last value.
        let keys: Vec<&String> = exact["a"].as_object().unwrap().keys().collect();
        assert_eq!(keys, ["k", "j"]);
        assert_eq!(exact["a"]["k"], 2);
    }

    #[test]
    fn containers_have_no_spare_room() {
        let exact = from_slice(br#"{"a":[1,2,3,4,5],"o":{"x":1}}"#).unwrap();
        assert_eq!(exact["a"].as_array().unwrap().capacity(), 5);
        let reference: Value = serde_json::from_slice(br#"[1,2,3,4,5]"#).unwrap();
        // The comparison that makes the test mean something: serde_json's own leaves room.
        assert!(reference.as_array().unwrap().capacity() > 5);
    }

    #[test]
    fn a_tightened_value_is_equal_and_has_no_spare_room() {
        let mut grown = serde_json::json!({"a": [1, 2, 3], "o": {"x": {"y": [true]}}});
        grown["a"].as_array_mut().unwrap().push(4.into());
        assert!(grown["a"].as_array().unwrap().capacity() > 4);
        let tight = tighten(grown.clone());
        assert_eq!(tight, grown);
        assert_eq!(tight["a"].as_array().unwrap().capacity(), 4);
    }

    #[test]
    fn a_document_of_more_values_than_allowed_stops_at_the_first_value_past_the_budget() {
        let text = br#"{"a":[0,0,{"b":0}]}"#; // 6 values: the root, a, three elements, b.
        assert!(from_slice_within(text, 6).is_ok());
        let error = from_slice_within(text, 5).unwrap_err();
        assert!(error.to_string().starts_with("more than"), "{error}");
        assert_eq!((error.line(), error.column()), (1, 16), "{error}");
    }

    #[test]
    fn errors_are_serde_jsons() {
        for text in [&b"{\"a\":1"[..], b"[1,]", b"{} x", b"[1e400]"] {
            let exact = from_slice(text).unwrap_err().to_string();
            let reference = serde_json::from_slice::<Value>(text)
                .unwrap_err()
                .to_string();
            assert_eq!(exact, reference, "{}", String::from_utf8_lossy(text));
        }
    }
}
