//! Which texels of an image a mesh's triangles read: every texel a bilinear sample anywhere
//! inside a triangle blends, through a texture transform and the sampler's wrap modes. The
//! checker's pixel rules judge those texels, not the gutters between UV islands that nothing
//! reads; the evaluator's comparison samples its UV grid there and nowhere else.

use super::gl::{CLAMP_TO_EDGE, MIRRORED_REPEAT, REPEAT};

/// The texels some triangle reads, bilinear neighbours included.
#[derive(Clone, Debug, PartialEq)]
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

    /// How many texels are seen.
    pub(crate) fn count(&self) -> usize {
        self.mask.iter().filter(|&&seen| seen).count()
    }
}

/// Texel writes per texel of the image at most (triangles that tile the texture many times
/// cost a row each), beyond [`WRITES_PER_TRIANGLE`] each triangle brings; past it the painter
/// gives up, and every texel counts as seen.
const MAX_WRITES_PER_TEXEL: usize = 16;
/// Writes each triangle may make without drawing on the texels' allowance: a dense mesh on a
/// small texture (thousands of triangles a few texels wide) is painted, not given up on. The
/// triangles themselves are bounded by what their readers read.
const WRITES_PER_TRIANGLE: usize = 16;

/// Where UVs land on an image: its size in texels, the texture transform (a 2×3 matrix, row
/// by row) and the sampler's `wrapS`, `wrapT`.
pub(crate) struct Grid {
    pub width: usize,
    pub height: usize,
    pub transform: [f64; 6],
    pub wrap: [u64; 2],
}

impl Grid {
    /// A `size`² grid read as stored: no transform, REPEAT both ways.
    pub(crate) fn plain(size: usize) -> Grid {
        Grid {
            width: size,
            height: size,
            transform: [1.0, 0.0, 0.0, 0.0, 1.0, 0.0],
            wrap: [REPEAT; 2],
        }
    }

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

/// Marks the texels triangles read on one grid.
pub(crate) struct Painter {
    grid: Grid,
    seen: Seen,
    writes_left: usize,
}

impl Painter {
    pub(crate) fn new(grid: Grid) -> Painter {
        let texels = grid.width * grid.height;
        Painter {
            seen: Seen {
                width: grid.width,
                mask: vec![false; texels],
            },
            writes_left: texels.saturating_mul(MAX_WRITES_PER_TEXEL),
            grid,
        }
    }

    /// What was marked.
    pub(crate) fn seen(self) -> Seen {
        self.seen
    }

    /// Marks every texel a bilinear sample inside the triangle with these UVs reads. None
    /// when the triangles would cost more than [`MAX_WRITES_PER_TEXEL`] writes a texel, or
    /// one spans the texture more than a few times: then every texel counts as seen.
    pub(crate) fn triangle(&mut self, uvs: [[f64; 2]; 3]) -> Option<()> {
        self.writes_left = self.writes_left.saturating_add(WRITES_PER_TRIANGLE);
        let corners = uvs.map(|uv| self.grid.texel_space(uv));
        self.paint(corners)
    }

    /// For each texel row j, the triangle's extent over the rows it blends (j − 1, j + 1),
    /// widened by one texel.
    fn paint(&mut self, corners: [[f64; 2]; 3]) -> Option<()> {
        let grid = &self.grid;
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
            let row = &mut self.seen.mask[y * grid.width..][..grid.width];
            mark_columns(row, (first, last), grid.wrap[0]);
        }
        Some(())
    }
}

/// Marks columns `first..=last` of one row as a sampler wrapped as `wrap` reads them: a run at
/// a time (the painter's texels are mostly such runs), texel by texel only when mirrored.
fn mark_columns(row: &mut [bool], (first, last): (i64, i64), wrap: u64) {
    let width = row.len() as i64;
    match wrap {
        MIRRORED_REPEAT => {
            for x in first..=last {
                row[Grid::wrapped(x, row.len(), wrap)] = true;
            }
        }
        // `Grid::columns` has clamped them already.
        CLAMP_TO_EDGE => row[first as usize..=last as usize].fill(true),
        _ if last - first + 1 >= width => row.fill(true),
        _ => {
            let (start, length) = (first.rem_euclid(width) as usize, row.len());
            let end = start + (last - first) as usize;
            match end < length {
                true => row[start..=end].fill(true),
                false => {
                    row[start..].fill(true);
                    row[..=end - length].fill(true);
                }
            }
        }
    }
}

/// The x extent of a triangle between two horizontal lines, if it reaches between them.
fn extent(corners: [[f64; 2]; 3], y0: f64, y1: f64) -> Option<(f64, f64)> {
    let (mut left, mut right) = (f64::INFINITY, f64::NEG_INFINITY);
    let mut include = |x: f64| {
        left = left.min(x);
        right = right.max(x);
    };
    for (i, &[x, y]) in corners.iter().enumerate() {
        if (y0..=y1).contains(&y) {
            include(x);
        }
        let [x2, y2] = corners[(i + 1) % 3];
        for line in [y0, y1] {
            if (y - line) * (y2 - line) < 0.0 {
                include(x + (x2 - x) * (line - y) / (y2 - y));
            }
        }
    }
    (left <= right).then_some((left, right))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn grid(size: usize, wrap: u64) -> Grid {
        Grid {
            wrap: [wrap; 2],
            ..Grid::plain(size)
        }
    }

    fn painted(grid: Grid, triangles: &[[[f64; 2]; 3]]) -> Option<Vec<bool>> {
        let mut painter = Painter::new(grid);
        for t in triangles {
            painter.triangle(*t)?;
        }
        Some(painter.seen().mask)
    }

    #[test]
    fn a_triangle_in_one_corner_leaves_the_far_corner_unseen() {
        // Clamped: under REPEAT the filter at u, v = 0 also blends the far corner's texel.
        let g = grid(16, CLAMP_TO_EDGE);
        let mask = painted(g, &[[[0.0, 0.0], [0.25, 0.0], [0.0, 0.25]]]).unwrap();
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
        let repeat = painted(grid(16, 10497), &strip).unwrap();
        assert!(column(&repeat, 0) && !column(&repeat, 8));
        let mirror = painted(grid(16, MIRRORED_REPEAT), &strip).unwrap();
        assert!(column(&mirror, 15) && !column(&mirror, 8));
        let clamp = painted(grid(16, CLAMP_TO_EDGE), &strip).unwrap();
        assert!(column(&clamp, 15) && !column(&clamp, 0) && !column(&clamp, 8));
    }

    #[test]
    fn runs_of_columns_are_marked_as_each_texel_wraps() {
        for wrap in [REPEAT, CLAMP_TO_EDGE, MIRRORED_REPEAT] {
            for first in -20i64..20 {
                for length in 1..20 {
                    let (mut first, mut last) = (first, first + length - 1);
                    if wrap == CLAMP_TO_EDGE {
                        (first, last) = (first.clamp(0, 6), last.clamp(0, 6));
                    }
                    let mut runs = vec![false; 7];
                    mark_columns(&mut runs, (first, last), wrap);
                    let mut each = vec![false; 7];
                    (first..=last).for_each(|x| each[Grid::wrapped(x, 7, wrap)] = true);
                    assert_eq!(runs, each, "wrap {wrap}, columns {first}..={last}");
                }
            }
        }
    }

    #[test]
    fn a_dense_mesh_on_a_small_texture_is_painted() {
        // 20,000 triangles of a tenth of a texel each, in one texel's corner of a 4² image:
        // more writes than the texels' allowance, each triangle's own few.
        let triangles: Vec<_> = (0..20_000)
            .map(|i| {
                let u = 0.05 + f64::from(i % 100) * 1e-4;
                [[u, 0.05], [u + 0.02, 0.05], [u, 0.07]]
            })
            .collect();
        let mask = painted(grid(4, CLAMP_TO_EDGE), &triangles).expect("painted");
        assert!(mask[0] && !mask[15], "{mask:?}");
    }

    #[test]
    fn a_triangle_tiling_the_texture_many_times_gives_up_rather_than_paint_forever() {
        let huge = [[0.0, 0.0], [1e6, 0.0], [0.0, 1e6]];
        assert!(painted(grid(8, 10497), &[huge]).is_none());
    }

    #[test]
    fn uvs_far_from_the_texture_neither_overflow_nor_paint_forever() {
        for far in [1e12, -1e12, 1e300, f64::MAX] {
            // Far along u only: its rows are ordinary, so its columns are computed.
            let small = [[far, 0.1], [far + 1e-3, 0.1], [far, 0.2]];
            let _ = painted(grid(8, 10497), &[small]);
            let _ = painted(grid(8, CLAMP_TO_EDGE), &[small]);
        }
    }

    #[test]
    fn the_extent_between_two_lines_includes_edge_crossings() {
        let triangle = [[0.0, 0.0], [10.0, 0.0], [0.0, 10.0]];
        assert_eq!(extent(triangle, 4.0, 6.0), Some((0.0, 6.0)));
        assert_eq!(extent(triangle, 11.0, 12.0), None);
    }
}
