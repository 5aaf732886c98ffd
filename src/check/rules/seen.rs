//! Which texels of a texture a material's meshes sample, so that the pixel rules judge what a
//! viewer can show and not the gutters between UV islands that nothing reads.

use crate::check::context::{Context, SlotUse};
use crate::check::khronos::accessor_data::{scannable, unit_scale};
use crate::document::tree::Node;
use crate::gltf::accessor::decode;
use crate::gltf::coverage::{Grid, Painter, Seen};
use crate::gltf::gl::REPEAT;
use crate::gltf::material::{effective_texcoord, uv_transform};
use crate::gltf::mesh::{drawn_materials, triangles};
use crate::gltf::{as_index, unsigned};

/// Vertex components (UVs and indices) read in one run at most, 32 MB as f64; past it every
/// texel counts as seen. With a mesh read once per binding, this bounds the masks' time and
/// memory.
const MAX_ELEMENTS: usize = 1 << 22;
/// What a run needs to tell the texels each binding samples: the primitives drawing each
/// material, found once, and what is left of the run's element budget.
pub(super) struct Sight<'a> {
    drawing: Vec<Vec<Node<'a>>>,
    elements_left: usize,
}

impl<'a> Sight<'a> {
    pub(super) fn new(ctx: &Context<'a>) -> Sight<'a> {
        let mut drawing = vec![Vec::new(); ctx.items("materials").len()];
        let primitives = (ctx.items("meshes").iter())
            .filter_map(|mesh| mesh.get("primitives")?.as_array())
            .flat_map(|primitives| primitives.iter());
        for primitive in primitives {
            for material in drawn_materials(primitive) {
                if let Some(list) = drawing.get_mut(material as usize) {
                    list.push(primitive);
                }
            }
        }
        Sight {
            drawing,
            elements_left: MAX_ELEMENTS,
        }
    }

    /// The texels of a `width` × `height` image that the primitives drawing `slot_use`'s
    /// material (directly or through a KHR_materials_variants mapping) sample through the
    /// binding's texCoord set, texture transform and wrap modes. None when that cannot be
    /// told — a primitive's UVs are compressed, unreadable or past the limits above — and every
    /// texel then counts as seen.
    pub(super) fn seen(
        &mut self,
        ctx: &Context,
        slot_use: &SlotUse,
        width: u32,
        height: u32,
    ) -> Option<Seen> {
        if width == 0 || height == 0 {
            return None;
        }
        let info = slot_use.slot.lookup(slot_use.material)?;
        let set = effective_texcoord(info);
        let grid = Grid {
            width: width as usize,
            height: height as usize,
            transform: uv_transform(info),
            wrap: wraps(ctx, slot_use.texture),
        };
        let mut painter = Painter::new(grid);
        for &primitive in self.drawing.get(slot_use.material_index)? {
            let mesh = Mesh::read(ctx, primitive, set, &mut self.elements_left)?;
            for [a, b, c] in mesh.triangles() {
                painter.triangle([mesh.uv(a), mesh.uv(b), mesh.uv(c)])?;
            }
        }
        Some(painter.seen())
    }
}

fn wraps(ctx: &Context, texture: Node) -> [u64; 2] {
    let sampler = unsigned(texture, "sampler").and_then(|i| ctx.element("samplers", i));
    ["wrapS", "wrapT"].map(|key| sampler.and_then(|s| unsigned(s, key)).unwrap_or(REPEAT))
}

/// A primitive's texture coordinates and how its vertices make triangles.
struct Mesh {
    /// u, v of each vertex in turn.
    uvs: Vec<f64>,
    indices: Option<Vec<u32>>,
    mode: u64,
}

impl Mesh {
    fn read(ctx: &Context, primitive: Node, set: u64, budget: &mut usize) -> Option<Mesh> {
        let accessors = ctx.items("accessors");
        let accessor = |node: Node| accessors.get(usize::try_from(as_index(node)?).ok()?);
        let uv = accessor(
            primitive
                .get("attributes")?
                .get(format!("TEXCOORD_{set}").as_str())?,
        )?;
        let mut uvs = read_all(ctx, uv, budget)?;
        if let Some(scale) = unsigned(uv, "componentType").and_then(|t| unit_scale(t, uv)) {
            uvs.iter_mut().for_each(|v| *v = scale(*v));
        }
        let vertices = uvs.len() / 2;
        let indices = match primitive.get("indices") {
            None => None,
            Some(node) => {
                let values = read_all(ctx, accessor(node)?, budget)?;
                let fits = |v: f64| (v >= 0.0 && v < vertices as f64).then_some(v as u32);
                Some(values.into_iter().filter_map(fits).collect())
            }
        };
        let mode = crate::check::khronos::mode_of(primitive)?;
        Some(Mesh { uvs, indices, mode })
    }

    fn uv(&self, vertex: usize) -> [f64; 2] {
        [self.uvs[2 * vertex], self.uvs[2 * vertex + 1]]
    }

    fn triangles(&self) -> impl Iterator<Item = [usize; 3]> + '_ {
        let n = self.indices.as_ref().map_or(self.uvs.len() / 2, Vec::len);
        let at = move |i: usize| self.indices.as_ref().map_or(i, |list| list[i] as usize);
        triangles(self.mode, n, at)
    }
}

/// Every element of a plain accessor as f64 components, within `budget` elements.
fn read_all(ctx: &Context, accessor: Node, budget: &mut usize) -> Option<Vec<f64>> {
    let (layout, view) = scannable(ctx, accessor)?;
    *budget = budget.checked_sub(layout.count.checked_mul(layout.components)?)?;
    let bytes = view.read()?;
    let mut values = vec![0.0; layout.count * layout.components];
    decode(&layout, &bytes, 0, &mut values).then_some(values)
}
