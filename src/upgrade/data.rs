//! Accessor data: reading 1.0 accessors (any stride, any component type) and repacking them
//! with the component types, alignment and min/max glTF 2.0 requires.

use super::binary::Binary;
use crate::document::Node;
pub(super) use crate::gltf::accessor::FLOAT;
use crate::gltf::accessor::{
    component_count, component_size, decode, decode_component, normalise, FloatBounds, Layout,
    BYTE, MAX_COMPONENTS, SHORT, UNSIGNED_BYTE, UNSIGNED_INT, UNSIGNED_SHORT,
};
use crate::legacy::source::Source;
use rayon::prelude::*;
use std::sync::atomic::{AtomicU64, AtomicUsize, Ordering};

/// A 1.0 accessor resolved to its bytes.
pub(super) struct Accessor<'a> {
    pub component_type: u64,
    pub kind: String,
    pub components: usize,
    pub count: usize,
    stride: usize,
    bytes: &'a [u8],
    source: &'a Source<'a>,
}

/// What an accessor is used for, which decides its 2.0 component type and alignment.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub(super) enum Role {
    Indices,
    /// POSITION, TANGENT: float only.
    FloatAttribute,
    /// NORMAL: float only; two integers are an octahedron encoding (see [`oct_decoded`]).
    Normal,
    /// TEXCOORD_n, COLOR_n: float (integer 1.0 data is converted, keeping its values).
    TexcoordOrColour,
    /// JOINTS_n: unsigned byte or short.
    Joints,
    /// WEIGHTS_n: float or normalized unsigned byte/short.
    Weights,
    /// Application-specific attributes: kept as they are, 4-byte aligned.
    OtherAttribute,
    /// Animation samplers, inverse bind matrices.
    Data,
}

impl Role {
    pub(super) fn of_semantic(semantic: &str) -> Role {
        let base = semantic.split('_').next().unwrap_or(semantic);
        match base {
            "NORMAL" => Role::Normal,
            "POSITION" | "TANGENT" => Role::FloatAttribute,
            "TEXCOORD" | "COLOR" => Role::TexcoordOrColour,
            "JOINTS" => Role::Joints,
            "WEIGHTS" => Role::Weights,
            _ => Role::OtherAttribute,
        }
    }

    pub(super) fn is_vertex(self) -> bool {
        !matches!(self, Role::Indices | Role::Data)
    }
}

pub(super) fn read<'a>(source: &'a Source, id: &str) -> Result<Accessor<'a>, String> {
    let accessor = source
        .object("accessors", id)
        .ok_or_else(|| format!("accessor '{id}' does not exist"))?;
    let number = |key: &str| accessor.get(key).and_then(Node::as_u64);
    let component_type = number("componentType").unwrap_or(0);
    let size = component_size(component_type)
        .ok_or_else(|| format!("accessor '{id}': unknown componentType {component_type}"))?;
    let kind = accessor.get("type").and_then(Node::as_str).unwrap_or("");
    let components =
        component_count(kind).ok_or_else(|| format!("accessor '{id}': unknown type '{kind}'"))?;
    let count = number("count").unwrap_or(0) as usize;
    let element = size * components;
    let stride = match number("byteStride").unwrap_or(0) as usize {
        0 => element,
        s => s,
    };
    let view_id = accessor
        .get("bufferView")
        .and_then(Node::as_str)
        .unwrap_or("");
    let view = source.view(view_id)?;
    let offset = number("byteOffset").unwrap_or(0) as usize;
    let needed = match count {
        0 => 0,
        n => (n - 1)
            .checked_mul(stride)
            .and_then(|b| b.checked_add(element))
            .ok_or_else(|| format!("accessor '{id}': size overflows"))?,
    };
    let bytes = offset
        .checked_add(needed)
        .and_then(|end| view.get(offset..end))
        .ok_or_else(|| format!("accessor '{id}' runs past the end of bufferView '{view_id}'"))?;
    Ok(Accessor {
        component_type,
        kind: kind.to_string(),
        components,
        count,
        stride,
        bytes,
        source,
    })
}

impl Accessor<'_> {
    /// Where its bytes lie in the loaded input (address and length) and how far apart its
    /// elements are: accessors with the same place read the same data.
    pub(super) fn place(&self) -> (usize, usize, usize) {
        (self.bytes.as_ptr() as usize, self.bytes.len(), self.stride)
    }

    /// Component `c` of element `i`, as stored (integers are not normalised).
    pub(super) fn get(&self, i: usize, c: usize) -> f64 {
        let size = component_size(self.component_type).unwrap_or(4);
        let at = i * self.stride + c * size;
        decode_component(self.component_type, &self.bytes[at..at + size])
    }

    /// Its elements, to be read from several threads.
    fn elements(&self) -> Elements<'_> {
        Elements {
            bytes: self.bytes,
            layout: Layout {
                component_type: self.component_type,
                size: component_size(self.component_type).unwrap_or(4),
                components: self.components.min(MAX_COMPONENTS),
                stride: self.stride,
                offset: 0,
                count: self.count,
            },
        }
    }

    /// Every element's components, in order.
    pub(super) fn values(&self) -> Vec<f64> {
        let mut out = vec![0.0; self.count * self.components];
        self.elements().read_run(0, &mut out);
        out
    }
}

/// An accessor's elements as stored.
#[derive(Clone, Copy)]
struct Elements<'a> {
    bytes: &'a [u8],
    layout: Layout,
}

impl Elements<'_> {
    /// The components, as stored, of the elements from `first` on that `out` has room for
    /// (`components` values each), decoded as the check's walks decode them.
    fn read_run(&self, first: usize, out: &mut [f64]) {
        // `read` bounded the bytes to the elements: all of them are there.
        decode(&self.layout, self.bytes, first, out);
    }
}

/// Repacked data, appended to the output binary, ready to become one bufferView + one
/// accessor.
#[derive(Clone)]
pub(super) struct Packed {
    /// Where the data starts in the output binary (4-byte aligned).
    pub offset: usize,
    pub length: usize,
    pub component_type: u64,
    pub normalized: bool,
    /// Set when elements were padded to 4 bytes (vertex attributes).
    pub byte_stride: Option<usize>,
    pub min: Vec<f64>,
    pub max: Vec<f64>,
    /// The component type changed: say so in the report.
    pub converted_from: Option<u64>,
    /// Skin weights divided by their per-vertex sum (see `some_weights_to_renormalise`).
    pub renormalised: Option<Renormalised>,
}

/// What renormalising skin weights changed.
#[derive(Debug, Clone, Copy)]
pub(super) struct Renormalised {
    /// Vertices whose weights did not sum to 1.
    pub vertices: usize,
    /// The smallest such sum.
    pub lowest: f64,
}

/// How far from 1 a vertex's weights may sum before they are divided by the sum: below
/// the Khronos validator's allowance (2·10⁻⁷ per weight, summed in single precision).
const WEIGHT_SUM_TOLERANCE: f64 = 1e-7;

/// Whether dividing each vertex's skin weights (as values in [0, 1]) by their sum changes
/// some vertex: whether some sum is not 1. Stops at the first such vertex; what the division
/// changed is tallied as it is made ([`Tally`]). 2.0 requires sums of 1; the 1.0 shaders
/// multiplied the affine joint matrices by the raw weights, which scales the homogeneous
/// coordinate by the sum, and the perspective divide (and `normalize` of the normal) took
/// the same factor out again: dividing by the sum draws exactly what 1.0 drew. A vertex
/// whose weights sum to 0 is left as it is (no division repairs it; the output check
/// reports it).
fn some_weights_to_renormalise(accessor: &Accessor) -> bool {
    let elements = accessor.elements();
    let components = elements.layout.components.max(1);
    let count = accessor.count;
    (0..count.div_ceil(BLOCK)).into_par_iter().any(|block| {
        let mut buffer = [0.0; RUN * MAX_COMPONENTS];
        let end = ((block + 1) * BLOCK).min(count);
        (block * BLOCK..end).step_by(RUN).any(|first| {
            let run = &mut buffer[..RUN.min(end - first) * components];
            weights_of_run(elements, first, run);
            run.chunks_exact(components)
                .any(|vertex| divisor(vertex).is_some())
        })
    })
}

/// What renormalising changes, tallied by the runs as they are packed on all cores.
struct Tally {
    vertices: AtomicUsize,
    /// The lowest sum divided by, as bits: sums divided by are finite and above 0, and
    /// such doubles order as their bits do.
    lowest: AtomicU64,
}

impl Tally {
    fn new() -> Self {
        Tally {
            vertices: AtomicUsize::new(0),
            lowest: AtomicU64::new(f64::INFINITY.to_bits()),
        }
    }

    fn add(&self, vertices: usize, lowest: f64) {
        self.vertices.fetch_add(vertices, Ordering::Relaxed);
        self.lowest.fetch_min(lowest.to_bits(), Ordering::Relaxed);
    }

    fn into_renormalised(self) -> Renormalised {
        Renormalised {
            vertices: self.vertices.into_inner(),
            lowest: f64::from_bits(self.lowest.into_inner()),
        }
    }
}

/// The weights of the vertices from `first` on that `out` has room for, as values in [0, 1].
fn weights_of_run(elements: Elements, first: usize, out: &mut [f64]) {
    elements.read_run(first, out);
    if let Some(unit) = normalise(elements.layout.component_type) {
        out.iter_mut().for_each(|w| *w = unit(*w));
    }
}

/// The sum a vertex's weights are divided by, when they need it: not 1 (beyond the
/// tolerance), and a finite sum above 0.
fn divisor(vertex: &[f64]) -> Option<f64> {
    let sum: f64 = vertex.iter().sum();
    let needed = (sum - 1.0).abs() > WEIGHT_SUM_TOLERANCE && sum > 0.0 && sum.is_finite();
    needed.then_some(sum)
}

/// The weights of a run of vertices, each vertex's divided by their sum when it is not 1
/// (see [`divisor`]); what was divided is added to `tally`.
fn renormalised_run(elements: Elements, first: usize, out: &mut [f64], tally: &Tally) {
    weights_of_run(elements, first, out);
    let (vertices, lowest) = match elements.layout.components {
        // Skin weights are VEC4 (2.0 allows nothing else): with a vertex's size known when
        // compiled, its loops are unrolled.
        4 => renormalise_vertices::<4>(out, 4),
        n => renormalise_vertices::<0>(out, n.max(1)),
    };
    if vertices > 0 {
        tally.add(vertices, lowest);
    }
}

/// Divides the weights of each vertex (`N` of them, or `n` when `N` is 0) that needs it by
/// their sum and settles them in single precision; returns how many vertices were divided
/// and the lowest sum divided by.
fn renormalise_vertices<const N: usize>(weights: &mut [f64], n: usize) -> (usize, f64) {
    let n = if N == 0 { n } else { N };
    let (mut vertices, mut lowest) = (0, f64::INFINITY);
    for vertex in weights.chunks_exact_mut(n) {
        if let Some(sum) = divisor(vertex) {
            vertex.iter_mut().for_each(|w| *w /= sum);
            settle_in_single_precision(vertex);
            vertices += 1;
            lowest = lowest.min(sum);
        }
    }
    (vertices, lowest)
}

/// Rounds a vertex's weights (they sum to 1) to single precision, as they are stored, and
/// moves the rounding residue into the largest weight, so that their single-precision sum,
/// added in order as the check adds them, is 1 too. Most vertices settle in one round; the
/// rounds stop there.
#[inline(always)]
fn settle_in_single_precision(weights: &mut [f64]) {
    weights.iter_mut().for_each(|w| *w = f64::from(*w as f32));
    // The last of equal largest weights, as `max_by` picks it: any would do, but one rule.
    let largest =
        (0..weights.len()).fold(0, |at, c| if weights[c] >= weights[at] { c } else { at });
    for _ in 0..3 {
        let sum = weights
            .iter()
            .fold(0f32, |sum, &w| (f64::from(sum) + w) as f32);
        let residue = 1.0 - f64::from(sum);
        if residue == 0.0 {
            break;
        }
        weights[largest] = f64::from((weights[largest] + residue) as f32);
    }
}

fn output_type(role: Role, input: u64) -> (u64, bool) {
    match (role, input) {
        (Role::FloatAttribute | Role::Normal | Role::TexcoordOrColour, _) => (FLOAT, false),
        (Role::Joints, UNSIGNED_BYTE | UNSIGNED_SHORT) => (input, false),
        (Role::Joints, _) => (UNSIGNED_SHORT, false),
        (Role::Weights, UNSIGNED_BYTE | UNSIGNED_SHORT) => (input, true),
        (Role::Weights, _) => (FLOAT, false),
        (Role::Indices, UNSIGNED_BYTE | UNSIGNED_SHORT | UNSIGNED_INT) => (input, false),
        (Role::Indices, _) => (UNSIGNED_INT, false),
        _ => (input, false),
    }
}

/// Appends values (`components` per element) to `out` with the given component type (an
/// unsigned type takes integers or single-precision floats: see [`to_unsigned`]).
pub(super) fn pack_values(
    values: &[f64],
    components: usize,
    component_type: u64,
    normalized: bool,
    vertex: bool,
    binary: &mut Binary,
) -> Packed {
    let count = values.len() / components.max(1);
    let layout = PackingLayout {
        count,
        components,
        component_type,
        normalized,
        vertex,
    };
    pack_elements(layout, binary, |first, out| {
        out.copy_from_slice(&values[first * components..][..out.len()])
    })
}

/// How packed elements are laid out.
#[derive(Clone, Copy)]
struct PackingLayout {
    count: usize,
    components: usize,
    component_type: u64,
    normalized: bool,
    /// Vertex attributes: each element padded to 4 bytes.
    vertex: bool,
}

/// Elements packed by one task: enough that a task outweighs its scheduling.
const BLOCK: usize = 1 << 14;

/// Elements made at once within a block, into a buffer small enough for L1.
const RUN: usize = 256;

/// Appends `layout.count` elements with the given component type, made a run at a time by
/// `run(first, buffer)`, which fills `buffer` with the values of elements `first..` it has
/// room for: no vector of every value is made first (a 2·10^6-vertex skin's joints and
/// weights would take 128 MB of them), and blocks of elements are packed on all cores, each
/// into its own place of the output.
fn pack_elements(
    layout: PackingLayout,
    binary: &mut Binary,
    run: impl Fn(usize, &mut [f64]) + Sync,
) -> Packed {
    let PackingLayout {
        count,
        components,
        component_type,
        normalized,
        vertex,
    } = layout;
    let components = components.clamp(1, MAX_COMPONENTS);
    let offset = binary.align();
    let size = component_size(component_type).unwrap_or(4);
    let element_size = size * components;
    let stride = if vertex {
        element_size.div_ceil(4) * 4
    } else {
        element_size
    };
    let packing = Packing {
        components,
        stride,
        run,
    };
    let (mut min, mut max) = binary.append_made(count * stride, |target| {
        packing.encode(component_type, target)
    });
    keep_writable_bounds(count, &mut min, &mut max);
    Packed {
        offset,
        length: binary.len() - offset,
        component_type,
        normalized,
        byte_stride: (stride != element_size).then_some(stride),
        min,
        max,
        converted_from: None,
        renormalised: None,
    }
}

/// `v` clamped to [0, `high`] (an integer, as the top of an unsigned type is) and raised by
/// a half, so that the cast to that type, which truncates, makes it `v` rounded half away
/// from zero: the same integer as `v.round().clamp(0.0, high)` (NaN becomes 0 either way).
/// Exact for every value that reaches it, which is a value a 1.0 accessor stores: an integer
/// or a single-precision float, to which double precision adds a half without rounding.
/// Without `round` (a library call on the baseline x86-64) or a branch, the compiler
/// vectorises the loops this runs in, once a value of every converted accessor.
fn to_unsigned(v: f64, high: f64) -> f64 {
    v.clamp(0.0, high) + 0.5
}

/// Elements being written as one component type.
struct Packing<R> {
    components: usize,
    /// Bytes from one element to the next (vertex attributes are padded to 4 bytes).
    stride: usize,
    /// Makes a run of elements' values (see [`pack_elements`]).
    run: R,
}

/// Per-component bounds of the values stored.
type Bounds = ([f64; MAX_COMPONENTS], [f64; MAX_COMPONENTS]);

/// The bounds of no value: any value stored replaces them.
fn no_bounds() -> Bounds {
    (
        [f64::INFINITY; MAX_COMPONENTS],
        [f64::NEG_INFINITY; MAX_COMPONENTS],
    )
}

impl<R: Fn(usize, &mut [f64]) + Sync> Packing<R> {
    /// Writes every element into `target` as `component_type`; returns the min/max of the
    /// values stored. One loop per component type: the type is matched once, not once per
    /// value. Converted data is stored unsigned or as floats (see `output_type`).
    fn encode(&self, component_type: u64, target: &mut [u8]) -> (Vec<f64>, Vec<f64>) {
        match component_type {
            UNSIGNED_BYTE => self.all(target, |v| {
                let x = to_unsigned(v, 255.0) as u8;
                ([x], f64::from(x))
            }),
            UNSIGNED_SHORT => self.all(target, |v| {
                let x = to_unsigned(v, 65535.0) as u16;
                (x.to_le_bytes(), f64::from(x))
            }),
            UNSIGNED_INT => self.all(target, |v| {
                let x = to_unsigned(v, f64::from(u32::MAX)) as u32;
                (x.to_le_bytes(), f64::from(x))
            }),
            _ => self.all(target, |v| {
                let x = v as f32;
                (x.to_le_bytes(), f64::from(x))
            }),
        }
    }

    /// Writes every element's values into `target` (zeroed, `stride` bytes an element) as
    /// `encode` stores them (their bytes and the value they hold); returns the min/max of
    /// the values stored.
    fn all<const N: usize>(
        &self,
        target: &mut [u8],
        encode: impl Fn(f64) -> ([u8; N], f64) + Sync,
    ) -> (Vec<f64>, Vec<f64>) {
        let stride = self.stride.max(1);
        let (min, max) = target
            .par_chunks_mut(BLOCK * stride)
            .enumerate()
            .map(|(block, bytes)| self.block(block * BLOCK, bytes, &encode))
            .reduce(no_bounds, |(min_a, max_a), (min_b, max_b)| {
                (
                    std::array::from_fn(|c| min_a[c].min(min_b[c])),
                    std::array::from_fn(|c| max_a[c].max(max_b[c])),
                )
            });
        (
            min[..self.components].to_vec(),
            max[..self.components].to_vec(),
        )
    }

    /// One block of elements, the first of which is element `first`.
    fn block<const N: usize>(
        &self,
        first: usize,
        bytes: &mut [u8],
        encode: impl Fn(f64) -> ([u8; N], f64),
    ) -> Bounds {
        let mut bounds = no_bounds();
        let mut buffer = [0.0; RUN * MAX_COMPONENTS];
        let (stride, n) = (self.stride.max(1), self.components);
        for (r, run) in bytes.chunks_mut(RUN * stride).enumerate() {
            let values = &mut buffer[..run.len() / stride * n];
            (self.run)(first + r * RUN, values);
            for (element, values) in run.chunks_exact_mut(stride).zip(values.chunks_exact_mut(n)) {
                for (value, slot) in values.iter_mut().zip(element.chunks_exact_mut(N)) {
                    let (stored_bytes, stored) = encode(*value);
                    slot.copy_from_slice(&stored_bytes);
                    *value = stored;
                }
            }
            bound_run(&mut bounds, values, n);
        }
        bounds
    }
}

/// Folds a run of values, `n` components an element, into per-component `bounds`, each
/// component's values in order. A comparison with NaN is false: NaN never becomes a bound.
fn bound_run(bounds: &mut Bounds, values: &[f64], n: usize) {
    match n {
        1 => bound_elements::<1>(bounds, values),
        2 => bound_elements::<2>(bounds, values),
        3 => bound_elements::<3>(bounds, values),
        4 => bound_elements::<4>(bounds, values),
        9 => bound_elements::<9>(bounds, values),
        16 => bound_elements::<16>(bounds, values),
        _ => {
            for c in 0..n.min(MAX_COMPONENTS) {
                let (mut low, mut high) = (bounds.0[c], bounds.1[c]);
                for &v in values[c..].iter().step_by(n) {
                    low = if v < low { v } else { low };
                    high = if v > high { v } else { high };
                }
                (bounds.0[c], bounds.1[c]) = (low, high);
            }
        }
    }
}

/// [`bound_run`] for `N` components known when compiled: the accumulators are registers,
/// one chain of comparisons per component side by side (in an array indexed at run time
/// each update waited on the store of the one before, and was most of a pack's time).
fn bound_elements<const N: usize>(bounds: &mut Bounds, values: &[f64]) {
    let mut low: [f64; N] = std::array::from_fn(|c| bounds.0[c]);
    let mut high: [f64; N] = std::array::from_fn(|c| bounds.1[c]);
    for element in values.chunks_exact(N) {
        for c in 0..N {
            low[c] = if element[c] < low[c] {
                element[c]
            } else {
                low[c]
            };
            high[c] = if element[c] > high[c] {
                element[c]
            } else {
                high[c]
            };
        }
    }
    bounds.0[..N].copy_from_slice(&low);
    bounds.1[..N].copy_from_slice(&high);
}

/// Copies elements whose component type does not change, padding vertex elements to 4
/// bytes, and computes min/max on the way: no per-value conversion for the common case.
/// Tightly packed data from a loaded buffer is not copied at all but referenced.
fn copy_elements(
    accessor: &Accessor,
    normalized: bool,
    vertex: bool,
    binary: &mut Binary,
) -> Packed {
    let offset = binary.align();
    let size = component_size(accessor.component_type).unwrap_or(4);
    let element = size * accessor.components;
    let stride = if vertex {
        element.div_ceil(4) * 4
    } else {
        element
    };
    let packed = accessor.stride == element && stride == element;
    let run = &accessor.bytes[..if packed { accessor.count * element } else { 0 }];
    let bytes: &[u8] = match accessor.source.shared(run).filter(|_| packed) {
        Some((buffer, range)) => {
            binary.share(&buffer, range);
            run
        }
        None => {
            let out = binary.owned();
            let start = out.len();
            if packed {
                out.extend_from_slice(run);
            } else {
                out.reserve(accessor.count * stride);
                for i in 0..accessor.count {
                    let at = i * accessor.stride;
                    out.extend_from_slice(&accessor.bytes[at..at + element]);
                    out.resize(out.len() + stride - element, 0);
                }
            }
            &binary.owned()[start..]
        }
    };
    let (mut min, mut max) = copied_bounds(accessor, bytes, stride);
    keep_writable_bounds(accessor.count, &mut min, &mut max);
    Packed {
        offset,
        length: binary.len() - offset,
        component_type: accessor.component_type,
        normalized,
        byte_stride: (stride != element).then_some(stride),
        min,
        max,
        converted_from: None,
        renormalised: None,
    }
}

/// Leaves out bounds JSON cannot hold: none for no elements, and none where an element is
/// infinite or NaN (JSON has no such number; the output's check then reports the values
/// themselves, traced to the source's accessor, rather than bounds written as `null`).
fn keep_writable_bounds(count: usize, min: &mut Vec<f64>, max: &mut Vec<f64>) {
    if count == 0 || !min.iter().chain(max.iter()).all(|v| v.is_finite()) {
        min.clear();
        max.clear();
    }
}

/// min/max per component of the elements `copy_elements` wrote (`stride` apart in
/// `bytes`): the common layouts read at memory speed, the others element by element.
fn copied_bounds(accessor: &Accessor, bytes: &[u8], stride: usize) -> (Vec<f64>, Vec<f64>) {
    let n = accessor.components;
    match accessor.component_type {
        FLOAT if stride == 4 * n && n <= 4 => match n {
            1 => FloatBounds::<1>::of(bytes, |_| true).min_max(),
            2 => FloatBounds::<2>::of(bytes, |_| true).min_max(),
            3 => FloatBounds::<3>::of(bytes, |_| true).min_max(),
            _ => FloatBounds::<4>::of(bytes, |_| true).min_max(),
        },
        FLOAT => bounds_of(bytes, stride, n, |b| f64::from(f32::from_le_bytes(b))),
        UNSIGNED_INT if stride == 4 && n == 1 => {
            let (low, high) = (bytes.par_chunks(4 * BLOCK))
                .map(|run| {
                    let words = (run.chunks_exact(4))
                        .map(|w| u32::from_le_bytes(w.try_into().unwrap_or_default()));
                    words.fold((u32::MAX, 0), |(l, h), v| (l.min(v), h.max(v)))
                })
                .reduce(|| (u32::MAX, 0), |a, b| (a.0.min(b.0), a.1.max(b.1)));
            (vec![f64::from(low)], vec![f64::from(high)])
        }
        UNSIGNED_INT => bounds_of(bytes, stride, n, |b| f64::from(u32::from_le_bytes(b))),
        _ => {
            let (mut min, mut max) = (vec![f64::INFINITY; n], vec![f64::NEG_INFINITY; n]);
            for i in 0..accessor.count {
                for c in 0..n {
                    let v = accessor.get(i, c);
                    min[c] = if v < min[c] { v } else { min[c] };
                    max[c] = if v > max[c] { v } else { max[c] };
                }
            }
            (min, max)
        }
    }
}

/// min/max per component over 4-byte components laid out with `stride`. A comparison is
/// false for NaN, so NaN never becomes a bound; compare-and-select on local accumulators
/// keeps this at memory speed.
fn bounds_of(
    bytes: &[u8],
    stride: usize,
    components: usize,
    read: impl Fn([u8; 4]) -> f64,
) -> (Vec<f64>, Vec<f64>) {
    const MOST: usize = 16;
    let n = components.min(MOST);
    let (mut low, mut high) = ([f64::INFINITY; MOST], [f64::NEG_INFINITY; MOST]);
    for element in bytes.chunks_exact(stride) {
        for (c, word) in element.chunks_exact(4).take(n).enumerate() {
            let v = read(word.try_into().unwrap_or_default());
            low[c] = if v < low[c] { v } else { low[c] };
            high[c] = if v > high[c] { v } else { high[c] };
        }
    }
    (low[..n].to_vec(), high[..n].to_vec())
}

/// The values of an accessor quantized with WEB3D_quantized_attributes, decoded: each element
/// v (n components) becomes the first n rows of `decodeMatrix` · [v, 1] (column-major, of
/// size (n + 1)²). None without the extension; `Err` when its matrix has the wrong size.
pub(super) fn dequantized(
    accessor: &Accessor,
    extension: Option<Node>,
) -> Option<Result<Vec<f64>, String>> {
    let matrix = extension?.get("decodeMatrix");
    let n = accessor.components;
    let matrix: Option<Vec<f64>> = matrix
        .and_then(Node::as_array)
        .filter(|m| m.len() == (n + 1) * (n + 1))
        .and_then(|m| m.iter().map(Node::as_f64).collect());
    let Some(matrix) = matrix else {
        return Some(Err(format!(
            "WEB3D_quantized_attributes decodeMatrix is not {0}×{0} numbers",
            n + 1
        )));
    };
    let stored = accessor.values();
    let mut decoded = Vec::with_capacity(stored.len());
    for element in stored.chunks_exact(n.max(1)) {
        for row in 0..n {
            let column = |c: usize| matrix[c * (n + 1) + row];
            let sum: f64 = (0..n).map(|c| column(c) * element[c]).sum();
            decoded.push(sum + column(n));
        }
    }
    Some(Ok(decoded))
}

/// A 1.0 NORMAL of two integer components, decoded to unit VEC3 floats. Two components can only
/// be an octahedron encoding (Cigolle et al. 2014), the convention of Cesium's 3D Tiles
/// content: each component normalised (a signed one by its maximum, as the tiles' own shaders
/// do with `1/127`; an unsigned one to [-1, 1], as Cesium's `czm_octDecode` does), then
/// (x, y, 1 − |x| − |y|), its lower half folded over, normalised. None for any other accessor.
pub(super) fn oct_decoded(accessor: &Accessor, role: Role) -> Option<Vec<f64>> {
    let unit = oct_unit(accessor, role)?;
    let stored = accessor.values();
    let mut decoded = Vec::with_capacity(stored.len() / 2 * 3);
    for pair in stored.chunks_exact(2) {
        let (x, y) = (unit(pair[0]), unit(pair[1]));
        let z = 1.0 - x.abs() - y.abs();
        let sign = |v: f64| if v >= 0.0 { 1.0 } else { -1.0 };
        let (x, y) = if z < 0.0 {
            ((1.0 - y.abs()) * sign(x), (1.0 - x.abs()) * sign(y))
        } else {
            (x, y)
        };
        let length = (x * x + y * y + z * z).sqrt();
        decoded.extend([x / length, y / length, z / length]);
    }
    Some(decoded)
}

/// Whether [`oct_decoded`] decodes this accessor.
pub(super) fn is_octahedral(accessor: &Accessor, role: Role) -> bool {
    oct_unit(accessor, role).is_some()
}

/// How an octahedron-encoded NORMAL's components map to [-1, 1]; None for any other accessor.
fn oct_unit(accessor: &Accessor, role: Role) -> Option<fn(f64) -> f64> {
    if role != Role::Normal || accessor.components != 2 {
        return None;
    }
    Some(match accessor.component_type {
        BYTE => |v| (v / 127.0).clamp(-1.0, 1.0),
        SHORT => |v| (v / 32767.0).clamp(-1.0, 1.0),
        UNSIGNED_BYTE => |v| v / 255.0 * 2.0 - 1.0,
        UNSIGNED_SHORT => |v| v / 65535.0 * 2.0 - 1.0,
        _ => return None,
    })
}

/// Appends an accessor's data to `out`, repacked for its role.
pub(super) fn pack(accessor: &Accessor, role: Role, out: &mut Binary) -> Packed {
    let layout = |component_type, normalized| PackingLayout {
        count: accessor.count,
        components: accessor.components,
        component_type,
        normalized,
        vertex: role.is_vertex(),
    };
    let converted_from = |to| (to != accessor.component_type).then_some(accessor.component_type);
    if role == Role::Weights && some_weights_to_renormalise(accessor) {
        // Floats: the quotients are not representable as normalised integers.
        let elements = accessor.elements();
        let tally = Tally::new();
        let mut packed = pack_elements(layout(FLOAT, false), out, |first, run| {
            renormalised_run(elements, first, run, &tally)
        });
        packed.converted_from = converted_from(FLOAT);
        packed.renormalised = Some(tally.into_renormalised());
        return packed;
    }
    let (component_type, normalized) = output_type(role, accessor.component_type);
    if component_type == accessor.component_type {
        return copy_elements(accessor, normalized, role.is_vertex(), out);
    }
    // Unsigned integer weights keep their type with `normalized` (see `output_type`); signed
    // ones become floats, scaled as 1.0 shaders normalised them.
    let scale = match (role, accessor.component_type) {
        (Role::Weights, BYTE) => 127.0,
        (Role::Weights, FLOAT) => 1.0,
        (Role::Weights, _) => 32767.0,
        _ => 1.0,
    };
    let elements = accessor.elements();
    let mut packed = pack_elements(layout(component_type, normalized), out, |first, values| {
        elements.read_run(first, values);
        if scale != 1.0 {
            values.iter_mut().for_each(|v| *v /= scale);
        }
    });
    packed.converted_from = converted_from(component_type);
    packed
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn values_become_the_integers_rounding_and_clamping_make() {
        let mut values = vec![
            -1e300,
            -70000.5,
            -2.5,
            -0.5,
            -0.0,
            0.0,
            0.49,
            0.5,
            1.5,
            2.5,
            2.4999,
            65535.4,
            65535.5,
            1e300,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NAN,
        ];
        // Single-precision values beside halves and where their spacing reaches 1 and 2.
        let beside = [
            0.5f32,
            1.5,
            255.5,
            65535.5,
            8_388_608.0,
            16_777_216.0,
            4_294_967_296.0,
        ];
        for at in beside {
            values.extend([at.next_down(), at, at.next_up()].map(f64::from));
        }
        for (bits, step) in [
            (0x3f00_0000_u32, 1),
            (0x4700_0000, 97),
            (0x4f00_0000, 9_973),
        ] {
            values.extend((0..2_000).map(|i| f64::from(f32::from_bits(bits + i * step))));
        }
        for high in [255.0, 65535.0, f64::from(u32::MAX)] {
            for &v in &values {
                let expected = v.round().clamp(0.0, high) as u64;
                assert_eq!(to_unsigned(v, high) as u64, expected, "{v} in [0, {high}]");
            }
        }
    }

    /// `weights` (VEC4 floats) packed as skin weights: what renormalising changed, and the
    /// weights written.
    fn pack_weights(weights: &[[f32; 4]]) -> (Option<Renormalised>, Vec<[f32; 4]>) {
        use base64::Engine;
        let bin: Vec<u8> = weights
            .iter()
            .flatten()
            .flat_map(|w| w.to_le_bytes())
            .collect();
        let uri = format!(
            "data:application/octet-stream;base64,{}",
            base64::engine::general_purpose::STANDARD.encode(&bin)
        );
        let asset = serde_json::json!({
            "asset": {"version": "1.0"},
            "buffers": {"b": {"uri": uri, "byteLength": bin.len()}},
            "bufferViews": {"v": {"buffer": "b", "byteLength": bin.len()}},
            "accessors": {"w": {"bufferView": "v", "componentType": FLOAT,
                "count": weights.len(), "type": "VEC4"}}
        });
        let text = serde_json::to_vec(&asset).unwrap();
        let loader = crate::document::uri::NoResources;
        let source = crate::legacy::source::read(text.into(), &loader).unwrap();
        let accessor = read(&source, "w").unwrap();
        let mut binary = Binary::default();
        let packed = pack(&accessor, Role::Weights, &mut binary);
        let written = (binary.to_vec().chunks_exact(16))
            .map(|v| {
                std::array::from_fn(|c| f32::from_le_bytes(v[4 * c..][..4].try_into().unwrap()))
            })
            .collect();
        (packed.renormalised, written)
    }

    #[test]
    fn renormalising_counts_every_vertex_it_divides_and_the_lowest_sum_across_blocks() {
        // Three blocks' worth of vertices; every seventh sums to 1 and is left alone.
        let weights: Vec<[f32; 4]> = (0..2 * BLOCK + 1000)
            .map(|i| match i % 7 {
                0 => [0.25, 0.75, 0.0, 0.0],
                _ => [0.1 + (i % 1009) as f32 / 1000.0, 0.08, 0.0, 0.0],
            })
            .collect();
        let sums: Vec<f64> = (weights.iter())
            .map(|w| w.iter().map(|&x| f64::from(x)).sum())
            .filter(|s: &f64| (s - 1.0).abs() > WEIGHT_SUM_TOLERANCE)
            .collect();
        let lowest = sums.iter().copied().fold(f64::INFINITY, f64::min);
        let (renormalised, written) = pack_weights(&weights);
        let renormalised = renormalised.expect("some sums are not 1");
        assert_eq!(renormalised.vertices, sums.len());
        assert_eq!(renormalised.lowest, lowest);
        assert_ne!(written, weights, "divided weights are new data");
        let normalised = vec![[0.5, 0.25, 0.25, 0.0]; BLOCK + 3];
        let (renormalised, written) = pack_weights(&normalised);
        assert!(renormalised.is_none(), "every sum is 1");
        assert_eq!(
            written, normalised,
            "weights that sum to 1 are kept as they are"
        );
    }

    #[test]
    fn runs_are_bounded_per_component_as_one_fold_over_each_component_bounds_them() {
        // Wide values, and zeros of both signs (which bound first wins) beside a NaN.
        let wide = [
            3.5,
            -0.0,
            0.0,
            f64::NAN,
            -7.25,
            1e300,
            -1e-300,
            42.0,
            f64::INFINITY,
        ];
        let zeros = [f64::NAN, -0.0, 0.0, 0.0, -0.0, f64::NAN, -0.0];
        let cases = [1, 2, 3, 4, 5, 9, 16].map(|n| [(n, &wide[..]), (n, &zeros[..])]);
        for (n, pool) in cases.into_iter().flatten() {
            let values: Vec<f64> = (0..37 * n)
                .map(|i| pool[(i * 5 + i / 7) % pool.len()])
                .collect();
            let mut bounds = no_bounds();
            bound_run(&mut bounds, &values[..20 * n], n);
            bound_run(&mut bounds, &values[20 * n..], n);
            for c in 0..n {
                let component = values[c..].iter().step_by(n);
                let (low, high) = component
                    .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), &v| {
                        (if v < l { v } else { l }, if v > h { v } else { h })
                    });
                assert_eq!(
                    bounds.0[c].to_bits(),
                    low.to_bits(),
                    "low of component {c} of {n}"
                );
                assert_eq!(
                    bounds.1[c].to_bits(),
                    high.to_bits(),
                    "high of component {c} of {n}"
                );
            }
        }
    }

    #[test]
    fn weights_are_divided_by_their_sum_until_single_precision_sums_to_one() {
        let mut weights = [0.1, 0.05, 0.03, 0.0].map(|w: f64| w / 0.18);
        settle_in_single_precision(&mut weights);
        let single: f32 = weights.iter().fold(0f32, |s, &w| (f64::from(s) + w) as f32);
        assert_eq!(single, 1.0);
        assert!((weights[0] - 0.1 / 0.18).abs() < 1e-6);
        assert_eq!(weights[3], 0.0, "a zero weight stays zero");
    }

    #[test]
    fn renormalised_weights_are_the_single_precision_quotients_with_the_residue_in_the_largest() {
        let mut sequence = crate::test_random::Sequence::new(88_172_645_463_325_252);
        let mut next = || sequence.unit();
        // Two blocks and a bit of vertices, with zeros, sums from about 0.05 to 4.
        let weights: Vec<[f32; 4]> = (0..2 * BLOCK + 77)
            .map(|v| std::array::from_fn(|c| if (v + c) % 5 == 3 { 0.0 } else { next() }))
            .collect();
        let (renormalised, written) = pack_weights(&weights);
        assert!(renormalised.unwrap().vertices > BLOCK);
        let single = |w: &[f32; 4]| {
            w.iter()
                .fold(0f32, |s, &v| (f64::from(s) + f64::from(v)) as f32)
        };
        for (input, output) in weights.iter().zip(&written) {
            let sum: f64 = input.iter().map(|&w| f64::from(w)).sum();
            if (sum - 1.0).abs() <= WEIGHT_SUM_TOLERANCE || sum == 0.0 {
                assert_eq!(input, output, "a vertex that sums to 1 (or to 0) is kept");
                continue;
            }
            let quotient = input.map(|w| (f64::from(w) / sum) as f32);
            let largest = (0..4)
                .max_by(|&a, &b| quotient[a].total_cmp(&quotient[b]))
                .unwrap();
            for c in 0..4 {
                if c == largest {
                    let moved = f64::from(output[c]) - f64::from(quotient[c]);
                    assert!(
                        moved.abs() <= 4e-7,
                        "{input:?} → {output:?}: the residue is rounding"
                    );
                } else {
                    assert_eq!(
                        output[c], quotient[c],
                        "{input:?} → {output:?}: component {c}"
                    );
                }
            }
            // Within the output check's allowance: a single-precision ulp near 1 per weight.
            let allowance = 2e-7 * output.iter().filter(|&&w| w != 0.0).count() as f64;
            assert!(
                (f64::from(single(output)) - 1.0).abs() <= allowance,
                "{output:?}"
            );
        }
    }

    #[test]
    fn elements_packed_in_blocks_are_laid_out_as_one_loop_lays_them() {
        let count = 3 * BLOCK + 5;
        let values: Vec<f64> = (0..count * 3).map(|v| ((v * 7919) % 300) as f64).collect();
        let mut out = Binary::default();
        let packed = pack_values(&values, 3, UNSIGNED_BYTE, false, true, &mut out);
        let (mut expected, mut min, mut max) = (Vec::new(), [f64::MAX; 3], [f64::MIN; 3]);
        for element in values.chunks_exact(3) {
            for (c, &v) in element.iter().enumerate() {
                let stored = v.min(255.0);
                expected.push(stored as u8);
                (min[c], max[c]) = (min[c].min(stored), max[c].max(stored));
            }
            expected.push(0);
        }
        assert_eq!(out.to_vec(), expected);
        assert_eq!((packed.min, packed.max), (min.to_vec(), max.to_vec()));
    }

    #[test]
    fn vertex_elements_are_padded_to_four_bytes_and_bounded() {
        let mut out = Binary::default();
        out.owned().push(9);
        let packed = pack_values(
            &[1.0, 2.0, 3.0, 4.0, 5.0, 6.0],
            3,
            UNSIGNED_BYTE,
            true,
            true,
            &mut out,
        );
        assert_eq!(packed.byte_stride, Some(4));
        assert_eq!((packed.offset, packed.length), (4, 8));
        assert_eq!(out.to_vec(), vec![9, 0, 0, 0, 1, 2, 3, 0, 4, 5, 6, 0]);
        assert_eq!(
            (packed.min, packed.max),
            (vec![1.0, 2.0, 3.0], vec![4.0, 5.0, 6.0])
        );
        let floats = pack_values(&[0.5, -1.0], 2, FLOAT, false, true, &mut out);
        assert_eq!(floats.byte_stride, None);
    }
}
