//! What a primitive draws: its materials, and the triangles its vertices make.

use super::{unsigned, Json};

/// The materials a primitive draws with: its own and each KHR_materials_variants mapping's,
/// once each, in increasing order.
pub(crate) fn drawn_materials<'a, J: Json<'a>>(primitive: J) -> Vec<u64> {
    let mappings = (primitive.get("extensions"))
        .and_then(|e| e.get("KHR_materials_variants"))
        .and_then(|v| v.get("mappings"));
    let variants = (0..)
        .map_while(move |i| mappings.and_then(|m| m.item(i)))
        .filter_map(|mapping| unsigned(mapping, "material"));
    let mut materials: Vec<u64> = unsigned(primitive, "material")
        .into_iter()
        .chain(variants)
        .collect();
    materials.sort_unstable();
    materials.dedup();
    materials
}

/// How many vertex triples [`triangles`] gives for `n` vertices.
pub(crate) fn triangle_count(mode: u64, n: usize) -> usize {
    match mode {
        0 => n,
        1 => n / 2,
        2 | 3 => n.saturating_sub(1),
        5 | 6 => n.saturating_sub(2),
        _ => n / 3,
    }
}

/// The vertex triples a primitive of `mode` draws from `n` vertices (`at(i)` the i-th index):
/// triangles as the mode assembles them; a line is a thin triangle and a point a degenerate
/// one, so that a caller looking at what a primitive covers sees them too.
pub(crate) fn triangles(
    mode: u64,
    n: usize,
    at: impl Fn(usize) -> usize,
) -> impl Iterator<Item = [usize; 3]> {
    (0..triangle_count(mode, n)).map(move |i| match mode {
        0 => [at(i); 3],
        1 => [at(2 * i), at(2 * i + 1), at(2 * i + 1)],
        2 | 3 => [at(i), at(i + 1), at(i + 1)],
        5 => [at(i), at(i + 1), at(i + 2)],
        6 => [at(0), at(i + 1), at(i + 2)],
        _ => [at(3 * i), at(3 * i + 1), at(3 * i + 2)],
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_mode_assembles_its_triangles() {
        let list = |mode, n| triangles(mode, n, |i| i).collect::<Vec<_>>();
        assert_eq!(list(4, 7), [[0, 1, 2], [3, 4, 5]]);
        assert_eq!(list(5, 4), [[0, 1, 2], [1, 2, 3]]);
        assert_eq!(list(6, 4), [[0, 1, 2], [0, 2, 3]]);
        assert_eq!(list(1, 3), [[0, 1, 1]]);
        assert_eq!(list(0, 2), [[0, 0, 0], [1, 1, 1]]);
        assert!(list(4, 2).is_empty());
    }
}
