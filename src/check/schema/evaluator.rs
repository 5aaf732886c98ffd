//! A JSON Schema (2020-12) evaluator for the keywords gltfmat's schemas use, over the
//! document's compact tree. Each failure is handed to the caller as it is found, with the
//! instance's pointer made only then, so a 10^7-element array of wrong types streams
//! through without a tree of `serde_json::Value` or a list of errors being built.
//!
//! Keywords: `type`, `$ref` (to `#/$defs/…` of the same document), `properties`,
//! `additionalProperties`, `required`, `dependentRequired`, `minProperties`, `items`,
//! `minItems`, `maxItems`, `uniqueItems`, `minimum`, `maximum`, `exclusiveMinimum`,
//! `exclusiveMaximum`, `multipleOf`, `enum`, `const`, `pattern`, `minLength`, `allOf`,
//! `anyOf`, `oneOf`, `if` / `then`. Anything else is an annotation and ignored; a schema
//! using a keyword outside this list fails to compile (a test compiles every embedded one).

use crate::document::json::escape_token;
use crate::document::Node;
use regex::Regex;
use serde_json::Value;
use std::collections::{HashMap, HashSet};

/// A compiled schema document: its root and its `$defs`, one arena.
pub(super) struct Compiled {
    schemas: Vec<Schema>,
    root: usize,
    /// The `$defs` names, by the index a schema's `definition` holds.
    names: Vec<String>,
}

/// What failed, as the mapping to Khronos codes needs it.
#[derive(Debug, Clone, PartialEq)]
pub(super) enum Kind {
    /// Not of the type named.
    Type(String),
    /// Members neither declared nor allowed, in the instance's order.
    AdditionalProperties(Vec<String>),
    Required(String),
    /// `key` is present and needs `missing`.
    DependentRequired {
        key: String,
        missing: String,
    },
    MinProperties,
    MinItems(u64),
    MaxItems(u64),
    /// Repeats elements: the positions of the repeats. Only elements valid against the
    /// items' schema are compared: the validator reads the others as mismatched, not as
    /// elements.
    UniqueItems(Vec<usize>),
    Minimum,
    Maximum,
    ExclusiveMinimum,
    ExclusiveMaximum,
    MultipleOf(f64),
    /// Not one of these values (the list as written).
    Enum(Value),
    Const,
    Pattern(String),
    MinLength {
        limit: u64,
    },
    AnyOf,
    OneOf,
}

/// One failure: what, on which value, where, and in which `$defs` entry the keyword is.
pub(super) struct Failure<'c, 't> {
    pub kind: Kind,
    pub instance: Node<'t>,
    pub pointer: String,
    pub definition: Option<&'c str>,
}

#[derive(Default)]
struct Schema {
    /// The `$defs` entry this schema belongs to (index into `names`).
    definition: Option<usize>,
    types: Vec<&'static str>,
    reference: Option<usize>,
    properties: Vec<(String, usize)>,
    additional: Additional,
    required: Vec<String>,
    dependent_required: Vec<(String, Vec<String>)>,
    min_properties: Option<u64>,
    items: Option<usize>,
    min_items: Option<u64>,
    max_items: Option<u64>,
    unique_items: bool,
    minimum: Option<f64>,
    maximum: Option<f64>,
    exclusive_minimum: Option<f64>,
    exclusive_maximum: Option<f64>,
    multiple_of: Option<f64>,
    enumeration: Option<Value>,
    constant: Option<Value>,
    pattern: Option<(String, Regex)>,
    min_length: Option<u64>,
    all_of: Vec<usize>,
    any_of: Vec<usize>,
    one_of: Vec<usize>,
    condition: Option<usize>,
    then: Option<usize>,
}

#[derive(Default)]
enum Additional {
    #[default]
    Any,
    None,
    Each(usize),
}

/// Keywords that only annotate.
const ANNOTATIONS: &[&str] = &[
    "$schema",
    "$id",
    "$comment",
    "title",
    "description",
    "default",
    "examples",
    "$defs",
];

impl Compiled {
    /// Compiles a schema document; an error names what it cannot read.
    pub(super) fn new(document: &Value) -> Result<Compiled, String> {
        let mut compiler = Compiler {
            schemas: Vec::new(),
            definitions: HashMap::new(),
        };
        // Every definition gets its place first (the n-th schema is the n-th definition), so
        // that references may point anywhere.
        let definitions = document.get("$defs").and_then(Value::as_object);
        let names: Vec<String> = definitions
            .into_iter()
            .flat_map(|d| d.keys().cloned())
            .collect();
        for (n, name) in names.iter().enumerate() {
            compiler.schemas.push(Schema::default());
            compiler.definitions.insert(name.clone(), n);
        }
        for (n, definition) in definitions.into_iter().flat_map(|d| d.values()).enumerate() {
            compiler.schemas[n] = compiler.schema(definition, Some(n))?;
        }
        let root = compiler.compile(document, None)?;
        Ok(Compiled {
            schemas: compiler.schemas,
            root,
            names,
        })
    }

    /// Evaluates `instance`, whose pointer is `prefix`, calling `fail` on each failure.
    pub(super) fn evaluate<'c, 't>(
        &'c self,
        instance: Node<'t>,
        prefix: &str,
        fail: &mut dyn FnMut(Failure<'c, 't>),
    ) {
        let at = Path::Root(prefix);
        self.check(self.root, instance, &at, &mut Report::To(fail, &self.names));
    }

    /// Whether `instance` is valid, without making any failure.
    fn is_valid(&self, schema: usize, instance: Node) -> bool {
        let mut report = Report::Count(0);
        self.check(schema, instance, &Path::Root(""), &mut report);
        matches!(report, Report::Count(0))
    }

    fn check<'c, 't>(
        &'c self,
        id: usize,
        instance: Node<'t>,
        at: &Path,
        report: &mut Report<'_, 'c, 't>,
    ) {
        let schema = &self.schemas[id];
        let mut fail = |kind: Kind| report.fail(kind, instance, at, schema.definition);
        if !schema.types.is_empty() && !schema.types.iter().any(|t| is_of_type(instance, t)) {
            fail(Kind::Type(schema.types.join(", ")));
        }
        self.check_value(schema, instance, &mut fail);
        if let Some(object) = instance.as_object() {
            self.check_object(schema, instance, object, at, report);
        }
        if let Some(array) = instance.as_array() {
            self.check_array(schema, instance, array, at, report);
        }
        if let Some(reference) = schema.reference {
            self.check(reference, instance, at, report);
        }
        for &part in &schema.all_of {
            self.check(part, instance, at, report);
        }
        let mut fail = |kind: Kind| report.fail(kind, instance, at, schema.definition);
        if !schema.any_of.is_empty() && !schema.any_of.iter().any(|&s| self.is_valid(s, instance)) {
            fail(Kind::AnyOf);
        }
        let valid_choices = schema
            .one_of
            .iter()
            .filter(|&&s| self.is_valid(s, instance));
        if !schema.one_of.is_empty() && valid_choices.count() != 1 {
            fail(Kind::OneOf);
        }
        if let (Some(condition), Some(then)) = (schema.condition, schema.then) {
            if self.is_valid(condition, instance) {
                self.check(then, instance, at, report);
            }
        }
    }

    /// The keywords about a scalar's value (and `enum` / `const` of any value).
    fn check_value(&self, schema: &Schema, instance: Node, fail: &mut dyn FnMut(Kind)) {
        if let Some(number) = instance.as_f64() {
            let limits: [(Option<f64>, Holds, Kind); 4] = [
                (schema.minimum, |v, l| v >= l, Kind::Minimum),
                (schema.maximum, |v, l| v <= l, Kind::Maximum),
                (
                    schema.exclusive_minimum,
                    |v, l| v > l,
                    Kind::ExclusiveMinimum,
                ),
                (
                    schema.exclusive_maximum,
                    |v, l| v < l,
                    Kind::ExclusiveMaximum,
                ),
            ];
            for (limit, holds, kind) in limits {
                if limit.is_some_and(|limit| !holds(number, limit)) {
                    fail(kind);
                }
            }
            if let Some(multiple) = schema.multiple_of {
                if !is_multiple(instance, number, multiple) {
                    fail(Kind::MultipleOf(multiple));
                }
            }
        }
        if let Some(text) = instance.as_str() {
            if let Some((pattern, regex)) = &schema.pattern {
                if !regex.is_match(text) {
                    fail(Kind::Pattern(pattern.clone()));
                }
            }
            if let Some(limit) = schema.min_length {
                if (text.chars().count() as u64) < limit {
                    fail(Kind::MinLength { limit });
                }
            }
        }
        if let Some(options) = &schema.enumeration {
            let listed = options.as_array().into_iter().flatten();
            if !listed.clone().any(|option| equal(instance, option)) {
                fail(Kind::Enum(options.clone()));
            }
        }
        if schema
            .constant
            .as_ref()
            .is_some_and(|c| !equal(instance, c))
        {
            fail(Kind::Const);
        }
    }

    fn check_object<'c, 't>(
        &'c self,
        schema: &Schema,
        instance: Node<'t>,
        object: crate::document::Object<'t>,
        at: &Path,
        report: &mut Report<'_, 'c, 't>,
    ) {
        let mut fail = |kind: Kind| report.fail(kind, instance, at, schema.definition);
        if schema
            .min_properties
            .is_some_and(|n| (object.len() as u64) < n)
        {
            fail(Kind::MinProperties);
        }
        for name in &schema.required {
            if !object.contains_key(name) {
                fail(Kind::Required(name.clone()));
            }
        }
        for (key, needs) in &schema.dependent_required {
            if object.contains_key(key) {
                for missing in needs.iter().filter(|n| !object.contains_key(n)) {
                    fail(Kind::DependentRequired {
                        key: key.clone(),
                        missing: missing.clone(),
                    });
                }
            }
        }
        let declared = |key: &str| schema.properties.iter().find(|(name, _)| name == key);
        if matches!(schema.additional, Additional::None) {
            let unexpected: Vec<String> = (object.keys())
                .filter(|key| declared(key).is_none())
                .map(str::to_string)
                .collect();
            if !unexpected.is_empty() {
                fail(Kind::AdditionalProperties(unexpected));
            }
        }
        for (key, value) in object.iter() {
            let member = Path::Key(at, key);
            match (declared(key), &schema.additional) {
                (Some(&(_, property)), _) => self.check(property, value, &member, report),
                (None, Additional::Each(each)) => self.check(*each, value, &member, report),
                _ => {}
            }
        }
    }

    fn check_array<'c, 't>(
        &'c self,
        schema: &Schema,
        instance: Node<'t>,
        array: crate::document::Array<'t>,
        at: &Path,
        report: &mut Report<'_, 'c, 't>,
    ) {
        let mut fail = |kind: Kind| report.fail(kind, instance, at, schema.definition);
        let length = array.len() as u64;
        if let Some(limit) = schema.min_items.filter(|&limit| length < limit) {
            fail(Kind::MinItems(limit));
        }
        if let Some(limit) = schema.max_items.filter(|&limit| length > limit) {
            fail(Kind::MaxItems(limit));
        }
        if schema.unique_items {
            let valid = |element: Node| schema.items.is_none_or(|i| self.is_valid(i, element));
            let repeats = repeated_positions(array, valid);
            if !repeats.is_empty() {
                fail(Kind::UniqueItems(repeats));
            }
        }
        if let Some(items) = schema.items {
            for (i, element) in array.iter().enumerate() {
                self.check(items, element, &Path::Index(at, i), report);
            }
        }
    }
}

/// Whether a number (first) is within a limit (second).
type Holds = fn(f64, f64) -> bool;

/// Where failures go: to the caller, or only counted (inside `anyOf`, `oneOf`, `if`).
enum Report<'r, 'c, 't> {
    To(&'r mut dyn FnMut(Failure<'c, 't>), &'c [String]),
    Count(usize),
}

impl<'c, 't> Report<'_, 'c, 't> {
    fn fail(&mut self, kind: Kind, instance: Node<'t>, at: &Path, definition: Option<usize>) {
        match self {
            Report::To(fail, names) => fail(Failure {
                kind,
                instance,
                pointer: at.to_string(),
                definition: definition.and_then(|n| names.get(n)).map(String::as_str),
            }),
            Report::Count(n) => *n += 1,
        }
    }
}

/// An instance's place, made into a pointer only when something fails there.
enum Path<'p> {
    Root(&'p str),
    Key(&'p Path<'p>, &'p str),
    Index(&'p Path<'p>, usize),
}

impl std::fmt::Display for Path<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        match self {
            Path::Root(prefix) => f.write_str(prefix),
            Path::Key(parent, key) => write!(f, "{parent}/{}", escape_token(key)),
            Path::Index(parent, i) => write!(f, "{parent}/{i}"),
        }
    }
}

fn is_of_type(instance: Node, name: &str) -> bool {
    match name {
        "object" => instance.is_object(),
        "array" => instance.is_array(),
        "string" => instance.is_string(),
        "number" => instance.is_number(),
        // As 2020-12 says: a number with no fractional part (`1.0` too).
        "integer" => instance.as_f64().is_some_and(|v| v.fract() == 0.0),
        "boolean" => instance.is_boolean(),
        "null" => instance.is_null(),
        _ => false,
    }
}

fn is_multiple(instance: Node, number: f64, multiple: f64) -> bool {
    match (
        instance.as_u64(),
        multiple.fract() == 0.0 && multiple >= 1.0,
    ) {
        (Some(integer), true) => integer % multiple as u64 == 0,
        _ => (number / multiple).fract() == 0.0,
    }
}

/// JSON equality of a document value and a schema's, numbers compared by value.
fn equal(instance: Node, expected: &Value) -> bool {
    match expected {
        Value::Number(n) => instance.as_f64().is_some() && instance.as_f64() == n.as_f64(),
        Value::String(s) => instance.as_str() == Some(s.as_str()),
        Value::Bool(b) => instance.as_bool() == Some(*b),
        Value::Null => instance.is_null(),
        _ => instance.to_value() == *expected,
    }
}

/// Whether two elements of an array are equal as JSON Schema compares them (see
/// [`unique_key`]).
/// The positions of the elements that repeat an earlier one, among those `compared`.
fn repeated_positions(
    array: crate::document::Array,
    compared: impl Fn(Node) -> bool,
) -> Vec<usize> {
    let mut seen = HashSet::new();
    (array.iter().enumerate())
        .filter(|&(_, element)| compared(element) && !seen.insert(unique_key(element)))
        .map(|(i, _)| i)
        .collect()
}

/// What makes two array elements one for `uniqueItems`: numbers by value (`1`, `1.0` and
/// `-0.0`… `0` are one), anything else by its JSON text (every uniqueItems array of glTF
/// holds strings or integers; two objects that differ only in key order are two).
fn unique_key(element: Node) -> String {
    match element.as_f64() {
        Some(number) => format!("{}", number + 0.0),
        None => element.to_string(),
    }
}

struct Compiler {
    schemas: Vec<Schema>,
    definitions: HashMap<String, usize>,
}

impl Compiler {
    fn compile(&mut self, value: &Value, definition: Option<usize>) -> Result<usize, String> {
        let schema = self.schema(value, definition)?;
        self.schemas.push(schema);
        Ok(self.schemas.len() - 1)
    }

    fn schema(&mut self, value: &Value, definition: Option<usize>) -> Result<Schema, String> {
        let mut schema = Schema {
            definition,
            ..Schema::default()
        };
        let Some(members) = value.as_object() else {
            return match value {
                Value::Bool(true) => Ok(schema),
                _ => Err(format!("not a schema: {value}")),
            };
        };
        for (keyword, v) in members {
            self.keyword(&mut schema, keyword, v, definition)?;
        }
        Ok(schema)
    }

    fn keyword(
        &mut self,
        schema: &mut Schema,
        keyword: &str,
        v: &Value,
        definition: Option<usize>,
    ) -> Result<(), String> {
        let number = || v.as_f64().ok_or(format!("`{keyword}` is no number"));
        let count = || v.as_u64().ok_or(format!("`{keyword}` is no count"));
        match keyword {
            "type" => schema.types = type_names(v)?,
            "$ref" => schema.reference = Some(self.reference(v)?),
            "properties" => {
                for (name, property) in v.as_object().ok_or("`properties` is no object")? {
                    let property = self.compile(property, definition)?;
                    schema.properties.push((name.clone(), property));
                }
            }
            "additionalProperties" => {
                schema.additional = match v {
                    Value::Bool(false) => Additional::None,
                    Value::Bool(true) => Additional::Any,
                    _ => Additional::Each(self.compile(v, definition)?),
                }
            }
            "required" => schema.required = strings(v)?,
            "dependentRequired" => {
                for (key, needs) in v.as_object().ok_or("`dependentRequired` is no object")? {
                    schema
                        .dependent_required
                        .push((key.clone(), strings(needs)?));
                }
            }
            "minProperties" => schema.min_properties = Some(count()?),
            "items" => schema.items = Some(self.compile(v, definition)?),
            "minItems" => schema.min_items = Some(count()?),
            "maxItems" => schema.max_items = Some(count()?),
            "uniqueItems" => schema.unique_items = v.as_bool() == Some(true),
            "minimum" => schema.minimum = Some(number()?),
            "maximum" => schema.maximum = Some(number()?),
            "exclusiveMinimum" => schema.exclusive_minimum = Some(number()?),
            "exclusiveMaximum" => schema.exclusive_maximum = Some(number()?),
            "multipleOf" => schema.multiple_of = Some(number()?),
            "enum" => schema.enumeration = Some(v.clone()),
            "const" => schema.constant = Some(v.clone()),
            "pattern" => {
                let text = v.as_str().ok_or("`pattern` is no string")?;
                let regex = Regex::new(text).map_err(|e| e.to_string())?;
                schema.pattern = Some((text.to_string(), regex));
            }
            "minLength" => schema.min_length = Some(count()?),
            "allOf" | "anyOf" | "oneOf" => {
                let parts = v.as_array().ok_or(format!("`{keyword}` is no list"))?;
                let parts = (parts.iter())
                    .map(|part| self.compile(part, definition))
                    .collect::<Result<Vec<_>, _>>()?;
                match keyword {
                    "allOf" => schema.all_of = parts,
                    "anyOf" => schema.any_of = parts,
                    _ => schema.one_of = parts,
                }
            }
            "if" => schema.condition = Some(self.compile(v, definition)?),
            "then" => schema.then = Some(self.compile(v, definition)?),
            _ if ANNOTATIONS.contains(&keyword) => {}
            _ => return Err(format!("keyword `{keyword}` is not supported")),
        }
        Ok(())
    }

    fn reference(&self, v: &Value) -> Result<usize, String> {
        let target = v.as_str().ok_or("`$ref` is no string")?;
        let name = target
            .strip_prefix("#/$defs/")
            .ok_or(format!("`$ref` {target} is not to #/$defs"))?;
        self.definitions
            .get(name)
            .copied()
            .ok_or(format!("`$ref` {target} names no definition"))
    }
}

fn type_names(v: &Value) -> Result<Vec<&'static str>, String> {
    const NAMES: [&str; 7] = [
        "object", "array", "string", "number", "integer", "boolean", "null",
    ];
    let names = match v {
        Value::String(name) => vec![name.as_str()],
        Value::Array(names) => names.iter().filter_map(Value::as_str).collect(),
        _ => return Err("`type` is no name".into()),
    };
    (names.into_iter())
        .map(|name| {
            NAMES
                .into_iter()
                .find(|n| *n == name)
                .ok_or(format!("unknown type {name}"))
        })
        .collect()
}

fn strings(v: &Value) -> Result<Vec<String>, String> {
    (v.as_array().ok_or("not a list of names")?.iter())
        .map(|s| {
            s.as_str()
                .map(str::to_string)
                .ok_or("not a name".to_string())
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::document::Tree;
    use serde_json::json;

    fn failures(schema: &Value, instance: &str) -> Vec<(Kind, String)> {
        let compiled = Compiled::new(schema).unwrap();
        let tree = Tree::parse(instance.as_bytes()).unwrap();
        let mut found = Vec::new();
        compiled.evaluate(tree.root(), "", &mut |f| found.push((f.kind, f.pointer)));
        found
    }

    /// Each keyword judged as an independent evaluator (the `jsonschema` crate) judges it.
    #[test]
    fn every_keyword_agrees_with_jsonschema() {
        let cases = [
            (
                json!({"type": "integer"}),
                ["1", "1.0", "1.5", "\"1\"", "-3"].as_slice(),
            ),
            (
                json!({"type": "object", "required": ["a"]}),
                &["{}", "{\"a\":null}", "[]"],
            ),
            (
                json!({"properties": {"a": {"type": "string"}}, "additionalProperties": false}),
                &["{\"a\":\"x\"}", "{\"a\":1}", "{\"b\":1}", "7"],
            ),
            (
                json!({"additionalProperties": {"minimum": 0}}),
                &["{\"x\":-1}", "{\"x\":0}"],
            ),
            (
                json!({"items": {"maximum": 2}, "minItems": 2, "maxItems": 3}),
                &["[1,2]", "[1]", "[1,2,3,4]", "[1,5]"],
            ),
            (
                json!({"uniqueItems": true}),
                &["[1,2]", "[\"a\",\"a\"]", "[1,1.0]"],
            ),
            (
                json!({"exclusiveMinimum": 0, "exclusiveMaximum": 1}),
                &["0", "0.5", "1"],
            ),
            (json!({"multipleOf": 4}), &["8", "6", "8.0", "4.5"]),
            (json!({"enum": [9728, 9729]}), &["9728", "9729.0", "1"]),
            (
                json!({"pattern": "^([0-9]+)\\.([0-9]+)$"}),
                &["\"2.0\"", "\"2\"", "2"],
            ),
            (
                json!({"minLength": 1, "minProperties": 1}),
                &["\"\"", "\"a\"", "{}", "{\"a\":1}"],
            ),
            (
                json!({"dependentRequired": {"a": ["b"]}}),
                &["{\"a\":1}", "{\"a\":1,\"b\":2}", "{}"],
            ),
            (
                json!({"anyOf": [{"minimum": 1}, {"enum": [0]}]}),
                &["0", "0.5", "2"],
            ),
            (
                json!({"oneOf": [{"required": ["a"]}, {"required": ["b"]}]}),
                &["{\"a\":1}", "{\"a\":1,\"b\":1}", "{}"],
            ),
            (
                json!({"allOf": [{"if": {"properties": {"t": {"const": "x"}}, "required": ["t"]},
                              "then": {"required": ["v"]}}]}),
                &["{\"t\":\"x\"}", "{\"t\":\"y\"}", "{\"t\":\"x\",\"v\":1}"],
            ),
            (
                json!({"$defs": {"id": {"type": "integer", "minimum": 0}}, "items": {"$ref": "#/$defs/id"}}),
                &["[0,1]", "[-1]", "[\"a\"]"],
            ),
        ];
        for (schema, instances) in cases {
            let oracle = jsonschema::options().build(&schema).unwrap();
            for instance in instances {
                let value: Value = serde_json::from_str(instance).unwrap();
                let ours = failures(&schema, instance);
                assert_eq!(
                    ours.is_empty(),
                    oracle.is_valid(&value),
                    "{schema} on {instance}: {ours:?}"
                );
            }
        }
    }

    #[test]
    fn failures_carry_their_pointer_and_definition() {
        let schema = json!({"$defs": {"glTFid": {"type": "integer", "minimum": 0}},
                            "properties": {"a/b": {"items": {"$ref": "#/$defs/glTFid"}}}});
        let compiled = Compiled::new(&schema).unwrap();
        let tree = Tree::parse(br#"{"a/b": [0, -1]}"#).unwrap();
        let mut found = Vec::new();
        compiled.evaluate(tree.root(), "/x", &mut |f| {
            found.push((f.kind, f.pointer, f.definition.map(str::to_string)))
        });
        assert_eq!(
            found,
            [(
                Kind::Minimum,
                "/x/a~1b/1".to_string(),
                Some("glTFid".to_string())
            )]
        );
    }

    #[test]
    fn an_unknown_keyword_does_not_compile() {
        let error = Compiled::new(&json!({"patternProperties": {}}))
            .err()
            .unwrap();
        assert!(error.contains("patternProperties"), "{error}");
        assert!(Compiled::new(&json!({"$ref": "#/$defs/missing"})).is_err());
    }
}
