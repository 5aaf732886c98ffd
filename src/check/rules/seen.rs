//! Which texels of a texture a material's meshes sample, so that the pixel rules judge what a
//! viewer can show and not the gutters between UV islands that nothing reads.

use crate::check::context::{Context, SlotUse};
use crate::check::khronos::accessor_data::{scannable, unit_scale};
use crate::document::tree::Node;
use crate::gltf::accessor::decode;
use crate::gltf::material::{effective_texcoord, uv_transform};
use crate::gltf::mesh::{drawn_materials, triangles};
use crate::gltf::{as_index, unsigned};

/// The texels a binding's meshes may read, bilinear neighbours included.
pub(crate) struct Seen {
    width: usize,
    mask: Vec<bool>,
}

impl Seen {
    pub(crate) fn contains(&self, x: u32, y: u32) -> bool {
        self.mask
            .get(y as usize * self.width + x as usize)
            .copied()
            .unwrap_or(false)
    }
}

/// Vertex components (UVs and indices) read in one run at most, 32 MB as f64; past it every
/// texel counts as seen. With a mesh read once per binding, this bounds the masks' time and
/// memory.
const MAX_ELEMENTS: usize = 1 << 22;
/// Texel writes per texel of the image at most (triangles that tile the texture many times
/// cost a row each); past it every texel counts as seen.
const MAX_WRITES_PER_TEXEL: usize = 16;

const CLAMP_TO_EDGE: u64 = 33071;
const MIRRORED_REPEAT: u64 = 33648;

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
        let mut painter = Painter {
            seen: Seen {
                width: grid.width,
                mask: vec![false; grid.width * grid.height],
            },
            writes_left: (grid.width * grid.height).saturating_mul(MAX_WRITES_PER_TEXEL),
        };
        for &primitive in self.drawing.get(slot_use.material_index)? {
            let mesh = Mesh::read(ctx, primitive, set, &mut self.elements_left)?;
            for [a, b, c] in mesh.triangles() {
                let corner = |i: usize| grid.texel_space(mesh.uv(i));
                painter.triangle(&grid, [corner(a), corner(b), corner(c)])?;
            }
        }
        Some(painter.seen)
    }
}

fn wraps(ctx: &Context, texture: Node) -> [u64; 2] {
    let sampler = unsigned(texture, "sampler").and_then(|i| ctx.element("samplers", i));
    ["wrapS", "wrapT"].map(|key| sampler.and_then(|s| unsigned(s, key)).unwrap_or(10497))
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

/// Where UVs land on the image.
struct Grid {
    width: usize,
    height: usize,
    transform: [f64; 6],
    wrap: [u64; 2],
}

impl Grid {
    /// A UV in texel units, texel centres at integers.
    fn texel_space(&self, [u, v]: [f64; 2]) -> [f64; 2] {
        let t = self.transform;
        let (u, v) = (t[0] * u + t[1] * v + t[2], t[3] * u + t[4] * v + t[5]);
        [u * self.width as f64 - 0.5, v * self.height as f64 - 0.5]
    }

    /// The column indices from `first` to `last` worth visiting: no more than one period of
    /// the wrap (every column is read once a span covers it), clamped to the edges for
    /// CLAMP_TO_EDGE.
    fn columns(&self, left: f64, right: f64) -> (i64, i64) {
        let width = self.width as f64;
        match self.wrap[0] {
            CLAMP_TO_EDGE => {
                let clamp = |x: f64| x.clamp(0.0, width - 1.0) as i64;
                (clamp(left.floor()), clamp(right.ceil()))
            }
            _ => {
                // Moved into the first period, so that far-off UVs stay small integers.
                let period = 2.0 * width;
                if right - left >= period {
                    return (0, 2 * self.width as i64 - 1);
                }
                let shift = (left / period).floor() * period;
                ((left - shift).floor() as i64, (right - shift).ceil() as i64)
            }
        }
    }

    /// The texel a coordinate index reads under a wrap mode.
    fn wrapped(index: i64, size: usize, wrap: u64) -> usize {
        let size = size as i64;
        let i = match wrap {
            CLAMP_TO_EDGE => index.clamp(0, size - 1),
            MIRRORED_REPEAT => {
                let m = index.rem_euclid(2 * size);
                if m >= size {
                    2 * size - 1 - m
                } else {
                    m
                }
            }
            _ => index.rem_euclid(size),
        };
        i as usize
    }
}

struct Painter {
    seen: Seen,
    writes_left: usize,
}

impl Painter {
    /// Marks every texel a bilinear sample inside the triangle reads: for each texel row j,
    /// the triangle's extent over the rows it blends (j − 1, j + 1), widened by one texel.
    fn triangle(&mut self, grid: &Grid, corners: [[f64; 2]; 3]) -> Option<()> {
        if corners.iter().flatten().any(|c| !c.is_finite()) {
            return Some(()); // nothing a GPU draws; ACCESSOR_INVALID_FLOAT says why
        }
        let ys = corners.map(|[_, y]| y);
        let low = ys.iter().copied().fold(f64::MAX, f64::min);
        let high = ys.iter().copied().fold(f64::MIN, f64::max);
        if high - low > 4.0 * grid.height as f64 {
            return None;
        }
        let rows = (low.floor() as i64)..=(high.ceil() as i64);
        for row in rows {
            let Some((left, right)) = extent(corners, row as f64 - 1.0, row as f64 + 1.0) else {
                continue;
            };
            let y = Grid::wrapped(row, grid.height, grid.wrap[1]);
            let (first, last) = grid.columns(left, right);
            self.writes_left = self.writes_left.checked_sub((last - first + 1) as usize)?;
            for x in first..=last {
                let x = Grid::wrapped(x, grid.width, grid.wrap[0]);
                self.seen.mask[y * grid.width + x] = true;
            }
        }
        Some(())
    }
}

/// The x extent of a triangle between two horizontal lines, if it reaches between them.
fn extent(corners: [[f64; 2]; 3], y0: f64, y1: f64) -> Option<(f64, f64)> {
    let mut xs = Vec::with_capacity(9);
    for (i, &[x, y]) in corners.iter().enumerate() {
        if (y0..=y1).contains(&y) {
            xs.push(x);
        }
        let [x2, y2] = corners[(i + 1) % 3];
        for line in [y0, y1] {
            if (y - line) * (y2 - line) < 0.0 {
                xs.push(x + (x2 - x) * (line - y) / (y2 - y));
            }
        }
    }
    let left = xs.iter().copied().fold(f64::INFINITY, f64::min);
    let right = xs.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    (left <= right).then_some((left, right))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn grid(size: usize, wrap: u64) -> Grid {
        Grid {
            width: size,
            height: size,
            transform: [1.0, 0.0, 0.0, 0.0, 1.0, 0.0],
            wrap: [wrap; 2],
        }
    }

    fn painted(grid: &Grid, triangles: &[[[f64; 2]; 3]]) -> Option<Vec<bool>> {
        let mut painter = Painter {
            seen: Seen {
                width: grid.width,
                mask: vec![false; grid.width * grid.height],
            },
            writes_left: grid.width * grid.height * MAX_WRITES_PER_TEXEL,
        };
        for t in triangles {
            painter.triangle(grid, t.map(|uv| grid.texel_space(uv)))?;
        }
        Some(painter.seen.mask)
    }

    #[test]
    fn a_triangle_in_one_corner_leaves_the_far_corner_unseen() {
        // Clamped: under REPEAT the filter at u, v = 0 also blends the far corner's texel.
        let g = grid(16, CLAMP_TO_EDGE);
        let mask = painted(&g, &[[[0.0, 0.0], [0.25, 0.0], [0.0, 0.25]]]).unwrap();
        assert!(mask[0]);
        assert!(mask[3 * 16], "the rows the triangle spans are seen");
        assert!(!mask[15 * 16 + 15] && !mask[10 * 16 + 10]);
        let count = mask.iter().filter(|&&m| m).count();
        assert!(
            count < 40,
            "{count} texels seen of a 16² image for a 4×4-texel triangle"
        );
    }

    #[test]
    fn uvs_past_the_edge_wrap_as_the_sampler_says() {
        // A thin strip at u in 1.0..1.1 reads the first columns under REPEAT, the last under
        // MIRRORED_REPEAT and only the last column under CLAMP_TO_EDGE.
        let strip = [
            [[1.0, 0.0], [1.1, 0.0], [1.0, 1.0]],
            [[1.1, 0.0], [1.1, 1.0], [1.0, 1.0]],
        ];
        let column = |mask: &[bool], x: usize| (0..16).all(|y| mask[y * 16 + x]);
        let repeat = painted(&grid(16, 10497), &strip).unwrap();
        assert!(column(&repeat, 0) && !column(&repeat, 8));
        let mirror = painted(&grid(16, MIRRORED_REPEAT), &strip).unwrap();
        assert!(column(&mirror, 15) && !column(&mirror, 8));
        let clamp = painted(&grid(16, CLAMP_TO_EDGE), &strip).unwrap();
        assert!(column(&clamp, 15) && !column(&clamp, 0) && !column(&clamp, 8));
    }

    #[test]
    fn a_triangle_tiling_the_texture_many_times_gives_up_rather_than_paint_forever() {
        let huge = [[0.0, 0.0], [1e6, 0.0], [0.0, 1e6]];
        assert!(painted(&grid(8, 10497), &[huge]).is_none());
    }

    #[test]
    fn uvs_far_from_the_texture_neither_overflow_nor_paint_forever() {
        for far in [1e12, -1e12, 1e300, f64::MAX] {
            // Far along u only: its rows are ordinary, so its columns are computed.
            let small = [[far, 0.1], [far + 1e-3, 0.1], [far, 0.2]];
            let _ = painted(&grid(8, 10497), &[small]);
            let _ = painted(&grid(8, CLAMP_TO_EDGE), &[small]);
        }
    }

    #[test]
    fn the_extent_between_two_lines_includes_edge_crossings() {
        let triangle = [[0.0, 0.0], [10.0, 0.0], [0.0, 10.0]];
        assert_eq!(extent(triangle, 4.0, 6.0), Some((0.0, 6.0)));
        assert_eq!(extent(triangle, 11.0, 12.0), None);
    }
}
