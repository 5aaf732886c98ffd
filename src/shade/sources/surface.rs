//! An asset's meshes as the comparison reads them: the triangles of each material in UV
//! space, where its UV grid is sampled (a viewer never sees the gutters between UV islands),
//! and points on them carrying their texture coordinates in every TEXCOORD_n set, so that
//! each slot is read through its own set, as a viewer reads it. Only points whose sets differ
//! are kept: where every set agrees, the comparison's UV grid already holds the point.

use super::views::Views;
use crate::document::Node;
use crate::gltf::accessor::{component_count, component_size, decode, normalise, Layout};
use crate::gltf::coverage::{Grid, Painter, Seen};
use crate::gltf::mesh::{drawn_materials, triangle_count, triangles};
use crate::gltf::{as_index, unsigned};
use std::collections::HashMap;
use std::sync::Arc;

/// A point's UV in each texCoord set, set 0 first.
pub(crate) type Point = Vec<[f64; 2]>;

/// The points of one material, and why some of its primitives gave none (their texture
/// coordinates could not be read as plain accessors); and the triangles of the primitives
/// drawing it.
#[derive(Clone, Debug, Default)]
pub(crate) struct Surface {
    pub points: Vec<Point>,
    pub unread: Option<String>,
    pub meshes: Meshes,
}

/// The primitives drawing a material, as far as the comparison's UV grid needs them: their
/// triangles in each texCoord set.
#[derive(Clone, Debug)]
pub(crate) enum Meshes {
    /// Why the whole UV square stands for them.
    Unknown(&'static str),
    Read(Vec<Arc<Sets>>),
}

impl Default for Meshes {
    fn default() -> Self {
        Meshes::Unknown(NOT_DRAWN)
    }
}

/// Why the UV grid is sampled whole.
pub(crate) const NOT_DRAWN: &str = "no mesh draws it";
const NO_TEXTURE: &str = "neither material reads a texture";
const UNREAD: &str = "its meshes' texture coordinates cannot be read as plain accessors";
const NO_SUCH_SET: &str = "a texture is read through a texCoord set its mesh does not have";
const TOO_MANY: &str = "its triangles cover the texture too many times over to tell";
const NO_TRIANGLE: &str = "its meshes have no triangle with finite texture coordinates";

impl Meshes {
    /// Every mesh of `all`: the whole square when any stands for it.
    pub(crate) fn union<'m>(all: impl IntoIterator<Item = &'m Meshes>) -> Meshes {
        let mut union: Vec<Arc<Sets>> = Vec::new();
        for meshes in all {
            match meshes {
                Meshes::Unknown(why) => return Meshes::Unknown(why),
                Meshes::Read(read) => union.extend(read.iter().cloned()),
            }
        }
        // Alike materials on one mesh bring it once.
        Meshes::Read(first_of_each(union))
    }

    /// The texels of a `grid`² grid over the UV square that a bilinear sample inside one of
    /// the triangles reads through texCoord sets `sets`, the UVs wrapping as REPEAT wraps
    /// them (the grid's coordinates are the mesh's, before any texture transform). Err: why
    /// the whole square stands for them.
    pub(crate) fn seen(&self, sets: &[usize], grid: u32) -> Result<Seen, &'static str> {
        let primitives = match self {
            Meshes::Unknown(why) => return Err(why),
            Meshes::Read(primitives) if primitives.is_empty() => return Err(NOT_DRAWN),
            Meshes::Read(primitives) => primitives,
        };
        if sets.is_empty() {
            return Err(NO_TEXTURE);
        }
        let mut painter = Painter::new(Grid::plain(grid as usize));
        for primitive in primitives {
            for &set in sets {
                let uvs = primitive.uvs.get(set).ok_or(NO_SUCH_SET)?;
                for [a, b, c] in primitive.triangles() {
                    painter.triangle([uvs[a], uvs[b], uvs[c]]).ok_or(TOO_MANY)?;
                }
            }
        }
        let seen = painter.seen();
        match seen.count() {
            0 => Err(NO_TRIANGLE),
            _ => Ok(seen),
        }
    }
}

/// Texture coordinate sets read per primitive (the spec's minimum a viewer supports is 2).
const SETS: usize = 4;
/// Triangles looked at per material: spread evenly over its primitives' triangles.
const TRIANGLES_PER_MATERIAL: usize = 1024;
/// Vertex elements read for one asset at most; past it the remaining materials keep the grid.
const MAX_ELEMENTS: usize = 1 << 22;
/// Where in a triangle the points lie (barycentric): its centroid and a point towards each
/// corner, so that a sharp texture is read between its texel centres too.
const WEIGHTS: [[f64; 3]; 4] = [
    [1.0 / 3.0, 1.0 / 3.0, 1.0 / 3.0],
    [0.7, 0.15, 0.15],
    [0.15, 0.7, 0.15],
    [0.15, 0.15, 0.7],
];

/// Where a document's mesh data lies: glTF 2.0's arrays, or glTF 1.0's dictionaries.
pub(super) trait MeshData<'t> {
    /// For each material, in material order, the primitives that draw it.
    fn drawing(&self) -> Vec<Vec<Node<'t>>>;
    /// The accessor a primitive's attribute or `indices` names.
    fn accessor(&self, reference: Node<'t>) -> Option<Node<'t>>;
    /// The bytes an accessor's buffer view holds, and the stride its elements lie at when
    /// one is given.
    fn bytes(&self, accessor: Node<'t>) -> Option<(&[u8], Option<usize>)>;
}

/// A glTF 2.0 document's meshes.
pub(super) struct Gltf2Meshes<'t, 'd> {
    root: Node<'t>,
    accessors: Vec<Node<'t>>,
    views: &'d Views<'d>,
}

impl<'t, 'd> Gltf2Meshes<'t, 'd> {
    pub(super) fn of(root: Node<'t>, views: &'d Views<'d>) -> Self {
        let accessors = (root.get("accessors").and_then(Node::as_array))
            .map(|a| a.iter().collect())
            .unwrap_or_default();
        Gltf2Meshes {
            root,
            accessors,
            views,
        }
    }
}

impl<'t> MeshData<'t> for Gltf2Meshes<'t, '_> {
    fn drawing(&self) -> Vec<Vec<Node<'t>>> {
        let items = |key: &str| self.root.get(key).and_then(Node::as_array);
        let material_count = items("materials").map_or(0, |a| a.len());
        let primitives = (items("meshes").into_iter().flat_map(|a| a.iter()))
            .filter_map(|mesh| mesh.get("primitives")?.as_array())
            .flat_map(|primitives| primitives.iter());
        let mut drawn: Vec<Vec<Node>> = vec![Vec::new(); material_count];
        for primitive in primitives {
            for material in drawn_materials(primitive) {
                if let Some(list) = drawn.get_mut(material as usize) {
                    list.push(primitive);
                }
            }
        }
        drawn
    }

    fn accessor(&self, reference: Node<'t>) -> Option<Node<'t>> {
        let index = usize::try_from(as_index(reference)?).ok()?;
        self.accessors.get(index).copied()
    }

    fn bytes(&self, accessor: Node<'t>) -> Option<(&[u8], Option<usize>)> {
        let view = unsigned(accessor, "bufferView")?;
        Some((self.views.bytes(view)?, self.views.stride(view)))
    }
}

/// For each material of a document, the primitives that draw it, and points on their
/// triangles whose texCoord sets differ (none for a material no mesh draws, meshes with one
/// set, or what cannot be read).
pub(super) fn surface_points<'t>(data: &impl MeshData<'t>) -> Vec<Surface> {
    let drawn = data.drawing();
    let mut surfaces = vec![Surface::default(); drawn.len()];
    let reader = Reader { data };
    let mut budget = MAX_ELEMENTS;
    // Primitives that share their accessors (meshes made of one set of vertex data) are read
    // once, within the budget once.
    let mut read: HashMap<String, Option<Arc<Sets>>> = HashMap::new();
    for (material, primitives) in drawn.iter().enumerate() {
        let mut meshes: Vec<Arc<Sets>> = Vec::new();
        for (i, primitive) in primitives.iter().enumerate() {
            let sets = read
                .entry(read_key(*primitive))
                .or_insert_with(|| reader.sets(*primitive, &mut budget).map(Arc::new));
            match sets {
                Some(sets) => meshes.push(Arc::clone(sets)),
                None => {
                    surfaces[material].unread = Some(format!(
                        "the texture coordinates of {} primitive(s) drawing it cannot be read as plain accessors (compressed, sparse, invalid or past the read budget)",
                        primitives.len() - i
                    ));
                    break;
                }
            }
        }
        let meshes = first_of_each(meshes);
        surfaces[material].meshes = match surfaces[material].unread {
            Some(_) => Meshes::Unknown(UNREAD),
            None => Meshes::Read(meshes.clone()),
        };
        if surfaces[material].unread.is_some() || !meshes.iter().any(|s| s.uvs.len() > 1) {
            continue;
        }
        let total: usize = meshes.iter().map(|sets| sets.triangle_count()).sum();
        let step = total.div_ceil(TRIANGLES_PER_MATERIAL).max(1);
        for mesh in &meshes {
            for [a, b, c] in mesh.triangles().step_by(step) {
                for w in WEIGHTS {
                    let point: Point = (mesh.uvs.iter())
                        .map(|uv| {
                            [0, 1].map(|k| w[0] * uv[a][k] + w[1] * uv[b][k] + w[2] * uv[c][k])
                        })
                        .collect();
                    if point
                        .iter()
                        .any(|uv| (uv[0] - point[0][0]).abs() + (uv[1] - point[0][1]).abs() > 1e-9)
                    {
                        surfaces[material].points.push(point);
                    }
                }
            }
        }
    }
    surfaces
}

#[cfg(test)]
impl Meshes {
    /// One primitive of `triangles`, in texCoord set 0.
    pub(crate) fn of_triangles(triangles: &[[[f64; 2]; 3]]) -> Meshes {
        let uvs = triangles.iter().flatten().copied().collect();
        let sets = Sets {
            uvs: vec![uvs],
            indices: None,
            mode: 4,
        };
        Meshes::Read(vec![Arc::new(sets)])
    }
}

/// Each primitive's read once, in the order first met (a hash of where each lies: one
/// material may be drawn by 10^5 primitives, and a scan for each is quadratic).
fn first_of_each(meshes: Vec<Arc<Sets>>) -> Vec<Arc<Sets>> {
    let mut met = std::collections::HashSet::new();
    (meshes.into_iter())
        .filter(|sets| met.insert(Arc::as_ptr(sets)))
        .collect()
}

/// What makes two primitives' reads the same: their texture coordinate accessors, their
/// indices and their mode.
fn read_key(primitive: Node) -> String {
    let attributes = primitive.get("attributes");
    let texcoords =
        (0..SETS).map(|set| attributes.and_then(|a| a.get(format!("TEXCOORD_{set}").as_str())));
    let members = texcoords.chain([primitive.get("indices"), primitive.get("mode")]);
    let texts: Vec<String> = members
        .map(|member| member.map_or_else(String::new, |m| m.to_value().to_string()))
        .collect();
    texts.join(";")
}

/// A primitive's texture coordinate sets and how its vertices make triangles.
#[derive(Debug)]
pub(crate) struct Sets {
    uvs: Vec<Vec<[f64; 2]>>,
    indices: Option<Vec<usize>>,
    mode: u64,
}

impl Sets {
    /// Vertices drawn (none without texture coordinates: there is nothing to place).
    fn vertex_count(&self) -> usize {
        match self.uvs.first() {
            None => 0,
            Some(set) => self.indices.as_ref().map_or(set.len(), Vec::len),
        }
    }

    fn triangle_count(&self) -> usize {
        triangle_count(self.mode, self.vertex_count())
    }

    fn triangles(&self) -> impl Iterator<Item = [usize; 3]> + '_ {
        let at = |i: usize| self.indices.as_ref().map_or(i, |list| list[i]);
        triangles(self.mode, self.vertex_count(), at)
    }
}

struct Reader<'r, D> {
    data: &'r D,
}

impl<'t, D: MeshData<'t>> Reader<'_, D> {
    /// The primitive's sets TEXCOORD_0, TEXCOORD_1 … (as many as it has, up to [`SETS`]; none
    /// for a primitive without texture coordinates), or None when one cannot be read.
    fn sets(&self, primitive: Node<'t>, budget: &mut usize) -> Option<Sets> {
        let attributes = primitive.get("attributes")?;
        let mut uvs = Vec::new();
        for set in 0..SETS {
            let Some(accessor) = attributes.get(format!("TEXCOORD_{set}").as_str()) else {
                break;
            };
            let values = self.read(accessor, budget)?;
            uvs.push(
                values
                    .chunks_exact(2)
                    .map(|p| [p[0], p[1]])
                    .collect::<Vec<_>>(),
            );
        }
        let mode = unsigned(primitive, "mode").unwrap_or(4);
        let Some(vertices) = uvs.first().map(Vec::len) else {
            // Nothing to place on the UV square: no triangle is read.
            return Some(Sets {
                uvs,
                indices: None,
                mode,
            });
        };
        if uvs.iter().any(|set| set.len() != vertices) {
            return None;
        }
        let indices = match primitive.get("indices") {
            None => None,
            Some(node) => {
                let values = self.read(node, budget)?;
                let fits = |v: f64| (v >= 0.0 && v < vertices as f64).then_some(v as usize);
                Some(values.into_iter().map(fits).collect::<Option<Vec<_>>>()?)
            }
        };
        Some(Sets { uvs, indices, mode })
    }

    /// Every component of a plain (not sparse) accessor, normalised as a shader reads it.
    fn read(&self, reference: Node<'t>, budget: &mut usize) -> Option<Vec<f64>> {
        let accessor = self.data.accessor(reference)?;
        if accessor.get("sparse").is_some() {
            return None;
        }
        let component_type = unsigned(accessor, "componentType")?;
        let size = component_size(component_type)?;
        let components = component_count(accessor.get("type")?.as_str()?)?;
        let count = usize::try_from(unsigned(accessor, "count")?).ok()?;
        *budget = budget.checked_sub(count.checked_mul(components)?)?;
        let (bytes, stride) = self.data.bytes(accessor)?;
        let layout = Layout {
            component_type,
            size,
            components,
            // 0: packed, as glTF 1.0 writes it.
            stride: stride.filter(|&s| s > 0).unwrap_or(size * components),
            offset: usize::try_from(unsigned(accessor, "byteOffset").unwrap_or(0)).ok()?,
            count,
        };
        let mut values = vec![0.0; count * components];
        if !decode(&layout, bytes, 0, &mut values) {
            return None;
        }
        let normalized = accessor.get("normalized").and_then(Node::as_bool) == Some(true);
        if let Some(scale) = normalise(component_type).filter(|_| normalized) {
            values.iter_mut().for_each(|v| *v = scale(*v));
        }
        Some(values)
    }
}
