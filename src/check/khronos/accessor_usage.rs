//! Data checks that depend on how an accessor is used: unit normals and tangents, clamped
//! colours, index buffers, animation inputs and rotations, inverse bind matrices (the
//! Khronos ACCESSOR_* data codes reported at the using pointer).
//!
//! Each use adds a [`Checker`] to its accessor; the accessor-data pass feeds every checker in
//! the same single walk over the accessor's elements that computes min/max.

use super::primitives::Format;
use super::Dart;
use crate::check::context::{elements, unsigned, Context};
use crate::diagnostic::{khronos, Code};
use crate::document::Array;
use crate::document::Node;
use crate::gltf::accessor::component_count;
use crate::gltf::gl;
use std::collections::HashMap;

/// How far from 1 a normal or tangent length may be: the Khronos validator's tolerance,
/// which admits 8-bit quantised unit vectors.
const UNIT_TOLERANCE_VEC3: f64 = 0.00674;
/// The same for quaternions.
pub(super) const UNIT_TOLERANCE_VEC4: f64 = 0.00769;

/// (code, pointer, message)
pub(super) type Finding = (Code, String, String);

/// The findings of one walk, bounded by its share of the pass's
/// [`WalkBudget`](crate::check::collector::WalkBudget).
pub(super) struct Findings {
    kept: Vec<Finding>,
    limit: usize,
    /// Per code, the place of the first finding not kept and how many were not.
    dropped: Vec<(Code, String, u64)>,
}

impl Findings {
    /// Findings that list at most `limit` and count the rest.
    pub(super) fn listing(limit: usize) -> Findings {
        Findings {
            kept: Vec::new(),
            limit,
            dropped: Vec::new(),
        }
    }

    /// How many are listed.
    pub(super) fn listed(&self) -> usize {
        self.kept.len()
    }

    pub(super) fn push(&mut self, finding: Finding) {
        let (code, pointer, message) = finding;
        self.record(code, || pointer, || message);
    }

    /// Keeps or counts a finding, making its pointer and message only when they are kept
    /// (a walk may make 10^8 findings, nearly all only counted).
    pub(super) fn record(
        &mut self,
        code: Code,
        pointer: impl FnOnce() -> String,
        message: impl FnOnce() -> String,
    ) {
        if self.kept.len() < self.limit {
            self.kept.push((code, pointer(), message()));
            return;
        }
        match self.dropped.iter_mut().find(|(c, ..)| *c == code) {
            Some((.., n)) => *n += 1,
            None => self.dropped.push((code, pointer(), 1)),
        }
    }

    /// Empty findings that may keep what these still have room for: those of a later part
    /// of the same walk, made apart (on another core) and then [`absorb`](Self::absorb)ed.
    pub(super) fn room(&self) -> Findings {
        Findings::listing(self.limit.saturating_sub(self.kept.len()))
    }

    /// Takes in the findings of the part of the walk that follows these, as if they had
    /// been recorded here: its kept ones are kept while there is room, and what it only
    /// counted is counted here, under the first place of each code.
    pub(super) fn absorb(&mut self, later: Findings) {
        for (code, pointer, message) in later.kept {
            self.record(code, || pointer, || message);
        }
        for (code, pointer, n) in later.dropped {
            match self.dropped.iter_mut().find(|(c, ..)| *c == code) {
                Some((.., count)) => *count += n,
                None => self.dropped.push((code, pointer, n)),
            }
        }
    }

    /// Whether nothing was found.
    #[cfg(test)]
    pub(super) fn is_empty(&self) -> bool {
        self.kept.is_empty() && self.dropped.is_empty()
    }

    /// Reports the kept findings, the last one saying how many more were not listed, and
    /// counts those.
    pub(super) fn report(mut self, ctx: &mut Context) {
        let more: u64 = self.dropped.iter().map(|(.., n)| n).sum();
        if let Some(last) = self.kept.last_mut().filter(|_| more > 0) {
            last.2 += &format!(" ({more} more findings here are not listed.)");
        }
        for (code, pointer, message) in self.kept {
            ctx.emit(code, pointer, message);
        }
        for (code, pointer, n) in self.dropped {
            ctx.count_unlisted(code, pointer, n);
        }
    }
}

enum Kind {
    UnitVector,
    UnitVectorWithSign,
    Clamped,
    Indices {
        max_vertex: i64,
        restart: f64,
        triangles: bool,
    },
    AnimationInput,
    Rotation {
        cubic: bool,
    },
    InverseBind,
}

/// One use of an accessor, with the running state its check needs.
pub(super) struct Checker {
    pointer: String,
    kind: Kind,
    last: f64,
    /// Position within a cubic-spline (in-tangent, value, out-tangent) triple, or within
    /// a triangle.
    slot: usize,
    triangle: [f64; 3],
    degenerate: u64,
}

impl Checker {
    fn new(pointer: String, kind: Kind) -> Self {
        Checker {
            pointer,
            kind,
            last: 0.0,
            slot: 0,
            triangle: [0.0; 3],
            degenerate: 0,
        }
    }

    /// Takes a batch of elements, as stored, `n` numbers each, the first number having
    /// flat index `first` (`element × n`); `unit` maps a stored value to its normalised value.
    pub(super) fn feed(
        &mut self,
        first: usize,
        values: &[f64],
        n: usize,
        unit: fn(f64) -> f64,
        out: &mut Findings,
    ) {
        let elements = values.chunks_exact(n).enumerate();
        let elements = elements.map(|(e, element)| (first + e * n, element));
        match self.kind {
            Kind::UnitVector => {
                for (at, element) in elements {
                    self.unit_length(at, element, unit, out);
                }
            }
            Kind::UnitVectorWithSign => {
                for (at, element) in elements {
                    self.unit_length(at, element, unit, out);
                    self.sign(at, element, unit, out);
                }
            }
            Kind::Clamped => {
                for (at, v) in values.iter().enumerate() {
                    // NaN is no number outside the range (it is an invalid float).
                    if *v < 0.0 || *v > 1.0 {
                        self.report(
                            out,
                            khronos::ACCESSOR_NON_CLAMPED,
                            format!(
                                "Accessor element at index {} is not clamped to 0..1 range: {}.",
                                first + at,
                                Dart(*v)
                            ),
                        );
                    }
                }
            }
            Kind::Indices {
                max_vertex,
                restart,
                triangles,
            } => {
                for (at, v) in values.iter().enumerate() {
                    if *v > max_vertex as f64 || *v == restart {
                        self.bad_index(first + at, *v, max_vertex, restart, out);
                    }
                }
                if triangles {
                    self.count_degenerate(values);
                }
            }
            Kind::AnimationInput => {
                for (at, v) in values.iter().enumerate() {
                    self.animation_input(first + at, *v, out);
                }
            }
            Kind::Rotation { cubic } => {
                for (at, element) in elements {
                    self.rotation(at, element, cubic, unit, out);
                }
            }
            Kind::InverseBind => {
                for (at, element) in elements {
                    self.inverse_bind(at, element, out);
                }
            }
        }
    }

    fn sign(&self, at: usize, element: &[f64], unit: fn(f64) -> f64, out: &mut Findings) {
        let w = element.get(3).map_or(1.0, |w| unit(*w));
        if w != 1.0 && w != -1.0 {
            self.report(out, khronos::ACCESSOR_INVALID_SIGN, format!("Vector3 with sign at accessor indices {at}..{} has invalid w component: {}. Must be 1.0 or -1.0.", at + 3, Dart(w)));
        }
    }

    fn rotation(
        &mut self,
        at: usize,
        element: &[f64],
        cubic: bool,
        unit: fn(f64) -> f64,
        out: &mut Findings,
    ) {
        // Cubic-spline outputs hold (in-tangent, value, out-tangent): only values must be
        // unit quaternions.
        let is_value = !cubic || self.slot == 1;
        self.slot = (self.slot + 1) % 3;
        let length = element.iter().map(|v| unit(*v).powi(2)).sum::<f64>().sqrt();
        if is_value && (length - 1.0).abs() > UNIT_TOLERANCE_VEC4 {
            self.report(out, khronos::ACCESSOR_ANIMATION_SAMPLER_OUTPUT_NON_NORMALIZED_QUATERNION, format!("Animation sampler output accessor element at indices {at}..{} is not of unit length: {}.", at + 3, Dart(length)));
        }
    }

    fn inverse_bind(&self, at: usize, element: &[f64], out: &mut Findings) {
        for c in [3, 7, 11, 15] {
            let expected = if c == 15 { 1.0 } else { 0.0 };
            let v = element.get(c).copied().unwrap_or(expected);
            if v != expected {
                self.report(out, khronos::ACCESSOR_INVALID_IBM, format!("Matrix element at index {} (component index {c}) contains invalid value: {}.", at + c, Dart(v)));
            }
        }
    }

    fn unit_length(&self, first: usize, element: &[f64], unit: fn(f64) -> f64, out: &mut Findings) {
        // A NaN component is ACCESSOR_INVALID_FLOAT already; the validator says no more of
        // it (an infinite one still makes a length, and is reported).
        if element.iter().take(3).any(|v| v.is_nan()) {
            return;
        }
        let length = element
            .iter()
            .take(3)
            .map(|v| unit(*v).powi(2))
            .sum::<f64>()
            .sqrt();
        if !is_unit_length(length) {
            self.report(
                out,
                khronos::ACCESSOR_VECTOR3_NON_UNIT,
                format!(
                    "Vector3 at accessor indices {first}..{} is not of unit length: {}.",
                    first + 2,
                    Dart(length)
                ),
            );
        }
    }

    fn bad_index(&self, at: usize, v: f64, max_vertex: i64, restart: f64, out: &mut Findings) {
        if v > max_vertex as f64 {
            self.report(out, khronos::ACCESSOR_INDEX_OOB, format!("Indices accessor element at index {at} has value {v} that is greater than the maximum vertex index available ({max_vertex})."));
        }
        if v == restart {
            self.report(
                out,
                khronos::ACCESSOR_INDEX_PRIMITIVE_RESTART,
                format!("Indices accessor contains primitive restart value ({v}) at index {at}."),
            );
        }
    }

    /// Counts triangles with a repeated vertex; a triangle may straddle two batches.
    fn count_degenerate(&mut self, values: &[f64]) {
        let mut rest = values;
        while self.slot != 0 {
            let Some((v, after)) = rest.split_first() else {
                return;
            };
            self.add_vertex(*v);
            rest = after;
        }
        let whole = rest.chunks_exact(3);
        let tail = whole.remainder();
        self.degenerate += whole
            .map(|t| u64::from(t[0] == t[1] || t[1] == t[2] || t[2] == t[0]))
            .sum::<u64>();
        for v in tail {
            self.add_vertex(*v);
        }
    }

    fn add_vertex(&mut self, v: f64) {
        self.triangle[self.slot] = v;
        self.slot += 1;
        if self.slot == 3 {
            self.slot = 0;
            let [a, b, c] = self.triangle;
            self.degenerate += u64::from(a == b || b == c || c == a);
        }
    }

    fn animation_input(&mut self, index: usize, value: f64, out: &mut Findings) {
        if value < 0.0 {
            self.report(
                out,
                khronos::ACCESSOR_ANIMATION_INPUT_NEGATIVE,
                format!(
                    "Animation input accessor element at index {index} is negative: {}.",
                    Dart(value)
                ),
            );
            return;
        }
        if index != 0 && value <= self.last {
            self.report(out, khronos::ACCESSOR_ANIMATION_INPUT_NON_INCREASING, format!("Animation input accessor element at index {index} is less than or equal to previous: {} <= {}.", Dart(value), Dart(self.last)));
        }
        self.last = value;
    }

    /// Takes the summary of an index buffer whose elements were not fed one by one: its
    /// largest value and its degenerate triangles. False when that value needs the
    /// element-by-element report (out of range, or the restart value) or this checker is not
    /// an index check: the caller then feeds every element instead.
    pub(super) fn accept_index_summary(&mut self, largest: f64, degenerate: u64) -> bool {
        let Kind::Indices {
            max_vertex,
            restart,
            triangles,
        } = self.kind
        else {
            return false;
        };
        if largest > max_vertex as f64 || largest == restart {
            return false;
        }
        if triangles {
            self.degenerate = degenerate;
        }
        true
    }

    /// Whether this checker only asks that (float) elements be unit vectors, which the fast
    /// path can test on its own.
    pub(super) fn wants_unit_vectors_only(&self) -> bool {
        matches!(self.kind, Kind::UnitVector)
    }

    /// Reports what is only known after the last element.
    pub(super) fn finish(&self, elements: usize, out: &mut Findings) {
        if self.degenerate > 0 {
            self.report(
                out,
                khronos::ACCESSOR_INDEX_TRIANGLE_DEGENERATE,
                format!(
                    "Indices accessor contains {} degenerate triangles (out of {}).",
                    self.degenerate,
                    elements / 3
                ),
            );
        }
    }

    fn report(&self, out: &mut Findings, code: Code, message: String) {
        out.push((code, self.pointer.clone(), message));
    }
}

/// Whether a normal or tangent of this length counts as unit length.
pub(super) fn is_unit_length(length: f64) -> bool {
    (length - 1.0).abs() <= UNIT_TOLERANCE_VEC3
}

/// The checkers of every accessor, keyed by accessor index.
pub(super) fn checkers(ctx: &Context) -> HashMap<usize, Vec<Checker>> {
    let mut found = Uses {
        accessors: ctx.items("accessors"),
        quantized: ctx.uses_extension("KHR_mesh_quantization"),
        map: HashMap::new(),
    };
    for (_, pointer, mesh) in ctx.objects("meshes") {
        for (p, primitive) in elements(mesh, "primitives") {
            found.primitive(primitive, &format!("{pointer}/primitives/{p}"));
        }
    }
    for (_, pointer, animation) in ctx.objects("animations") {
        found.animation(animation, &pointer);
    }
    for (_, pointer, skin) in ctx.objects("skins") {
        if let Some(a) = found.accessor(skin, "inverseBindMatrices", "MAT4", &[gl::FLOAT]) {
            found.add(
                a,
                format!("{pointer}/inverseBindMatrices"),
                Kind::InverseBind,
            );
        }
    }
    found.map
}

struct Uses<'a> {
    accessors: Array<'a>,
    /// KHR_mesh_quantization widens the attribute formats.
    quantized: bool,
    map: HashMap<usize, Vec<Checker>>,
}

impl Uses<'_> {
    fn add(&mut self, accessor: usize, pointer: String, kind: Kind) {
        self.map
            .entry(accessor)
            .or_default()
            .push(Checker::new(pointer, kind));
    }

    /// `object[key]` as an accessor index, when that accessor has the given type and one
    /// of the component types (integer ones normalised); other formats are reported by
    /// the format checks and not read here.
    fn accessor(&self, object: Node, key: &str, kind: &str, types: &[u64]) -> Option<usize> {
        let index = unsigned(object, key)? as usize;
        let accessor = self.accessors.get(index)?;
        let component_type = unsigned(accessor, "componentType")?;
        let normalized = accessor.get("normalized").and_then(Node::as_bool) == Some(true);
        let format_ok = accessor.get("type")?.as_str()? == kind
            && types.contains(&component_type)
            && (component_type == gl::FLOAT || normalized);
        format_ok.then_some(index)
    }

    /// A vertex attribute's accessor index, when its format is one the semantic allows
    /// (others are reported by the format check and not read here).
    fn attribute(&self, attributes: Node, semantic: &str) -> Option<(usize, Format<'_>)> {
        let index = unsigned(attributes, semantic)? as usize;
        let format = Format::of(self.accessors.get(index)?);
        format
            .allowed_for(semantic, false, self.quantized)?
            .then_some((index, format))
    }

    fn primitive(&mut self, primitive: Node, pointer: &str) {
        let attributes = primitive.get("attributes").filter(|a| a.is_object());
        if let Some(attributes) = attributes {
            let attribute = |name: &str| format!("{pointer}/attributes/{name}");
            if let Some((a, _)) = self.attribute(attributes, "NORMAL") {
                self.add(a, attribute("NORMAL"), Kind::UnitVector);
            }
            if let Some((a, _)) = self.attribute(attributes, "TANGENT") {
                self.add(a, attribute("TANGENT"), Kind::UnitVectorWithSign);
            }
            if let Some((a, format)) = self.attribute(attributes, "COLOR_0") {
                if format.is_float() {
                    self.add(a, attribute("COLOR_0"), Kind::Clamped);
                }
            }
        }
        // Without attributes the indices are still checked, against no vertex at all.
        self.indices(primitive, attributes.unwrap_or(primitive.null()), pointer);
    }

    fn indices(&mut self, primitive: Node, attributes: Node, pointer: &str) {
        let Some(index) = unsigned(primitive, "indices").map(|i| i as usize) else {
            return;
        };
        let Some(accessor) = self.accessors.get(index) else {
            return;
        };
        let restart = match unsigned(accessor, "componentType") {
            Some(gl::UNSIGNED_BYTE) => f64::from(u8::MAX),
            Some(gl::UNSIGNED_SHORT) => f64::from(u16::MAX),
            Some(gl::UNSIGNED_INT) => f64::from(u32::MAX),
            _ => return,
        };
        let is_scalar = accessor.get("type").and_then(Node::as_str) == Some("SCALAR");
        let normalized = accessor.get("normalized").and_then(Node::as_bool) == Some(true);
        if !is_scalar || normalized {
            return;
        }
        let vertex_count =
            super::primitives::vertex_count(attributes, self.accessors).map_or(0, |n| {
                // A count past i64 (2^64 and beyond, `1e308`) leaves no index out of range.
                i64::try_from(n).unwrap_or(i64::MAX)
            });
        let kind = Kind::Indices {
            max_vertex: vertex_count - 1,
            restart,
            triangles: super::primitives::mode_of(primitive) == Some(4),
        };
        self.add(index, format!("{pointer}/indices"), kind);
    }

    fn animation(&mut self, animation: Node, pointer: &str) {
        let Some((samplers, channels)) = super::animations::linked(animation) else {
            return;
        };
        for (s, sampler) in samplers.iter().enumerate() {
            if let Some(a) = self.accessor(sampler, "input", "SCALAR", &[gl::FLOAT]) {
                let p = format!("{pointer}/samplers/{s}/input");
                self.add(a, p, Kind::AnimationInput);
            }
        }
        for (c, channel) in channels.iter().enumerate() {
            let target_path = channel.get("target").and_then(|t| t.get("path"));
            if target_path.and_then(Node::as_str) != Some("rotation") {
                continue;
            }
            let Some(sampler) = unsigned(channel, "sampler").and_then(|s| samplers.get(s as usize))
            else {
                continue;
            };
            let Some(output) = unsigned(sampler, "output").map(|o| o as usize) else {
                continue;
            };
            let components = self
                .accessors
                .get(output)
                .and_then(|a| a.get("type")?.as_str())
                .and_then(component_count);
            if components == Some(4) {
                let interpolation = sampler.get("interpolation").and_then(Node::as_str);
                let cubic = interpolation == Some("CUBICSPLINE");
                let p = format!("{pointer}/channels/{c}/sampler");
                self.add(output, p, Kind::Rotation { cubic });
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A walk's findings: two codes interleaved, each at its own place.
    fn walk(count: usize) -> Vec<Finding> {
        (0..count)
            .map(|i| {
                let code = match i % 3 {
                    0 => khronos::ACCESSOR_WEIGHTS_NON_NORMALIZED,
                    _ => khronos::ACCESSOR_JOINTS_INDEX_DUPLICATE,
                };
                (code, format!("/at/{i}"), format!("finding {i}"))
            })
            .collect()
    }

    fn state(findings: &Findings) -> (Vec<Finding>, Vec<(Code, String, u64)>) {
        (findings.kept.clone(), findings.dropped.clone())
    }

    #[test]
    fn findings_recorded_in_parts_and_absorbed_equal_those_recorded_in_one_walk() {
        let all = walk(40);
        for limit in [0, 1, 7, 39, 40, 100] {
            let mut one = Findings::listing(limit);
            all.iter().cloned().for_each(|f| one.push(f));
            // Parts made as the influences pass makes them: each with the room the merged
            // findings had when the batch started, then absorbed in order.
            for cuts in [vec![0, 40], vec![0, 5, 40], vec![0, 3, 8, 20, 21, 40]] {
                let mut merged = Findings::listing(limit);
                for part in cuts.windows(2) {
                    let mut found = merged.room();
                    all[part[0]..part[1]]
                        .iter()
                        .cloned()
                        .for_each(|f| found.push(f));
                    merged.absorb(found);
                }
                assert_eq!(state(&merged), state(&one), "limit {limit}, cuts {cuts:?}");
            }
        }
    }
}
