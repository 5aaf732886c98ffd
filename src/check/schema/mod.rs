//! Schema pass: the document against gltfmat's own JSON Schemas (schema/), embedded in the
//! binary and evaluated over the compact tree by [`evaluator`]. Each schema failure is
//! mapped to the Khronos code and pointer for the same finding.

mod evaluator;

use crate::diagnostic::{khronos, Code, Diagnostic, Sink};
use crate::document::json::escape_token;
use crate::document::{Array, Node};
use evaluator::{Compiled, Failure, Kind};
use serde_json::Value;
use std::collections::HashSet;
use std::sync::OnceLock;

const CORE: &str = include_str!("../../../schema/gltf.schema.json");

/// Extension schemas, merged into the core schema's `$defs` under their name.
const EXTENSIONS: &[(&str, &str)] = &[
    (
        "KHR_materials_anisotropy",
        include_str!("../../../schema/extensions/KHR_materials_anisotropy.schema.json"),
    ),
    (
        "KHR_materials_clearcoat",
        include_str!("../../../schema/extensions/KHR_materials_clearcoat.schema.json"),
    ),
    (
        "KHR_materials_diffuse_transmission",
        include_str!("../../../schema/extensions/KHR_materials_diffuse_transmission.schema.json"),
    ),
    (
        "KHR_materials_dispersion",
        include_str!("../../../schema/extensions/KHR_materials_dispersion.schema.json"),
    ),
    (
        "KHR_materials_emissive_strength",
        include_str!("../../../schema/extensions/KHR_materials_emissive_strength.schema.json"),
    ),
    (
        "KHR_materials_ior",
        include_str!("../../../schema/extensions/KHR_materials_ior.schema.json"),
    ),
    (
        "KHR_materials_iridescence",
        include_str!("../../../schema/extensions/KHR_materials_iridescence.schema.json"),
    ),
    (
        "KHR_materials_pbrSpecularGlossiness",
        include_str!("../../../schema/extensions/KHR_materials_pbrSpecularGlossiness.schema.json"),
    ),
    (
        "KHR_materials_sheen",
        include_str!("../../../schema/extensions/KHR_materials_sheen.schema.json"),
    ),
    (
        "KHR_materials_specular",
        include_str!("../../../schema/extensions/KHR_materials_specular.schema.json"),
    ),
    (
        "KHR_materials_transmission",
        include_str!("../../../schema/extensions/KHR_materials_transmission.schema.json"),
    ),
    (
        "KHR_materials_unlit",
        include_str!("../../../schema/extensions/KHR_materials_unlit.schema.json"),
    ),
    (
        "KHR_materials_variants",
        include_str!("../../../schema/extensions/KHR_materials_variants.schema.json"),
    ),
    (
        "KHR_materials_variants_mapping",
        include_str!("../../../schema/extensions/KHR_materials_variants_mapping.schema.json"),
    ),
    (
        "KHR_materials_volume",
        include_str!("../../../schema/extensions/KHR_materials_volume.schema.json"),
    ),
    (
        "KHR_texture_transform",
        include_str!("../../../schema/extensions/KHR_texture_transform.schema.json"),
    ),
    (
        "EXT_texture_webp",
        include_str!("../../../schema/extensions/EXT_texture_webp.schema.json"),
    ),
    (
        "KHR_texture_basisu",
        include_str!("../../../schema/extensions/KHR_texture_basisu.schema.json"),
    ),
    (
        "KHR_node_visibility",
        include_str!("../../../schema/extensions/KHR_node_visibility.schema.json"),
    ),
    (
        "KHR_animation_pointer",
        include_str!("../../../schema/extensions/KHR_animation_pointer.schema.json"),
    ),
    (
        "KHR_lights_punctual",
        include_str!("../../../schema/extensions/KHR_lights_punctual.schema.json"),
    ),
    (
        "KHR_lights_punctual_light",
        include_str!("../../../schema/extensions/KHR_lights_punctual_light.schema.json"),
    ),
    (
        "KHR_lights_punctual_node",
        include_str!("../../../schema/extensions/KHR_lights_punctual_node.schema.json"),
    ),
];

/// Extensions the Khronos validator does not implement: in its profile their objects are not
/// validated (it reports UNSUPPORTED_EXTENSION instead).
pub(crate) const NOT_IN_KHRONOS: &[&str] = &[
    "KHR_materials_diffuse_transmission",
    "KHR_node_visibility",
    "KHR_texture_basisu",
];

fn build(skip: &[&str]) -> Compiled {
    let mut root: Value =
        serde_json::from_str(CORE).expect("schema/gltf.schema.json is valid JSON");
    let defs = root["$defs"]
        .as_object_mut()
        .expect("core schema has $defs");
    // The validator asks for an image's mimeType on the members as it reads them (a
    // bufferView read as an index, a mimeType read as a string), not as they are written:
    // the image check owns that dependency.
    if let Some(image) = defs.get_mut("image").and_then(Value::as_object_mut) {
        image.remove("dependentRequired");
    }
    for (name, text) in EXTENSIONS {
        if skip.contains(name) {
            // Leave the extension unvalidated: drop its entry from every host's map.
            for def in defs.values_mut() {
                if let Some(props) = def.get_mut("properties").and_then(Value::as_object_mut) {
                    props.remove(*name);
                }
            }
            continue;
        }
        let mut schema: Value = serde_json::from_str(text).expect("extension schema is valid JSON");
        if let Some(map) = schema.as_object_mut() {
            map.remove("$schema");
        }
        defs.insert((*name).to_string(), schema);
    }
    Compiled::new(&root).expect("the embedded schemas compile")
}

fn validator(khronos: bool) -> &'static Compiled {
    static FULL: OnceLock<Compiled> = OnceLock::new();
    static KHRONOS: OnceLock<Compiled> = OnceLock::new();
    if khronos {
        KHRONOS.get_or_init(|| build(NOT_IN_KHRONOS))
    } else {
        FULL.get_or_init(|| build(&[]))
    }
}

/// Validates the document into `found` (Khronos-coded findings); returns the members the
/// Khronos validator reads as absent: those of the wrong type and the arrays a wrongly typed
/// element makes unreadable (see [`AbsentMembers`]).
pub(crate) fn validate(doc: Node, khronos: bool, found: &mut dyn Sink) -> HashSet<String> {
    let mut absent = AbsentMembers::new(found);
    diagnostics(validator(khronos), doc, "", &mut absent);
    absent.finish()
}

/// What the Khronos validator finds missing besides what the schema pass reported: a `null`
/// member is both of the wrong type and missing, and an extension object of the wrong type
/// is read as an empty one. Once such members are out of the tree (`nulls`) or empty
/// (`emptied`), the findings of the required members they leave missing. Validates again
/// only when there are any.
pub(crate) fn required_members(
    doc: Node,
    khronos: bool,
    nulls: &HashSet<String>,
    emptied: &HashSet<String>,
    sink: &mut dyn Sink,
) {
    if nulls.is_empty() && emptied.is_empty() {
        return;
    }
    validator(khronos).evaluate(doc, "", &mut |failure| {
        if let Kind::Required(name) = &failure.kind {
            if emptied.contains(&failure.pointer) || nulls.contains(&member(&failure.pointer, name))
            {
                map_failure(&failure).into_iter().for_each(|d| sink.push(d));
            }
        }
    });
}

/// Validates a glTF 1.0 PBR material extension object found at `pointer`.
pub(crate) fn validate_gltf1_pbr(extension: Node, pointer: &str) -> Vec<Diagnostic> {
    static PBR: OnceLock<Compiled> = OnceLock::new();
    let validator = PBR.get_or_init(|| {
        let schema: Value = serde_json::from_str(GLTF1_PBR).expect("1.0 PBR schema is valid JSON");
        Compiled::new(&schema).expect("the 1.0 PBR schema compiles")
    });
    let mut found = Vec::new();
    diagnostics(validator, extension, pointer, &mut found);
    found
}

const GLTF1_PBR: &str = include_str!("../../../schema/gltf1/materials_pbr.schema.json");

/// Every schema failure of `instance`, streamed into `sink` as it is found (a 10^7-element
/// array of wrong types is never held as 10^7 findings).
fn diagnostics(validator: &Compiled, instance: Node, prefix: &str, sink: &mut dyn Sink) {
    validator.evaluate(instance, prefix, &mut |failure| {
        map_failure(&failure).into_iter().for_each(|d| sink.push(d));
    });
}

/// Whether `pointer` is a value of a map of accessor indices: a primitive's `attributes` or
/// one of its morph `targets`.
fn is_index_map_value(pointer: &str) -> bool {
    let Some((map, _)) = pointer.rsplit_once('/') else {
        return false;
    };
    map.ends_with("/attributes")
        || map.rsplit_once('/').is_some_and(|(list, index)| {
            list.ends_with("/targets") && index.parse::<usize>().is_ok()
        })
}

/// The array holding the element at `pointer`, when that array is a property
/// (`/meshes/0/primitives/3` → `/meshes/0/primitives`, `/extensionsUsed/1` →
/// `/extensionsUsed`). Elements of the top-level collections are objects in their own right
/// and are reported where they are.
fn array_holding(pointer: &str) -> Option<&str> {
    let (parent, last) = pointer.rsplit_once('/')?;
    let element = !last.is_empty() && last.bytes().all(|b| b.is_ascii_digit());
    (element && !is_collection_element(pointer) && !parent.is_empty()).then_some(parent)
}

/// Between the schema findings and their sink: notes each member the Khronos validator
/// reads as absent (one of the wrong type, an array with a wrongly typed element or of the
/// wrong length), and drops what
/// was found at or inside such a member besides the finding that made it absent. Findings
/// are held until the end to see every such member first, up to [`HELD`]; past that they
/// pass on filtered by the members known so far, so memory stays bounded.
struct AbsentMembers<'s> {
    sink: &'s mut dyn Sink,
    held: Vec<Diagnostic>,
    /// Members read as absent, by pointer.
    absent: HashSet<String>,
    /// Arrays of the wrong length: their elements are not read (absent too).
    elements_unread: HashSet<String>,
    /// Integer members outside their range or list of values, absent too once the findings
    /// are in (a mistyped value is absent for its type, not for its value).
    out_of_range: HashSet<String>,
    /// Arrays absent for an element of the wrong type: their other elements are still read,
    /// each against its range, as the validator reads a list of numbers.
    element_mistyped: HashSet<String>,
}

/// An empty array where the schema wants a fixed length above 1 (read as absent, as an array
/// of a wrong length is).
fn is_empty_fixed_length(diagnostic: &Diagnostic) -> bool {
    diagnostic.code == khronos::EMPTY_ENTITY
        && (diagnostic.pointer())
            .and_then(|p| p.rsplit('/').next())
            .is_some_and(is_fixed_length_array)
}

/// A finding about a value outside its range or list of values.
fn is_value_finding(diagnostic: &Diagnostic) -> bool {
    matches!(
        diagnostic.code,
        khronos::VALUE_NOT_IN_RANGE | khronos::VALUE_NOT_IN_LIST | khronos::INVALID_INDEX
    )
}

/// Whether `pointer` is one of `members` or inside one.
pub(crate) fn at_or_inside(members: &HashSet<String>, pointer: &str) -> bool {
    let mut at = pointer;
    loop {
        if members.contains(at) {
            return true;
        }
        match at.rsplit_once('/') {
            Some((parent, _)) if !parent.is_empty() => at = parent,
            _ => return false,
        }
    }
}

/// Whether `pointer` is an element of a top-level collection (`/nodes/3`).
pub(crate) fn is_collection_element(pointer: &str) -> bool {
    let mut tokens = pointer.split('/').skip(1);
    match (tokens.next(), tokens.next(), tokens.next()) {
        (Some(collection), Some(_), None) => crate::gltf::COLLECTIONS.contains(&collection),
        _ => false,
    }
}

/// Arrays the Khronos validator keeps, without their wrongly typed elements: morph
/// targets are plain maps of accessor indices, read one by one.
const KEPT_ELEMENT_BY_ELEMENT: &[&str] = &["/targets"];

/// Whether the schemas type members named `name` as integers (`byteStride`, `texCoord`, …):
/// read from the schemas themselves, where no name is typed both integer and number.
fn is_integer_member(name: &str) -> bool {
    static NAMES: OnceLock<HashSet<String>> = OnceLock::new();
    let integer =
        |property: &Value| property.get("type").and_then(Value::as_str) == Some("integer");
    NAMES.get_or_init(|| members_where(integer)).contains(name)
}

/// Whether the schemas make members named `name` arrays of a fixed length above 1
/// (`translation`, `min`, `baseColorFactor`, …): an empty one is EMPTY_ENTITY to the validator.
fn is_fixed_length_array(name: &str) -> bool {
    static NAMES: OnceLock<HashSet<String>> = OnceLock::new();
    let fixed = |property: &Value| property.get("minItems").and_then(Value::as_u64) > Some(1);
    NAMES.get_or_init(|| members_where(fixed)).contains(name)
}

/// The names of the properties, anywhere in the embedded schemas, whose schema `holds`.
fn members_where(holds: fn(&Value) -> bool) -> HashSet<String> {
    fn collect(schema: &Value, holds: fn(&Value) -> bool, names: &mut HashSet<String>) {
        match schema {
            Value::Object(members) => {
                let properties = members.get("properties").and_then(Value::as_object);
                for (name, property) in properties.into_iter().flatten() {
                    if holds(property) {
                        names.insert(name.clone());
                    }
                }
                members.values().for_each(|v| collect(v, holds, names));
            }
            Value::Array(items) => items.iter().for_each(|v| collect(v, holds, names)),
            _ => {}
        }
    }
    let mut names = HashSet::new();
    for text in std::iter::once(CORE).chain(EXTENSIONS.iter().map(|(_, text)| *text)) {
        if let Ok(schema) = serde_json::from_str::<Value>(text) {
            collect(&schema, holds, &mut names);
        }
    }
    names
}

/// Schema findings held back at most (a file of 10^7 findings streams past them).
const HELD: usize = 1 << 16;

impl<'s> AbsentMembers<'s> {
    fn new(sink: &'s mut dyn Sink) -> Self {
        AbsentMembers {
            sink,
            held: Vec::new(),
            absent: Default::default(),
            elements_unread: Default::default(),
            out_of_range: Default::default(),
            element_mistyped: Default::default(),
        }
    }

    /// Passes the held findings on and gives the members read as absent, by pointer.
    fn finish(mut self) -> HashSet<String> {
        let out_of_range = std::mem::take(&mut self.out_of_range);
        self.out_of_range = (out_of_range.into_iter())
            .filter(|p| !self.at_or_inside_absent(p))
            .collect();
        self.absent.extend(self.out_of_range.iter().cloned());
        self.release();
        self.absent
    }

    fn release(&mut self) {
        for diagnostic in std::mem::take(&mut self.held) {
            if !self.inside_absent(&diagnostic) {
                self.sink.push(diagnostic);
            }
        }
    }

    fn inside_absent(&self, diagnostic: &Diagnostic) -> bool {
        let Some(pointer) = diagnostic.pointer() else {
            return false;
        };
        // An array of the wrong length is reported for its length only: its elements are
        // not read; nor are those of an array inside a member that is not read.
        if diagnostic.code == khronos::ARRAY_TYPE_MISMATCH {
            let array = array_holding(pointer).unwrap_or(pointer);
            let inside = array
                .rsplit_once('/')
                .is_some_and(|(parent, _)| self.at_or_inside_absent(parent));
            return inside || self.elements_unread.contains(array);
        }
        // The finding that made a member absent stays, and a member demands the others it
        // depends on whatever it holds (the validator asks only whether it is there): unless
        // it lies inside a member that is not read (an element of an array of objects one of
        // whose elements is no object, say).
        if matches!(
            diagnostic.code,
            khronos::TYPE_MISMATCH
                | khronos::ARRAY_LENGTH_NOT_IN_LIST
                | khronos::UNSATISFIED_DEPENDENCY
        ) {
            return self.parent_unread(pointer);
        }
        // An element outside its range, or repeated, in an array read element by element
        // stays (unless the array's own parent is not read).
        let read_elements = array_holding(pointer)
            .filter(|array| self.element_mistyped.contains(*array))
            .filter(|array| !self.elements_unread.contains(*array));
        let element_finding =
            is_value_finding(diagnostic) || diagnostic.code == khronos::DUPLICATE_ELEMENTS;
        if let Some(array) = read_elements.filter(|_| element_finding) {
            return self.parent_unread(array);
        }
        // The finding that made an integer or an empty fixed-length array absent stays
        // (unless its parent is not read).
        let made_absent = (self.out_of_range.contains(pointer) && is_value_finding(diagnostic))
            || is_empty_fixed_length(diagnostic);
        if made_absent {
            return self.parent_unread(pointer);
        }
        // At the member itself (a mistyped value is not also outside its list of values) or
        // inside it.
        self.at_or_inside_absent(pointer)
    }

    fn at_or_inside_absent(&self, pointer: &str) -> bool {
        at_or_inside(&self.absent, pointer)
    }

    /// Whether the member holding `pointer` is not read (the root always is).
    fn parent_unread(&self, pointer: &str) -> bool {
        let parent = pointer.rsplit_once('/').map_or("", |(parent, _)| parent);
        !parent.is_empty() && self.at_or_inside_absent(parent)
    }
}

impl Sink for AbsentMembers<'_> {
    fn push(&mut self, diagnostic: Diagnostic) {
        // A member of the wrong type is read as absent, as the Khronos validator reads it
        // (an accessor whose `min` is a string has no bounds).
        // (Not an element of a top-level collection: it cannot be taken out, and 10^7
        // mistyped nodes must not be 10^7 remembered pointers.)
        if diagnostic.code == khronos::TYPE_MISMATCH {
            let member = diagnostic
                .pointer()
                .filter(|p| !is_collection_element(p) && !p.is_empty());
            if let Some(pointer) = member {
                self.absent.insert(pointer.to_string());
            }
        }
        // So is an integer member outside its range or list of values: the validator reads
        // an out-of-range byteStride as no stride. (A number or a name outside its range or
        // list is still present: an alphaCutoff of -1 still needs MASK.) Only a member is
        // named so: an array's element (its last token a number) stays, as the validator
        // keeps the array.
        // (A negative index, INVALID_INDEX, is such a member whatever its schema spells.)
        let integer = |p: &&str| {
            let name = p.rsplit('/').next().unwrap_or_default();
            is_integer_member(name)
                || diagnostic.code == khronos::INVALID_INDEX && name.parse::<u64>().is_err()
        };
        // A wrong value in a map of accessor indices stays: the validator reads the map's
        // names before their values, so the name is still judged (MESH_PRIMITIVE_INVALID_ATTRIBUTE).
        let member = Some(&diagnostic)
            .filter(|d| is_value_finding(d))
            .and_then(Diagnostic::pointer)
            .filter(integer)
            .filter(|p| !is_index_map_value(p));
        if let Some(pointer) = member {
            self.out_of_range.insert(pointer.to_string());
        }
        if diagnostic.code == khronos::ARRAY_LENGTH_NOT_IN_LIST
            || is_empty_fixed_length(&diagnostic)
        {
            if let Some(pointer) = diagnostic.pointer() {
                self.elements_unread.insert(pointer.to_string());
                self.absent.insert(pointer.to_string());
            }
        }
        if diagnostic.code == khronos::ARRAY_TYPE_MISMATCH {
            if let Some(pointer) = diagnostic.pointer() {
                // At the array, or, for a list of names, at the element.
                let array = array_holding(pointer).unwrap_or(pointer);
                if !KEPT_ELEMENT_BY_ELEMENT
                    .iter()
                    .any(|name| array.ends_with(name))
                {
                    self.absent.insert(array.to_string());
                    self.element_mistyped.insert(array.to_string());
                }
            }
        }
        if self.held.len() < HELD {
            self.held.push(diagnostic);
        } else {
            self.release();
            if !self.inside_absent(&diagnostic) {
                self.sink.push(diagnostic);
            }
        }
    }
}

fn member(pointer: &str, key: &str) -> String {
    format!("{pointer}/{}", escape_token(key))
}

fn show(value: impl std::fmt::Display) -> String {
    let text = value.to_string();
    if text.len() > 60 {
        format!(
            "{}…",
            &text[..text.char_indices().nth(57).map_or(text.len(), |c| c.0)]
        )
    } else {
        text
    }
}

fn map_failure(failure: &Failure) -> Vec<Diagnostic> {
    let pointer = failure.pointer.as_str();
    match &failure.kind {
        Kind::Type(expected) => vec![type_mismatch(expected, failure.instance, pointer)],
        Kind::AdditionalProperties(unexpected) => (unexpected.iter())
            .map(|key| {
                Diagnostic::at(
                    khronos::UNEXPECTED_PROPERTY,
                    member(pointer, key),
                    "Unexpected property.",
                )
            })
            .collect(),
        Kind::UniqueItems(repeats) => (repeats.iter())
            .map(|i| {
                Diagnostic::at(
                    khronos::DUPLICATE_ELEMENTS,
                    format!("{pointer}/{i}"),
                    "Duplicate element.",
                )
            })
            .collect(),
        _ => (one_finding(failure).into_iter())
            .map(|(code, at, message)| Diagnostic::at(code, at, message))
            .collect(),
    }
}

/// The finding of a failure that makes at most one: its code, pointer and message.
fn one_finding(failure: &Failure) -> Option<(Code, String, String)> {
    let Failure {
        kind,
        instance,
        pointer,
        definition,
    } = failure;
    let instance = *instance;
    let at = pointer.to_string();
    Some(match kind {
        Kind::DependentRequired { key, missing } => (
            khronos::UNSATISFIED_DEPENDENCY,
            member(pointer, key),
            format!("Dependency failed. '{missing}' must be defined."),
        ),
        Kind::Required(name) => (
            khronos::UNDEFINED_PROPERTY,
            if pointer.is_empty() { "/".into() } else { at },
            format!("Property '{name}' must be defined."),
        ),
        Kind::Minimum | Kind::Maximum | Kind::ExclusiveMinimum | Kind::ExclusiveMaximum
            if *definition == Some("glTFid") =>
        {
            (khronos::INVALID_INDEX, at, INDEX_MESSAGE.into())
        }
        Kind::Minimum
        | Kind::Maximum
        | Kind::ExclusiveMinimum
        | Kind::ExclusiveMaximum
        | Kind::AnyOf => (
            khronos::VALUE_NOT_IN_RANGE,
            at,
            format!("Value {} is out of range.", show(instance)),
        ),
        Kind::Enum(options) => (
            khronos::VALUE_NOT_IN_LIST,
            at,
            format!(
                "Invalid value {}. Valid values are {}.",
                show(instance),
                show(options)
            ),
        ),
        // An empty array of a fixed length is empty to the validator, not of a wrong length.
        Kind::MinItems(1) | Kind::MinProperties => (khronos::EMPTY_ENTITY, at, EMPTY.into()),
        Kind::MinItems(_) if instance.as_array().is_some_and(Array::is_empty) => {
            (khronos::EMPTY_ENTITY, at, EMPTY.into())
        }
        Kind::MinItems(limit) | Kind::MaxItems(limit) => (
            khronos::ARRAY_LENGTH_NOT_IN_LIST,
            at,
            format!(
                "Invalid array length {}. Valid lengths are: {limit}.",
                instance.as_array().map_or(0, Array::len)
            ),
        ),
        Kind::MultipleOf(multiple_of) => (
            khronos::VALUE_MULTIPLE_OF,
            at,
            format!(
                "Value {} is not a multiple of {multiple_of}.",
                show(instance)
            ),
        ),
        Kind::Pattern(pattern) => (
            khronos::PATTERN_MISMATCH,
            at,
            format!(
                "Value {} does not match regexp pattern '{pattern}'.",
                show(instance)
            ),
        ),
        Kind::MinLength { .. } | Kind::Const => (
            khronos::TYPE_MISMATCH,
            at,
            format!("Schema violation: {kind:?}"),
        ),
        // An image's `uri` / `bufferView` choice is counted by the images pass on the members
        // as read (one of the wrong type is absent); a number's (KHR_materials_ior's 0 or ≥ 1)
        // is reported as its range.
        Kind::OneOf => return None,
        // Made by `map_failure`: a type's finding, or one per member or element.
        Kind::Type(_) | Kind::AdditionalProperties(_) | Kind::UniqueItems(_) => return None,
    })
}

/// What an empty array or object is told.
const EMPTY: &str = "Entity cannot be empty.";

/// What a wrong index is told.
const INDEX_MESSAGE: &str = "Index must be a non-negative integer.";

/// A value of another type than the schema's `expected`, reported as the Khronos validator
/// reports it: an element of a property's array by what the array holds (a wrong index where
/// it is, the others kept; a wrong number or object at the array, which is then unreadable;
/// a wrong name of a string list where it is, the list unreadable); a wrong index in a map of
/// indices where it is, the map kept; any other value where it is.
fn type_mismatch(expected: &str, instance: Node, pointer: &str) -> Diagnostic {
    let at = |code, at: &str, message: String| Diagnostic::at(code, at.to_string(), message);
    if let Some(array) = array_holding(pointer) {
        let mismatch = format!(
            "Type mismatch. Array element {} is not a '{expected}'.",
            show(instance)
        );
        return match expected {
            "integer" => at(khronos::INVALID_INDEX, pointer, INDEX_MESSAGE.into()),
            "string" => at(khronos::ARRAY_TYPE_MISMATCH, pointer, mismatch),
            _ => at(khronos::ARRAY_TYPE_MISMATCH, array, mismatch),
        };
    }
    if is_index_map_value(pointer) && expected == "integer" {
        return at(khronos::INVALID_INDEX, pointer, INDEX_MESSAGE.into());
    }
    let message = format!(
        "Type mismatch. Property value {} is not a '{expected}'.",
        show(instance)
    );
    at(khronos::TYPE_MISMATCH, pointer, message)
}

/// Indices of array elements equal to an earlier element.
#[cfg(test)]
mod tests {
    use super::*;
    use crate::document::Tree;
    use serde_json::json;

    fn codes(doc: Value) -> Vec<(String, String)> {
        let mut found = Vec::new();
        let tree = Tree::parse(doc.to_string().as_bytes()).unwrap();
        validate(tree.root(), true, &mut found);
        found
            .into_iter()
            .map(|d| (d.code.to_string(), d.pointer().unwrap().to_string()))
            .collect()
    }

    #[test]
    fn a_minimal_document_is_valid() {
        assert!(codes(json!({"asset": {"version": "2.0"}})).is_empty());
    }

    #[test]
    fn errors_map_to_khronos_codes_and_pointers() {
        let found = codes(json!({
            "asset": {"version": "2.0", "x": 1},
            "materials": [{"pbrMetallicRoughness": {"baseColorFactor": [1, 1, 2, 1]}}],
            "bufferViews": [{}],
            "samplers": [{"magFilter": 1}],
            "extensionsRequired": ["A_b"]
        }));
        for expected in [
            (khronos::UNEXPECTED_PROPERTY, "/asset/x"),
            (
                khronos::VALUE_NOT_IN_RANGE,
                "/materials/0/pbrMetallicRoughness/baseColorFactor/2",
            ),
            (khronos::UNDEFINED_PROPERTY, "/bufferViews/0"),
            (khronos::VALUE_NOT_IN_LIST, "/samplers/0/magFilter"),
            (khronos::UNSATISFIED_DEPENDENCY, "/extensionsRequired"),
        ] {
            assert!(
                found.contains(&(expected.0.to_string(), expected.1.to_string())),
                "{expected:?} not in {found:?}"
            );
        }
    }

    #[test]
    fn extension_objects_are_validated_on_their_host() {
        let found = codes(
            json!({"asset": {"version": "2.0"}, "materials": [{"extensions": {
            "KHR_materials_sheen": {"sheenRoughnessFactor": 2}}}]}),
        );
        assert_eq!(
            found,
            vec![(
                khronos::VALUE_NOT_IN_RANGE.to_string(),
                "/materials/0/extensions/KHR_materials_sheen/sheenRoughnessFactor".to_string()
            )]
        );
    }
}
