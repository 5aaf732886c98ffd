//! JSON text → `serde_json::Value`, each array and object allocated at its exact size.
//!
//! serde_json's own `Value` deserializer grows every array and object as it reads it: an
//! object of one member holds room for four (with `preserve_order`, 4 × 104 bytes plus a hash
//! table) and an array up to twice its length. A document's tree is most of the memory a
//! check uses, so on a file of many small objects (10^5 materials) the growth room alone
//! is about half of it. Here each container's members are gathered first and then moved
//! into a container made for exactly that many; the values are the ones serde_json would
//! build (same numbers, same last-wins duplicate keys at the first key's place).

use serde::de::{DeserializeSeed, Deserializer, MapAccess, SeqAccess, Visitor};
use serde_json::{Map, Number, Value};
use std::fmt;

/// Parses JSON text into a tree whose containers have no spare capacity.
pub fn from_slice(text: &[u8]) -> serde_json::Result<Value> {
    let mut deserializer = serde_json::Deserializer::from_slice(text);
    let value = ExactValue.deserialize(&mut deserializer)?;
    deserializer.end()?;
    Ok(value)
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

/// A `Value` whose arrays and objects are allocated at their final size.
struct ExactValue;

impl<'de> DeserializeSeed<'de> for ExactValue {
    type Value = Value;

    fn deserialize<D: Deserializer<'de>>(self, deserializer: D) -> Result<Value, D::Error> {
        deserializer.deserialize_any(self)
    }
}

impl<'de> Visitor<'de> for ExactValue {
    type Value = Value;

    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str("any JSON value")
    }

    fn visit_bool<E>(self, value: bool) -> Result<Value, E> {
        Ok(Value::Bool(value))
    }

    fn visit_i64<E>(self, value: i64) -> Result<Value, E> {
        Ok(Value::Number(value.into()))
    }

    fn visit_u64<E>(self, value: u64) -> Result<Value, E> {
        Ok(Value::Number(value.into()))
    }

    fn visit_f64<E>(self, value: f64) -> Result<Value, E> {
        // As serde_json's own visitor: a number with no finite f64 is null.
        Ok(Number::from_f64(value).map_or(Value::Null, Value::Number))
    }

    fn visit_str<E>(self, value: &str) -> Result<Value, E> {
        Ok(Value::String(value.to_owned()))
    }

    fn visit_string<E>(self, value: String) -> Result<Value, E> {
        Ok(Value::String(value))
    }

    fn visit_unit<E>(self) -> Result<Value, E> {
        Ok(Value::Null)
    }

    fn visit_seq<A: SeqAccess<'de>>(self, mut elements: A) -> Result<Value, A::Error> {
        let mut array = Vec::new();
        while let Some(element) = elements.next_element_seed(ExactValue)? {
            array.push(element);
        }
        array.shrink_to_fit();
        Ok(Value::Array(array))
    }

    fn visit_map<A: MapAccess<'de>>(self, mut members: A) -> Result<Value, A::Error> {
        let mut gathered: Vec<(String, Value)> = Vec::new();
        while let Some(key) = members.next_key::<String>()? {
            gathered.push((key, members.next_value_seed(ExactValue)?));
        }
        let mut object = Map::with_capacity(gathered.len());
        for (key, value) in gathered {
            object.insert(key, value);
        }
        Ok(Value::Object(object))
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
