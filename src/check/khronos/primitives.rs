//! Mesh primitives as the Khronos validator checks them: attribute semantic names and their
//! numbering, accessor formats per semantic (widened by KHR_mesh_quantization), alignment,
//! equal counts, byteStride for shared views, index formats, draw mode counts, and morph
//! targets against their base attributes.

use crate::check::context::{elements, member, unsigned, Context};
use crate::diagnostic::khronos;
use crate::document::{Array, Node, Object};
use crate::gltf::accessor::{component_count, component_size, element_lengths};
use crate::gltf::as_index;
use std::collections::{HashMap, HashSet};

use crate::gltf::gl::{BYTE, FLOAT, SHORT, UNSIGNED_BYTE, UNSIGNED_INT, UNSIGNED_SHORT};

/// An accessor's type, component type and `normalized` flag.
#[derive(Clone, Copy)]
pub(super) struct Format<'a> {
    kind: &'a str,
    component_type: u64,
    normalized: bool,
}

impl<'a> Format<'a> {
    /// The accessor's format as the Khronos validator reads it: a type or component type
    /// that is missing or not of its kind reads as none, which no format rule allows (it
    /// is still an invalid format for the attribute, output or matrices it holds).
    pub(super) fn of(accessor: Node<'a>) -> Self {
        Format {
            kind: accessor.get("type").and_then(Node::as_str).unwrap_or(""),
            component_type: unsigned(accessor, "componentType").unwrap_or(0),
            normalized: accessor.get("normalized").and_then(Node::as_bool) == Some(true),
        }
    }

    /// Whether the accessor declares both bounds in a form that can be read: the Khronos
    /// validator reads `min` and `max` by the type and component type, so with either of
    /// those missing or invalid an accessor has no bounds.
    pub(super) fn has_bounds(accessor: Node) -> bool {
        let format = Format::of(accessor);
        let readable = component_size(format.component_type).is_some()
            && component_count(format.kind).is_some();
        readable && accessor.get("min").is_some() && accessor.get("max").is_some()
    }

    pub(super) fn is_float(self) -> bool {
        self.component_type == FLOAT
    }

    /// Whether this is `kind` with non-normalised float components.
    pub(super) fn is_plain_float(self, kind: &str) -> bool {
        self.kind == kind && self.component_type == FLOAT && !self.normalized
    }

    /// Whether this format may hold animation output for a channel `path`; None for paths
    /// with no format rule.
    pub(super) fn allowed_for_animation(self, path: &str) -> Option<bool> {
        let t = self.component_type;
        let float = t == FLOAT && !self.normalized;
        let normalized_int =
            self.normalized && matches!(t, BYTE | UNSIGNED_BYTE | SHORT | UNSIGNED_SHORT);
        let allowed = match path {
            "translation" | "scale" => self.kind == "VEC3" && float,
            "rotation" => self.kind == "VEC4" && (float || normalized_int),
            "weights" => self.kind == "SCALAR" && (float || normalized_int),
            _ => return None,
        };
        Some(allowed)
    }

    /// Whether this format may hold the attribute `semantic` (of a morph target when
    /// `morph`); None when the semantic has no format rule (custom or invalid names).
    pub(super) fn allowed_for(self, semantic: &str, morph: bool, quantized: bool) -> Option<bool> {
        let Format {
            kind,
            component_type: t,
            normalized: n,
        } = self;
        let float = t == FLOAT && !n;
        let signed = matches!(t, BYTE | SHORT);
        let unsigned_small = matches!(t, UNSIGNED_BYTE | UNSIGNED_SHORT);
        let base = semantic.split('_').next().unwrap_or(semantic);
        let allowed = match (base, morph) {
            ("POSITION", false) => {
                kind == "VEC3" && (float || quantized && (signed || unsigned_small))
            }
            ("POSITION", true) => kind == "VEC3" && (float || quantized && signed),
            ("NORMAL", _) => kind == "VEC3" && (float || quantized && n && signed),
            ("TANGENT", false) => kind == "VEC4" && (float || quantized && n && signed),
            ("TANGENT", true) => kind == "VEC3" && (float || quantized && n && signed),
            ("TEXCOORD", false) => {
                kind == "VEC2"
                    && (float || n && unsigned_small || quantized && (signed || unsigned_small))
            }
            ("TEXCOORD", true) => {
                kind == "VEC2" && (float || n && (signed || unsigned_small) || quantized && signed)
            }
            ("COLOR", false) => matches!(kind, "VEC3" | "VEC4") && (float || n && unsigned_small),
            ("COLOR", true) => {
                matches!(kind, "VEC3" | "VEC4") && (float || n && (signed || unsigned_small))
            }
            ("JOINTS", false) => kind == "VEC4" && !n && unsigned_small,
            ("WEIGHTS", false) => kind == "VEC4" && (float || n && unsigned_small),
            _ => return None,
        };
        Some(allowed)
    }
}

/// How many morph targets a mesh has, as its first primitive lists them (None when it lists
/// none, or a list the validator ignores: see [`morph_targets`]): what node weights and
/// weight animations are counted against.
pub(super) fn mesh_morph_targets(mesh: Node) -> Option<usize> {
    let first = mesh.get("primitives")?.as_array()?.first()?;
    Some(morph_targets(first)?.len())
}

/// A primitive's morph targets when they are a non-empty list of non-empty objects; any
/// other form is a schema error, and the list is then ignored, as the Khronos validator does.
pub(super) fn morph_targets(primitive: Node) -> Option<Array> {
    let targets = primitive.get("targets")?.as_array()?;
    let valid = !targets.is_empty()
        && targets
            .iter()
            .all(|t| t.as_object().is_some_and(|o| !o.is_empty()));
    valid.then_some(targets)
}

/// The index of an indexed semantic (`TEXCOORD_1` → 1): digits only, no leading zero.
fn semantic_index(digits: &str) -> Option<u64> {
    let valid = !digits.is_empty()
        && digits.bytes().all(|b| b.is_ascii_digit())
        && !(digits.len() > 1 && digits.starts_with('0'));
    valid.then(|| digits.parse().ok()).flatten()
}

/// Whether `semantic` is a valid attribute name (custom `_` names always are); for indexed
/// semantics, also its family and index.
fn classify(semantic: &str, morph: bool) -> Result<Option<(&str, u64)>, ()> {
    if semantic.starts_with('_') || matches!(semantic, "POSITION" | "NORMAL" | "TANGENT") {
        return Ok(None);
    }
    let families: &[&str] = if morph {
        &["COLOR", "TEXCOORD"]
    } else {
        &["COLOR", "JOINTS", "TEXCOORD", "WEIGHTS"]
    };
    match semantic.split('_').collect::<Vec<_>>()[..] {
        [family, digits] if families.contains(&family) => {
            semantic_index(digits).map(|i| Some((family, i))).ok_or(())
        }
        _ => Err(()),
    }
}

/// Per indexed family (COLOR, JOINTS, TEXCOORD, WEIGHTS): how many validly named sets a
/// primitive has, and the largest index.
fn indexed_families(attributes: Object<'_>) -> HashMap<&str, (u64, u64)> {
    let mut families: HashMap<&str, (u64, u64)> = HashMap::new();
    for semantic in attributes.keys() {
        if let Ok(Some((family, index))) = classify(semantic, false) {
            let entry = families.entry(family).or_insert((0, 0));
            entry.0 += 1;
            entry.1 = entry.1.max(index);
        }
    }
    families
}

/// How many sets of an indexed family a renderer reads: all of them when they are numbered
/// 0, 1, … without gaps, none otherwise (as the Khronos validator counts them).
pub(super) fn indexed_sets(attributes: Object, family: &str) -> u64 {
    match indexed_families(attributes).get(family) {
        Some(&(count, largest)) if largest + 1 == count => count,
        _ => 0,
    }
}

/// The skinning sets a primitive has: JOINTS_n and WEIGHTS_n in equal number, else none.
pub(super) fn joint_sets(attributes: Object) -> u64 {
    let joints = indexed_sets(attributes, "JOINTS");
    if joints == indexed_sets(attributes, "WEIGHTS") {
        joints
    } else {
        0
    }
}

pub(crate) fn check(ctx: &mut Context) {
    let quantized = ctx.uses_extension("KHR_mesh_quantization");
    let mut walk = Walk {
        ctx,
        quantized,
        view_accessors: HashMap::new(),
    };
    for (_, pointer, mesh) in walk.ctx.objects("meshes") {
        walk.mesh(mesh, &pointer);
    }
}

struct Walk<'c, 'a> {
    ctx: &'c mut Context<'a>,
    quantized: bool,
    /// Vertex accessors seen per bufferView without byteStride.
    view_accessors: HashMap<u64, HashSet<u64>>,
}

impl<'a> Walk<'_, 'a> {
    fn mesh(&mut self, mesh: Node<'a>, pointer: &str) {
        let primitives: Vec<Node> = elements(mesh, "primitives").map(|(_, p)| p).collect();
        let target_count = |p: Node| morph_targets(p).map_or(0, Array::len);
        let first_count = primitives.first().map_or(0, |&p| target_count(p));
        for (i, primitive) in primitives.iter().enumerate().filter(|(_, p)| p.is_object()) {
            let at = format!("{pointer}/primitives/{i}");
            let count = target_count(*primitive);
            if i > 0 && count != first_count {
                let where_ = if count > 0 {
                    member(&at, "targets")
                } else {
                    at.clone()
                };
                self.ctx.emit(
                    khronos::MESH_PRIMITIVES_UNEQUAL_TARGETS_COUNT,
                    where_,
                    "All primitives must have the same number of morph targets.",
                );
            }
            self.primitive(*primitive, &at);
        }
        // An empty list of weights (EMPTY_ENTITY) is none, as the validator reads it.
        let weights = mesh.get("weights").and_then(Node::as_array);
        if let Some(weights) = weights.filter(|w| !w.is_empty()) {
            if !primitives.is_empty() && weights.len() != first_count {
                self.ctx.emit(
                    khronos::MESH_INVALID_WEIGHTS_COUNT,
                    member(pointer, "weights"),
                    format!("The length of weights array ({}) does not match the number of morph targets ({first_count}).", weights.len()),
                );
            }
        }
    }

    fn primitive(&mut self, primitive: Node<'a>, pointer: &str) {
        let attributes = primitive
            .get("attributes")
            .and_then(Node::as_object)
            .filter(|a| !a.is_empty());
        if let Some(attributes) = attributes {
            self.names(attributes, &member(pointer, "attributes"));
        }
        let vertex_count = self.attributes(attributes, pointer);
        // Drawn by its indices when they resolve (an index accessor without a count is not
        // checked against the mode, as the Khronos validator does not), else by its vertices.
        let drawn_count = self.indices(primitive, pointer).unwrap_or(vertex_count);
        self.mode(primitive, pointer, drawn_count);
        // Every target's names are read; its accessors only when the whole list is one the
        // validator links (see [`morph_targets`]).
        let linked = morph_targets(primitive).is_some();
        for (t, target) in elements(primitive, "targets") {
            let at = format!("{pointer}/targets/{t}");
            if let Some(target) = target.as_object() {
                self.target(target, attributes, &at, linked);
            }
        }
    }

    /// Semantic names, their numbering, and the sets every primitive needs.
    fn names(&mut self, attributes: Object, at: &str) {
        for semantic in attributes.keys() {
            if !self.valid_name(semantic, false) {
                self.invalid_name(&member(at, semantic));
            }
        }
        if !attributes.contains_key("POSITION") {
            self.ctx.emit(
                khronos::MESH_PRIMITIVE_NO_POSITION,
                at,
                "No POSITION attribute found.",
            );
        }
        let families = indexed_families(attributes);
        for family in ["COLOR", "JOINTS", "TEXCOORD", "WEIGHTS"] {
            let (count, largest) = families.get(family).copied().unwrap_or((0, 0));
            if count > 0 && largest + 1 != count {
                self.ctx.emit(
                    khronos::MESH_PRIMITIVE_INDEXED_SEMANTIC_CONTINUITY,
                    at,
                    format!("Indices for indexed attribute semantic '{family}' must start with 0 and be continuous. Total expected indices: {}, total provided indices: {count}.", largest + 1),
                );
            }
        }
        let (joints, weights) = (
            indexed_sets(attributes, "JOINTS"),
            indexed_sets(attributes, "WEIGHTS"),
        );
        if joints != weights {
            self.ctx.emit(
                khronos::MESH_PRIMITIVE_JOINTS_WEIGHTS_MISMATCH,
                at,
                format!("Number of JOINTS attribute semantics ({joints}) does not match the number of WEIGHTS ({weights})."),
            );
        }
    }

    /// Whether `semantic` is a valid attribute name (in a morph target when `morph`): a
    /// core or `_` one, or, in a profile that reads them, `<extension>:<name>` after an
    /// extension `extensionsUsed` declares.
    fn valid_name(&self, semantic: &str, morph: bool) -> bool {
        let extension = || {
            let named = semantic
                .split_once(':')
                .filter(|(_, name)| !name.is_empty());
            named.is_some_and(|(extension, _)| self.ctx.uses_extension(extension))
        };
        let profile = self.ctx.options.profile;
        classify(semantic, morph).is_ok()
            || (profile.reads_extension_attribute_semantics() && extension())
    }

    fn invalid_name(&mut self, at: &str) {
        self.ctx.emit(
            khronos::MESH_PRIMITIVE_INVALID_ATTRIBUTE,
            at,
            "Invalid attribute name.",
        );
    }

    /// The attributes' accessors; returns the vertex count (see [`vertex_count`]).
    fn attributes(&mut self, attributes: Option<Object<'a>>, pointer: &str) -> Option<f64> {
        let mut vertex_count = None;
        for (semantic, value) in attributes.into_iter().flatten() {
            let at = format!(
                "{pointer}/attributes/{}",
                crate::document::json::escape_token(semantic)
            );
            let Some(accessor) = self.accessor(value) else {
                continue;
            };
            // A missing or unreadable count (the validator's -1) differs from any count
            // before it, and leaves the vertex count to the next attribute.
            let count = count_of(accessor);
            match vertex_count {
                None => vertex_count = count,
                Some(n) if count != Some(n) => self.ctx.emit(
                    khronos::MESH_PRIMITIVE_UNEQUAL_ACCESSOR_COUNT,
                    at.clone(),
                    "All accessors of the same primitive must have the same count.",
                ),
                Some(_) => {}
            }
            self.vertex_accessor(accessor, value, semantic, &at, false);
        }
        vertex_count
    }

    /// The checks every vertex accessor gets, in attributes and in morph targets.
    fn vertex_accessor(
        &mut self,
        accessor: Node<'a>,
        index: Node,
        semantic: &str,
        at: &str,
        morph: bool,
    ) {
        if semantic == "POSITION" && !Format::has_bounds(accessor) {
            self.ctx.emit(
                khronos::MESH_PRIMITIVE_POSITION_ACCESSOR_WITHOUT_BOUNDS,
                at,
                "accessor.min and accessor.max must be defined for POSITION attribute accessor.",
            );
        }
        let format = Format::of(accessor);
        match format.allowed_for(semantic, morph, self.quantized) {
            Some(false) => self.ctx.emit(
                khronos::MESH_PRIMITIVE_ATTRIBUTES_ACCESSOR_INVALID_FORMAT,
                at,
                "Invalid accessor format for this attribute semantic.",
            ),
            None if !morph && format.component_type == UNSIGNED_INT => self.ctx.emit(
                khronos::MESH_PRIMITIVE_ATTRIBUTES_ACCESSOR_UNSIGNED_INT,
                at,
                "Mesh attributes cannot use UNSIGNED_INT component type.",
            ),
            _ => {}
        }
        let view = unsigned(accessor, "bufferView")
            .filter(|v| self.ctx.element("bufferViews", *v).is_some());
        let strided = self.ctx.has_strided_view(accessor);
        // The validator measures an element to the end of its data: a matrix of bytes is
        // 6 or 11 long, never a multiple of 4, before its padding.
        let element = component_size(format.component_type)
            .map(|size| element_lengths(format.kind, size).1)
            .filter(|&data| data > 0);
        let offset = unsigned(accessor, "byteOffset").unwrap_or(0);
        let unpadded = element.is_some_and(|e| e % 4 != 0) && view.is_some() && !strided;
        if !offset.is_multiple_of(4) || unpadded {
            self.ctx.emit(
                khronos::MESH_PRIMITIVE_ACCESSOR_UNALIGNED,
                at,
                "Vertex attribute data must be aligned to 4-byte boundaries.",
            );
        }
        if let (Some(view), false) = (view, strided) {
            let seen = self.view_accessors.entry(view).or_default();
            if seen.insert(as_index(index).unwrap_or(u64::MAX)) && seen.len() > 1 {
                self.ctx.emit(
                    khronos::MESH_PRIMITIVE_ACCESSOR_WITHOUT_BYTESTRIDE,
                    at,
                    "bufferView.byteStride must be defined when two or more accessors use the same buffer view.",
                );
            }
        }
    }

    /// Returns the index accessor's count, when `indices` resolves to one.
    fn indices(&mut self, primitive: Node<'a>, pointer: &str) -> Option<Option<f64>> {
        let value = primitive.get("indices")?;
        let accessor = self.accessor(value)?;
        let at = member(pointer, "indices");
        if self.ctx.has_strided_view(accessor) {
            self.ctx.emit(
                khronos::MESH_PRIMITIVE_INDICES_ACCESSOR_WITH_BYTESTRIDE,
                at.clone(),
                "bufferView.byteStride must not be defined for indices accessor.",
            );
        }
        let f = Format::of(accessor);
        let valid = f.kind == "SCALAR"
            && !f.normalized
            && matches!(
                f.component_type,
                UNSIGNED_BYTE | UNSIGNED_SHORT | UNSIGNED_INT
            );
        if !valid {
            self.ctx.emit(
                khronos::MESH_PRIMITIVE_INDICES_ACCESSOR_INVALID_FORMAT,
                at,
                "Invalid indices accessor format. Must be one of SCALAR UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT.",
            );
        }
        Some(count_of(accessor))
    }

    /// The vertex or index count must suit the draw mode.
    fn mode(&mut self, primitive: Node, pointer: &str, count: Option<f64>) {
        let Some(count) = count else { return };
        // An invalid mode (reported by the schema pass) suits no count.
        let Some(mode) = mode_of(primitive) else {
            return;
        };
        let incompatible = match mode {
            1 => count % 2.0 != 0.0,
            2 | 3 => count < 2.0,
            4 => count % 3.0 != 0.0,
            5 | 6 => count < 3.0,
            _ => false,
        };
        if incompatible {
            let names = [
                "POINTS",
                "LINES",
                "LINE_LOOP",
                "LINE_STRIP",
                "TRIANGLES",
                "TRIANGLE_STRIP",
                "TRIANGLE_FAN",
            ];
            self.ctx.emit(
                khronos::MESH_PRIMITIVE_INCOMPATIBLE_MODE,
                pointer,
                format!("Number of vertices or indices ({}) is not compatible with used drawing mode ('{}').", written(count), names[mode as usize]),
            );
        }
    }

    fn target(
        &mut self,
        target: Object<'a>,
        attributes: Option<Object<'a>>,
        at: &str,
        linked: bool,
    ) {
        for (semantic, value) in target {
            let semantic_at = member(at, semantic);
            if !self.valid_name(semantic, true) {
                self.invalid_name(&semantic_at);
            }
            let Some(accessor) = self.accessor(value).filter(|_| linked) else {
                continue;
            };
            let base = attributes
                .and_then(|a| a.get(semantic))
                .and_then(|b| self.accessor(b));
            match base {
                None => self.ctx.emit(
                    khronos::MESH_PRIMITIVE_MORPH_TARGET_NO_BASE_ACCESSOR,
                    semantic_at.clone(),
                    "The mesh primitive does not define this attribute semantic.",
                ),
                Some(base) if unsigned(base, "count") != unsigned(accessor, "count") => {
                    self.ctx.emit(
                        khronos::MESH_PRIMITIVE_MORPH_TARGET_INVALID_ATTRIBUTE_COUNT,
                        semantic_at.clone(),
                        "Base accessor has different count.",
                    )
                }
                Some(_) => {}
            }
            self.vertex_accessor(accessor, value, semantic, &semantic_at, true);
        }
    }

    /// The accessor an index value names, when it exists (unresolved ones are reported by
    /// the reference pass).
    fn accessor(&self, value: Node) -> Option<Node<'a>> {
        self.ctx
            .items("accessors")
            .get(usize::try_from(as_index(value)?).ok()?)
            .filter(|a| a.is_object())
    }
}

/// An accessor's count as the validator computes with it: the double written, so that a
/// count past 2^64 (`1e308`) keeps its remainders and differs from another such count.
fn count_of(accessor: Node) -> Option<f64> {
    unsigned(accessor, "count")?;
    accessor.get("count")?.as_f64()
}

/// A count as a message shows it: whole below 2^53, in exponent form past it.
fn written(count: f64) -> String {
    match count < 9_007_199_254_740_992.0 {
        true => format!("{}", count as u64),
        false => format!("{count:e}"),
    }
}

/// A primitive's vertex count as the Khronos validator takes it: the first readable count of
/// an attribute that names an accessor (an unreadable count leaves it to the next one).
pub(super) fn vertex_count(attributes: Node, accessors: Array) -> Option<u64> {
    (attributes.as_object().into_iter().flat_map(|a| a.values()))
        .filter_map(|v| accessors.get(usize::try_from(as_index(v)?).ok()?))
        .find_map(|accessor| unsigned(accessor, "count"))
}

/// A primitive's drawing mode: TRIANGLES (4) when absent, none when invalid (the schema
/// pass reports it; the Khronos validator then draws nothing it could check).
pub(crate) fn mode_of(primitive: Node) -> Option<u64> {
    match primitive.get("mode") {
        None => Some(4),
        Some(mode) => mode.as_u64().filter(|&mode| mode <= 6),
    }
}
