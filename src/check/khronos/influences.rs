//! Skinning influences: each vertex's JOINTS_n / WEIGHTS_n sets read together (the Khronos
//! ACCESSOR_JOINTS_* and ACCESSOR_WEIGHTS_* codes).

use super::accessor_data::{scannable, unit_scale};
use super::accessor_usage::Findings;
use super::resources::ViewData;
use super::Dart;
use crate::check::context::{elements, unsigned, Context};
use crate::diagnostic::khronos;
use crate::document::{Array, Node};
use crate::gltf::accessor::{decode, Layout};
use crate::gltf::as_index;
use crate::gltf::gl;
use rayon::prelude::*;
use std::borrow::Cow;
use std::collections::HashMap;
use std::ops::Range;

pub(super) fn check(ctx: &mut Context) {
    let mut budget = ctx.diagnostics.walk_budget();
    let limits = limiting_skins(ctx);
    for (m, pointer, mesh) in ctx.objects("meshes") {
        let Some(&(max_joint, skin)) = limits.get(&m) else {
            continue;
        };
        for (p, primitive) in elements(mesh, "primitives") {
            if let Some(sets) = influence_sets(ctx, primitive) {
                let at = format!("{pointer}/primitives/{p}/attributes");
                let limit = JointLimit { max_joint, skin };
                let mut found = Findings::listing(budget.share(1));
                check_primitive(&sets, &at, limit, &mut found);
                budget.spend(found.listed());
                found.report(ctx);
            }
        }
    }
}

/// The largest joint index every skin used with the mesh can resolve, and that skin.
#[derive(Clone, Copy)]
struct JointLimit {
    max_joint: f64,
    skin: usize,
}

/// For each mesh drawn skinned, the largest joint index every skin it is drawn with can
/// resolve, and the skin with the fewest joints (one pass over the nodes for all meshes).
fn limiting_skins(ctx: &Context) -> HashMap<usize, (f64, usize)> {
    let skins = ctx.items("skins");
    let mut fewest: HashMap<usize, (usize, usize)> = HashMap::new();
    for node in ctx.items("nodes") {
        let (Some(m), Some(s)) = (unsigned(node, "mesh"), unsigned(node, "skin")) else {
            continue;
        };
        let Some(joints) = (skins.get(s as usize))
            .and_then(|skin| skin.get("joints")?.as_array())
            .map(Array::len)
        else {
            continue;
        };
        let entry = fewest.entry(m as usize).or_insert((joints, s as usize));
        if joints < entry.0 {
            *entry = (joints, s as usize);
        }
    }
    (fewest.into_iter())
        .filter(|(_, (joints, _))| *joints > 0)
        .map(|(m, (joints, s))| (m, ((joints - 1) as f64, s)))
        .collect()
}

/// One JOINTS_n / WEIGHTS_n pair, readable and as long as the primitive.
struct Set<'c> {
    joints: Attribute<'c>,
    weights: Attribute<'c>,
    /// What makes the stored weights the values a shader sees (normalized integers); None
    /// when they are those values.
    weight_scale: Option<fn(f64) -> f64>,
}

/// Vertices checked as one piece of work: each attribute's elements for the block are
/// read and decoded at once (the component type matched once a block, not once a value),
/// and blocks run on all cores. A block's decoded sets take 256 KB an attribute.
const BLOCK: usize = 1 << 13;

/// One attribute's elements in its view (read a block at a time: a primitive may have many
/// sets, all over one large view of a GLB read from its file).
struct Attribute<'c> {
    layout: Layout,
    view: ViewData<'c>,
}

impl Attribute<'_> {
    /// The bytes of `vertices`, from the first's element to the last's, or None when they
    /// cannot be read (the file changed).
    fn bytes(&self, vertices: &Range<usize>) -> Option<Cow<'_, [u8]>> {
        let layout = &self.layout;
        let last = vertices.end.checked_sub(1)?;
        let start = layout.offset + vertices.start * layout.stride;
        let end = layout.offset + last * layout.stride + layout.size * layout.components;
        self.view.part(start..end)?.read()
    }

    /// The elements of `vertices` as stored, four components of `SIZE` bytes each, read
    /// by `value`.
    fn stored<'b, const SIZE: usize, T>(
        &self,
        bytes: &'b [u8],
        value: impl Fn([u8; SIZE]) -> T + 'b,
    ) -> impl Iterator<Item = [T; 4]> + 'b {
        // Elements never overlap (see `scannable`): each chunk holds a whole element.
        (bytes.chunks(self.layout.stride)).map(move |element| {
            let element = &element[..4 * SIZE];
            std::array::from_fn(|c| {
                value(element[SIZE * c..][..SIZE].try_into().unwrap_or([0; SIZE]))
            })
        })
    }

    /// The components of `vertices`, four a vertex, or None when their bytes cannot be
    /// read (the file changed).
    fn decode(&self, vertices: &Range<usize>) -> Option<Vec<f64>> {
        let layout = &self.layout;
        let bytes = self.bytes(vertices)?;
        let block = Layout {
            offset: 0,
            count: vertices.len(),
            ..*layout
        };
        let mut values = vec![0.0; vertices.len() * layout.components];
        decode(&block, &bytes, 0, &mut values).then_some(values)
    }
}

/// All sets of a primitive, or None when any is missing, unreadable or of another length
/// (those are reported elsewhere).
fn influence_sets<'c>(ctx: &'c Context, primitive: Node) -> Option<Vec<Set<'c>>> {
    let attributes = primitive.get("attributes")?;
    let accessors = ctx.items("accessors");
    let vertex_count = super::primitives::vertex_count(attributes, accessors)?;
    let mut sets = Vec::new();
    for n in 0.. {
        let Some(joints) = attributes.get(format!("JOINTS_{n}")) else {
            break;
        };
        let joints = accessors.get(usize::try_from(as_index(joints)?).ok()?)?;
        let weights = accessors
            .get(usize::try_from(as_index(attributes.get(format!("WEIGHTS_{n}"))?)?).ok()?)?;
        let readable = |a: Node<'c>| {
            let (layout, view) = scannable(ctx, a)?;
            let fits = layout.count as u64 == vertex_count && layout.components == 4;
            fits.then_some(Attribute { layout, view })
        };
        let weight_scale = unit_scale(unsigned(weights, "componentType")?, weights);
        sets.push(Set {
            joints: readable(joints)?,
            weights: readable(weights)?,
            weight_scale,
        });
    }
    (!sets.is_empty()).then_some(sets)
}

/// Blocks of vertices checked in parallel before their findings are merged: what the
/// blocks may keep is what the findings so far left room for.
const BLOCKS_AT_ONCE: usize = 16;

fn check_primitive(sets: &[Set], at: &str, limit: JointLimit, out: &mut Findings) {
    let count = sets[0].joints.layout.count;
    let blocks: Vec<Range<usize>> = (0..count.div_ceil(BLOCK))
        .map(|b| b * BLOCK..((b + 1) * BLOCK).min(count))
        .collect();
    for batch in blocks.chunks(BLOCKS_AT_ONCE) {
        let checked: Vec<Option<Findings>> = (batch.par_iter())
            .map(|vertices| {
                let mut found = out.room();
                check_block(sets, vertices, at, limit, &mut found).then_some(found)
            })
            .collect();
        for found in checked {
            // Unreadable data ends the walk (the accessor-data pass reports it).
            let Some(found) = found else { return };
            out.absorb(found);
        }
    }
}

/// Checks the influences of `vertices`; false when their bytes cannot be read. A block of
/// one set is first asked [`nothing_to_report`]: read as stored when its types allow (see
/// [`Set::read_as_stored`]), else as the doubles the walk would read anyway.
fn check_block(
    sets: &[Set],
    vertices: &Range<usize>,
    at: &str,
    limit: JointLimit,
    out: &mut Findings,
) -> bool {
    let one_set = match sets {
        [set] => Some(set),
        _ => None,
    };
    if let Some(set) = one_set.filter(|set| set.read_as_stored()) {
        match set.stored_nothing_to_report(vertices, limit.max_joint) {
            None => return false,
            Some(true) => return true,
            Some(false) => {}
        }
    }
    let decoded: Option<Vec<(Vec<f64>, Vec<f64>)>> =
        (sets.iter()).map(|set| set.decode(vertices)).collect();
    let Some(decoded) = decoded else {
        return false;
    };
    let clean = match (one_set, &decoded[..]) {
        (Some(set), [(joints, weights)]) if !set.read_as_stored() => {
            let vertices = (joints.chunks_exact(4).zip(weights.chunks_exact(4)))
                .map(|(j, w)| (four(j), four(w)));
            nothing_to_report(vertices, limit.max_joint, sum_as_the_walk_adds)
        }
        _ => false,
    };
    if !clean {
        walk(&decoded, vertices, at, limit, out);
    }
    true
}

impl Set<'_> {
    /// Its joints and weights (as a shader sees them) of `vertices`, four a vertex; None
    /// when their bytes cannot be read.
    fn decode(&self, vertices: &Range<usize>) -> Option<(Vec<f64>, Vec<f64>)> {
        let mut weights = self.weights.decode(vertices)?;
        if let Some(scale) = self.weight_scale {
            weights.iter_mut().for_each(|w| *w = scale(*w));
        }
        Some((self.joints.decode(vertices)?, weights))
    }

    /// Whether its influences are of the usual kinds, unsigned joints with float weights,
    /// which are tested as stored: in their own types a vertex's tests take half the time
    /// they take as doubles.
    fn read_as_stored(&self) -> bool {
        let joints = self.joints.layout.component_type;
        self.weights.layout.component_type == gl::FLOAT
            && matches!(joints, gl::UNSIGNED_BYTE | gl::UNSIGNED_SHORT)
    }

    /// [`nothing_to_report`] of `vertices` read as stored (see [`Set::read_as_stored`]);
    /// None when their bytes cannot be read.
    fn stored_nothing_to_report(&self, vertices: &Range<usize>, max_joint: f64) -> Option<bool> {
        let (joints, weights) = (self.joints.bytes(vertices)?, self.weights.bytes(vertices)?);
        let weights = self.weights.stored(&weights, f32::from_le_bytes);
        // Every joint compared is an integer, and so is `max_joint`.
        let limit = max_joint.min(f64::from(u16::MAX)) as u16;
        Some(match self.joints.layout.component_type {
            gl::UNSIGNED_BYTE => {
                let joints = self.joints.stored(&joints, |[b]| u16::from(b));
                nothing_to_report(joints.zip(weights), limit, sum_of_floats)
            }
            _ => {
                let joints = self.joints.stored(&joints, u16::from_le_bytes);
                nothing_to_report(joints.zip(weights), limit, sum_of_floats)
            }
        })
    }
}

/// The first four values of `values`.
fn four(values: &[f64]) -> [f64; 4] {
    std::array::from_fn(|c| values[c])
}

/// Every finding of `vertices`, whose sets are `decoded` (joints and weights as a shader
/// sees them, four a vertex), one vertex at a time.
fn walk(
    decoded: &[(Vec<f64>, Vec<f64>)],
    vertices: &Range<usize>,
    at: &str,
    limit: JointLimit,
    out: &mut Findings,
) {
    let joints_at = |n: usize| format!("{at}/JOINTS_{n}");
    let weights_at = |n: usize| format!("{at}/WEIGHTS_{n}");
    // A vertex has a few influences: a short list searched linearly beats hashing, and it
    // is reused from vertex to vertex.
    let mut seen: Vec<u64> = Vec::new();
    for (k, vertex) in vertices.clone().enumerate() {
        seen.clear();
        let mut sum = 0f32;
        // Rounding allowance: a float32 ulp near 1 per weight summed.
        let mut allowance = 0.0;
        for c in 0..4 {
            let index = vertex * 4 + c;
            for (n, (joints, weights)) in decoded.iter().enumerate() {
                let joint = joints[k * 4 + c];
                if joint > limit.max_joint {
                    out.record(khronos::ACCESSOR_JOINTS_INDEX_OOB, || joints_at(n), || format!("Joints accessor element at index {index} (component index {c}) has value {joint} that is greater than the maximum joint index ({}) set by skin {}.", limit.max_joint, limit.skin));
                    continue;
                }
                let weight = weights[k * 4 + c];
                if weight == 0.0 {
                    if joint != 0.0 {
                        out.record(khronos::ACCESSOR_JOINTS_USED_ZERO_WEIGHT, || joints_at(n), || format!("Joints accessor element at index {index} (component index {c}) is used with zero weight but has non-zero value ({joint})."));
                    }
                    continue;
                }
                let unique = !seen.contains(&joint.to_bits());
                if unique {
                    seen.push(joint.to_bits());
                }
                if !unique {
                    out.record(khronos::ACCESSOR_JOINTS_INDEX_DUPLICATE, || joints_at(n), || format!("Joints accessor element at index {index} (component index {c}) has value {joint} that is already in use for the vertex."));
                }
                if weight < 0.0 {
                    out.record(khronos::ACCESSOR_WEIGHTS_NEGATIVE, || weights_at(n), || format!("Weights accessor element at index {index} (component index {c}) has negative value {}.", Dart(weight)));
                } else if unique {
                    sum = (f64::from(sum) + weight) as f32;
                    allowance += 2e-7;
                }
            }
        }
        if (f64::from(sum) - 1.0).abs() > allowance {
            let first = vertex * 4;
            for n in 0..decoded.len() {
                out.record(khronos::ACCESSOR_WEIGHTS_NON_NORMALIZED, || weights_at(n), || format!("Weights accessor elements (at indices {first}..{}) have non-normalized sum: {}.", first + 3, Dart(f64::from(sum))));
            }
        }
    }
}

/// Whether the vertices of one set of influences (four joints and four weights each, the
/// weights as a shader sees them) have nothing the walk in [`check_block`] reports: every
/// joint at most `max_joint`, joint 0 wherever the weight is 0, no joint twice among the
/// weighted ones, no negative (or NaN) weight, and a single-precision sum (`sum`) within the
/// walk's allowance (a zero weight adds nothing to it). Real data is like this, and this
/// needs neither a finding to make nor a list of joints seen; whenever it says no, the walk
/// runs and finds what there is. Joints and weights may be of any type
/// that holds their values exactly: doubles, or the types they are stored in.
fn nothing_to_report<J, W>(
    vertices: impl Iterator<Item = ([J; 4], [W; 4])>,
    max_joint: J,
    sum: impl Fn(&[W; 4]) -> f32,
) -> bool
where
    J: Copy + PartialOrd + Default,
    W: Copy + PartialOrd + Default,
{
    let zero_joint = J::default();
    let zero = W::default();
    vertices.fold(true, |clean, (j, w)| {
        let mut fine = clean;
        let mut allowance = 0.0;
        for c in 0..4 {
            fine &= j[c] <= max_joint && w[c] >= zero && (w[c] != zero || j[c] == zero_joint);
            for d in 0..c {
                fine &= w[d] == zero || w[c] == zero || j[d] != j[c];
            }
            if w[c] != zero {
                allowance += 2e-7;
            }
        }
        fine && (f64::from(sum(&w)) - 1.0).abs() <= allowance
    })
}

/// A vertex's weights summed in order as the walk sums them: each addition made in double
/// precision and rounded to single.
fn sum_as_the_walk_adds(weights: &[f64; 4]) -> f32 {
    (weights.iter()).fold(0f32, |sum, &w| (f64::from(sum) + w) as f32)
}

/// [`sum_as_the_walk_adds`] of single-precision weights, added in single precision: the
/// same sum, since the double-precision sum of two single-precision numbers, rounded to
/// single precision, is their single-precision sum (double precision has more than twice
/// the digits plus two, which makes the two roundings one).
fn sum_of_floats(weights: &[f32; 4]) -> f32 {
    weights.iter().fold(0.0, |sum, &w| sum + w)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Joints and weights a vertex's four influences may hold: in range, past the skin's
    /// last joint (3), NaN and a negative zero; weights that sum to 1, slightly off it,
    /// zero, negative and NaN.
    const JOINTS: [f64; 7] = [0.0, 1.0, 2.0, 3.0, 4.0, f64::NAN, -0.0];
    const WEIGHTS: [f64; 9] = [
        0.0,
        0.25,
        0.5,
        1.0,
        0.5 + 3e-7,
        0.125,
        -0.25,
        f64::NAN,
        1e-8,
    ];

    /// Vertices drawn from those values by a fixed generator, clean ones among them.
    fn vertices(count: usize) -> Vec<([f64; 4], [f64; 4])> {
        let mut sequence = crate::test_random::Sequence::new(0x2545_f491_4f6c_dd1d);
        let mut next = |n: usize| sequence.below(n);
        let clean = [
            ([0.0, 1.0, 2.0, 0.0], [0.25, 0.25, 0.5, 0.0]),
            ([3.0, 0.0, 0.0, 0.0], [1.0, 0.0, 0.0, 0.0]),
        ];
        (0..count)
            .map(|_| match next(3) {
                0 => clean[next(2)],
                _ => (
                    std::array::from_fn(|_| JOINTS[next(JOINTS.len())]),
                    std::array::from_fn(|_| WEIGHTS[next(WEIGHTS.len())]),
                ),
            })
            .collect()
    }

    fn found_by_walk(joints: &[f64], weights: &[f64]) -> bool {
        let mut found = Findings::listing(usize::MAX);
        let decoded = [(joints.to_vec(), weights.to_vec())];
        let limit = JointLimit {
            max_joint: 3.0,
            skin: 0,
        };
        walk(
            &decoded,
            &(0..joints.len() / 4),
            "/meshes/0",
            limit,
            &mut found,
        );
        !found.is_empty()
    }

    /// [`nothing_to_report`] of vertices decoded into doubles, with the skin's last joint 3.
    fn in_doubles(vertices: &[([f64; 4], [f64; 4])]) -> bool {
        nothing_to_report(vertices.iter().copied(), 3.0, sum_as_the_walk_adds)
    }

    #[test]
    fn the_fast_answer_is_the_walks_wherever_it_says_nothing_is_to_report() {
        let (mut clean, mut reported) = (0, 0);
        for (joints, weights) in vertices(20_000) {
            let fast = in_doubles(&[(joints, weights)]);
            let found = found_by_walk(&joints, &weights);
            assert!(
                !(fast && found),
                "{joints:?} {weights:?}: the walk finds something"
            );
            // NaN and a negative zero joint are left to the walk, which may find nothing.
            let unusual = joints.iter().chain(&weights).any(|v| v.is_nan())
                || joints.iter().any(|j| *j == 0.0 && j.is_sign_negative());
            if !unusual {
                assert_eq!(fast, !found, "{joints:?} {weights:?}");
            }
            clean += usize::from(fast);
            reported += usize::from(found);
        }
        assert!(
            clean > 5_000 && reported > 5_000,
            "{clean} clean, {reported} reported"
        );
    }

    #[test]
    fn a_block_has_nothing_to_report_only_when_none_of_its_vertices_has() {
        let all = vertices(4_000);
        let clean = |v: &&([f64; 4], [f64; 4])| in_doubles(&[**v]);
        let mut block: Vec<_> = all.iter().filter(clean).copied().collect();
        let dirty = *all.iter().find(|v| !clean(v)).unwrap();
        assert!(block.len() > 1_000 && in_doubles(&block));
        block.insert(block.len() / 2, dirty);
        assert!(!in_doubles(&block), "{dirty:?} has something to report");
    }

    #[test]
    fn influences_read_as_stored_have_the_answer_they_have_as_doubles() {
        let mut sequence = crate::test_random::Sequence::new(0x9e37_79b9_7f4a_7c15);
        let mut next = || sequence.unit();
        let (mut clean, mut reported) = (0, 0);
        for _ in 0..50_000 {
            // Weights that sum to about 1, off by up to a few single-precision steps, some
            // zero and, rarely, negative; distinct joints (0 where the weight is 0), now and
            // then one past the skin's last or the same as another.
            let raw: [f32; 4] = std::array::from_fn(|_| match next() {
                p if p < 0.2 => 0.0,
                p if p < 0.21 => -0.5,
                _ => next(),
            });
            let total: f32 = raw.iter().sum();
            let off = 1.0 + (f64::from(next()) - 0.5) * 2e-6;
            let weights = raw.map(|w| (f64::from(w) / f64::from(total) * off) as f32);
            let first = (next() * 4.0) as u16;
            let joints: [u16; 4] = std::array::from_fn(|c| match next() {
                _ if weights[c] == 0.0 => 0,
                p if p < 0.03 => 4,
                p if p < 0.06 => first,
                _ => (first + c as u16) % 4,
            });
            let stored = nothing_to_report(std::iter::once((joints, weights)), 3, sum_of_floats);
            let doubles = (joints.map(f64::from), weights.map(f64::from));
            assert_eq!(stored, in_doubles(&[doubles]), "{joints:?} {weights:?}");
            clean += usize::from(stored);
            reported += usize::from(!stored);
        }
        assert!(
            clean > 5_000 && reported > 5_000,
            "{clean} clean, {reported} reported"
        );
    }
}
