//! Skinning influences: each vertex's JOINTS_n / WEIGHTS_n sets read together (the Khronos
//! ACCESSOR_JOINTS_* and ACCESSOR_WEIGHTS_* codes).

use super::accessor_data::{scannable, unit_scale, visit};
use super::accessor_fast::Layout;
use super::accessor_usage::{Budget, Findings};
use super::resources::ViewData;
use crate::check::context::{elements, unsigned, Context};
use crate::diagnostic::khronos;
use crate::document::{Array, Node};
use rayon::prelude::*;
use std::collections::HashMap;
use std::ops::Range;

pub fn check(ctx: &mut Context) {
    let mut budget = Budget::new();
    let limits = limiting_skins(ctx);
    for (m, pointer, mesh) in ctx.objects("meshes") {
        let Some(&(max_joint, skin)) = limits.get(&m) else {
            continue;
        };
        for (p, primitive) in elements(mesh, "primitives") {
            if let Some(sets) = influence_sets(ctx, primitive) {
                let at = format!("{pointer}/primitives/{p}/attributes");
                let limit = JointLimit { max_joint, skin };
                let mut found = budget.share(1);
                check_primitive(&sets, &at, limit, &mut found);
                budget.spend(&found);
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
    weight_scale: fn(f64) -> f64,
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
    /// The components of `vertices`, four a vertex, or None when their bytes cannot be
    /// read (the file changed).
    fn decode(&self, vertices: &Range<usize>) -> Option<Vec<f64>> {
        let layout = &self.layout;
        let last = vertices.end.checked_sub(1)?;
        let start = layout.offset + vertices.start * layout.stride;
        let end = layout.offset + last * layout.stride + layout.size * layout.components;
        let bytes = self.view.part(start..end)?.read()?;
        let block = Layout {
            offset: 0,
            count: vertices.len(),
            ..*layout
        };
        let mut values = Vec::with_capacity(vertices.len() * layout.components);
        visit(&block, &bytes, |_, batch| values.extend_from_slice(batch));
        Some(values)
    }
}

/// All sets of a primitive, or None when any is missing, unreadable or of another length
/// (those are reported elsewhere).
fn influence_sets<'c>(ctx: &'c Context, primitive: Node) -> Option<Vec<Set<'c>>> {
    let attributes = primitive.get("attributes")?;
    let accessors = ctx.items("accessors");
    let vertex_count = attributes
        .as_object()?
        .values()
        .next()
        .and_then(|a| accessors.get(a.as_u64()? as usize))
        .and_then(|a| unsigned(a, "count"))?;
    let mut sets = Vec::new();
    for n in 0.. {
        let Some(joints) = attributes.get(format!("JOINTS_{n}")) else {
            break;
        };
        let joints = accessors.get(joints.as_u64()? as usize)?;
        let weights = accessors.get(attributes.get(format!("WEIGHTS_{n}"))?.as_u64()? as usize)?;
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

/// Checks the influences of `vertices`; false when their bytes cannot be read.
fn check_block(
    sets: &[Set],
    vertices: &Range<usize>,
    at: &str,
    limit: JointLimit,
    out: &mut Findings,
) -> bool {
    let joints_at = |n: usize| format!("{at}/JOINTS_{n}");
    let weights_at = |n: usize| format!("{at}/WEIGHTS_{n}");
    let decoded: Option<Vec<(Vec<f64>, Vec<f64>)>> = (sets.iter())
        .map(|set| Some((set.joints.decode(vertices)?, set.weights.decode(vertices)?)))
        .collect();
    let Some(decoded) = decoded else {
        return false;
    };
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
            for (n, (set, (joints, weights))) in sets.iter().zip(&decoded).enumerate() {
                let joint = joints[k * 4 + c];
                if joint > limit.max_joint {
                    out.record(khronos::ACCESSOR_JOINTS_INDEX_OOB, || joints_at(n), || format!("Joints accessor element at index {index} (component index {c}) has value {joint} that is greater than the maximum joint index ({}) set by skin {}.", limit.max_joint, limit.skin));
                    continue;
                }
                let weight = (set.weight_scale)(weights[k * 4 + c]);
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
                    out.record(khronos::ACCESSOR_WEIGHTS_NEGATIVE, || weights_at(n), || format!("Weights accessor element at index {index} (component index {c}) has negative value {weight:?}."));
                } else if unique {
                    sum = (f64::from(sum) + weight) as f32;
                    allowance += 2e-7;
                }
            }
        }
        if (f64::from(sum) - 1.0).abs() > allowance {
            let first = vertex * 4;
            for n in 0..sets.len() {
                out.record(khronos::ACCESSOR_WEIGHTS_NON_NORMALIZED, || weights_at(n), || format!("Weights accessor elements (at indices {first}..{}) have non-normalized sum: {:?}.", first + 3, f64::from(sum)));
            }
        }
    }
    true
}
