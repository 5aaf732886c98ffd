//! Materials of whole assets, paired and compared or rendered: what `compare`, `render` and
//! `upgrade --verify` share, so that no caller builds a shader or a sheen table by hand.

use super::brdf::SheenVisibility;
pub(crate) use super::compare::TexelMap;
use super::compare::{self as evaluate, Area, Comparison};
use super::legacy::{legacy_materials, LegacyMaterialsError};
use super::load::gltf2_materials;
use super::material::{Shader, SpecGlossReading};
use super::render::{contact_sheet, material_ball, Balls, SheetLayout, MAX_PIXELS, MAX_SIZE};
pub(crate) use super::sample::AS_STORED;
use super::sample::{MaterialSource, LIGHTING_UNREAD};
use super::sheen_table::SheenTable;
use super::surface::{Meshes, Surface};
use crate::document::file::FileId;
use crate::document::uri::{FolderResources, ResourceLoader};
use crate::error::Error;
use crate::legacy::source::NotGltf1;
use image::RgbImage;
use std::borrow::Cow;
use std::collections::HashMap;
use std::path::Path;

/// A material's name with what the evaluator samples (`None`: a 1.0 material that is not a
/// PBR-draft material, so it has no model to evaluate).
pub(crate) type Named = (String, Option<MaterialSource>);

/// An asset's materials: a 1.0 asset's PBR-draft materials, otherwise a 2.0 asset's; their
/// textures no finer than `finest` texels a side ([`AS_STORED`]: as the files store them);
/// and with `surfaces` the points on a glTF 2.0 asset's meshes where each
/// material's texCoord sets differ: the comparison reads each slot through its own set there.
/// A glTF 1.0 asset has none (the PBR drafts bind one set).
pub(crate) fn load_materials(
    bytes: Vec<u8>,
    name: &str,
    loader: &dyn ResourceLoader,
    finest: u32,
    surfaces: bool,
) -> Result<(Vec<Named>, Vec<Surface>), String> {
    match legacy_materials(&bytes, loader, finest, surfaces) {
        Ok(materials) => Ok(materials),
        // A GLB v1 is read as 1.0 or not at all; other bytes the 2.0 reader reads again, to
        // say why as a `.gltf` or `.glb` of that name.
        Err(LegacyMaterialsError::NotGltf1(NotGltf1::BrokenGlb(why))) => {
            Err(format!("not a readable glTF document: {why}"))
        }
        Err(LegacyMaterialsError::NotGltf1(_)) => {
            let (materials, points) = gltf2_materials(bytes, name, loader, finest, surfaces)?;
            let named = materials.into_iter().map(|(n, m)| (n, Some(m))).collect();
            Ok((named, points))
        }
        Err(e) => Err(e.to_string()),
    }
}

/// A shader whose sheen table covers the materials (the standard table only when one has
/// sheen).
pub(crate) fn shader_for<'m>(materials: impl IntoIterator<Item = &'m MaterialSource>) -> Shader {
    let sheen = materials.into_iter().any(|m| match m {
        MaterialSource::Gltf2(prepared) => prepared.has_sheen,
        MaterialSource::Legacy { .. } => false,
    });
    Shader::new(if sheen {
        SheenTable::standard()
    } else {
        SheenTable::compute(2, SheenVisibility::Charlie)
    })
}

/// Why a material has no model: the evaluator shades glTF 2.0 materials and the 1.0 PBR
/// drafts, not a 1.0 technique's shaders or KHR_materials_common's lighting models.
pub const NO_MODEL: &str = "a glTF 1.0 material drawn by its technique's shaders or by KHR_materials_common's Blinn, Phong, Lambert or constant lighting, which the evaluator does not shade";

/// One compared pair of materials.
#[derive(Debug, Clone)]
pub struct Outcome {
    /// Index and name of the material in the first asset.
    pub a: (usize, String),
    /// Index and name of the material in the second asset.
    pub b: (usize, String),
    /// The ΔE2000 figures, the source read as its options say.
    pub result: Comparison,
    /// For a source whose text can be read several ways (a 1.0 spec-gloss draft material):
    /// how far its other readings are from the one compared, a fact of the source and not
    /// of the comparison.
    pub ambiguity: Option<Ambiguity>,
    /// What the evaluator could not show of either material ("first: …", "second: …"):
    /// when any, the figures cover the rest only and the pair is never the same.
    pub not_evaluated: Vec<String>,
}

impl Outcome {
    /// Whether all that is not evaluated of the pair is the lighting of a glTF 1.0 material
    /// (see `LIGHTING_UNREAD`): its figures are of emission and coverage.
    pub fn only_lighting_unread(&self) -> bool {
        let lighting = |n: &String| {
            ["first", "second"]
                .iter()
                .any(|side| *n == format!("{side}: {LIGHTING_UNREAD}"))
        };
        !self.not_evaluated.is_empty() && self.not_evaluated.iter().all(lighting)
    }

    /// Whether the pair renders the same: everything evaluated, and within `threshold`.
    pub fn same(&self, threshold: f64) -> bool {
        self.not_evaluated.is_empty() && self.result.max <= threshold
    }

    /// Whether anything of the pair was evaluated: false for a material without a model,
    /// whose outcome has no figures at all.
    pub fn is_evaluated(&self) -> bool {
        self.result.samples > 0
    }

    /// The outcome as `compare --format json` writes it (`pass`: [`same`](Self::same) at
    /// `threshold`).
    pub fn to_json(&self, threshold: f64) -> serde_json::Value {
        let (result, worst) = (&self.result, &self.result.worst);
        serde_json::json!({"a": self.a.0, "aName": self.a.1, "b": self.b.0, "bName": self.b.1,
            "max": result.max, "p99": result.p99, "mean": result.mean,
            "worst": {"uv": worst.uv, "texcoords": worst.sets, "view": worst.directions.view,
                      "light": worst.directions.light, "background": worst.background,
                      "behind": worst.behind},
            "dominant": result.dominant, "evaluated": self.is_evaluated(),
            "notEvaluated": self.not_evaluated,
            "grid": result.grid, "samples": result.samples, "blendedCorners": result.blended_corners,
            "area": match result.area {
                Area::Mesh { texels } => serde_json::json!({"on": "mesh", "texels": texels}),
                Area::Whole(why) => serde_json::json!({"on": "whole UV square", "why": why}),
            },
            "offMesh": result.off_mesh,
            "ambiguity": self.ambiguity.as_ref().map(|a| serde_json::json!({"readAs": a.read_as, "furthest": a.furthest, "max": a.max, "grid": a.grid})),
            "pass": self.same(threshold)})
    }
}

/// How far a source's other readings are from the one it is compared under.
#[derive(Debug, Clone)]
pub struct Ambiguity {
    /// The reading compared under.
    pub read_as: &'static str,
    /// The other reading furthest from it.
    pub furthest: &'static str,
    /// Their largest ΔE2000 from it.
    pub max: f64,
    /// The UV grid it was found on (at most [`AMBIGUITY_GRID`]).
    pub grid: u32,
}

/// The finest grid the spread between a source's readings is sampled on.
pub(crate) const AMBIGUITY_GRID: u32 = 512;

/// Surface points evaluated in one run: they are evaluated per pair (two alike materials may lie
/// on different meshes); past it a pair that needs them is not evaluated.
const SURFACE_POINTS: usize = 1 << 16;

/// Compares each pair `(i, j)` of `a[i]` with `b[j]`; pairs with a missing side are skipped.
/// A material of `a` whose text can be read several ways (a 1.0 spec-gloss draft material)
/// is compared as it is read, and its other readings' distance from that reading is given
/// beside, as [`Outcome::ambiguity`]. Where a material reads a texCoord set other than 0,
/// `surfaces[j]` (the points on the mesh whose sets differ) are evaluated too, and when they
/// cannot be, the pair is not evaluated.
pub(crate) fn compare_pairs(
    a: &[Named],
    b: &[Named],
    pairs: &[(usize, usize)],
    surfaces: &[Surface],
    grid: u32,
    map: TexelMap,
) -> Vec<Outcome> {
    let shader = shader_for(a.iter().chain(b).filter_map(|(_, m)| m.as_ref()));
    let evaluated: Vec<Evaluated> = (pairs.iter())
        .filter_map(|&(i, j)| Some(Evaluated::of((i, a.get(i)?), (j, b.get(j)?))))
        .collect();
    // Materials that evaluate the same way are compared once (an asset's thousand copies of
    // one material are one comparison), over the meshes that draw any of them.
    let meshes_of = |j: usize| surfaces.get(j).map_or(&UNREAD_MESHES, |s| &s.meshes);
    let mut drawn: HashMap<&(String, String), Vec<&Meshes>> = HashMap::new();
    for e in &evaluated {
        if let Some((_, key)) = &e.models {
            drawn.entry(key).or_default().push(meshes_of(e.b.0));
        }
    }
    let mut done: HashMap<&(String, String), PairResult> = HashMap::new();
    let mut points_left = SURFACE_POINTS;
    (evaluated.iter())
        .map(|e| {
            let Some(((ma, mb), key)) = &e.models else {
                return e.without_model();
            };
            let mut compared = (done.entry(key))
                .or_insert_with(|| {
                    let meshes = Meshes::union(drawn[key].iter().copied());
                    compare_as_read(&shader, ma, mb, (grid, &meshes), map)
                })
                .clone();
            // Only a material that reads a set other than 0 can differ where the sets do.
            let surface = surfaces
                .get(e.b.0)
                .filter(|_| ma.reads_other_sets() || mb.reads_other_sets());
            let mut unseen = surface.and_then(|s| s.unread.clone());
            if let Some(points) = surface.map(|s| &s.points).filter(|_| unseen.is_none()) {
                match points_left.checked_sub(points.len()) {
                    Some(left) => {
                        points_left = left;
                        evaluate::on_surface(&shader, ma, mb, points, &mut compared.result);
                    }
                    None => {
                        unseen = Some(format!(
                            "the run's {SURFACE_POINTS} surface points were used up"
                        ))
                    }
                }
            }
            let not_evaluated = (ma.unmodelled().iter().map(|u| format!("first: {u}")))
                .chain(mb.unmodelled().iter().map(|u| format!("second: {u}")))
                .chain(unseen.map(|why| format!("texCoord sets on the mesh: {why}")))
                .collect();
            Outcome {
                a: e.a.clone(),
                b: e.b.clone(),
                result: compared.result,
                ambiguity: compared.ambiguity,
                not_evaluated,
            }
        })
        .collect()
}

/// Where the second asset's meshes were not read.
static UNREAD_MESHES: Meshes = Meshes::Unknown("the asset's meshes were not read");

/// A pair as it is evaluated: each side's index and name, and, when both have a model, the
/// two materials as compared and what makes them evaluate alike.
struct Evaluated<'m> {
    a: (usize, String),
    b: (usize, String),
    models: Option<(Models<'m>, (String, String))>,
    /// The sides without a model ("first", "second").
    no_model: Vec<&'static str>,
}

type Models<'m> = (Cow<'m, MaterialSource>, Cow<'m, MaterialSource>);

impl<'m> Evaluated<'m> {
    fn of((i, (name_a, ma)): (usize, &'m Named), (j, (name_b, mb)): (usize, &'m Named)) -> Self {
        let models = match (ma, mb) {
            // A 1.0 material whose lighting is not read is compared by its emission and
            // coverage, and the other material is seen the same way.
            (Some(ma), Some(mb)) if ma.lighting_unread() || mb.lighting_unread() => Some((
                Cow::Owned(ma.emission_and_coverage()),
                Cow::Owned(mb.emission_and_coverage()),
            )),
            (Some(ma), Some(mb)) => Some((Cow::Borrowed(ma), Cow::Borrowed(mb))),
            _ => None,
        };
        let sides = [("first", ma.is_none()), ("second", mb.is_none())];
        Evaluated {
            a: (i, name_a.clone()),
            b: (j, name_b.clone()),
            models: models.map(|(ma, mb)| {
                let key = (ma.fingerprint(), mb.fingerprint());
                ((ma, mb), key)
            }),
            no_model: (sides.iter().filter(|(_, none)| *none))
                .map(|(side, _)| *side)
                .collect(),
        }
    }

    /// Said, never skipped: a pair without a model on a side is not evaluated.
    fn without_model(&self) -> Outcome {
        Outcome {
            a: self.a.clone(),
            b: self.b.clone(),
            result: Comparison::nothing(),
            ambiguity: None,
            not_evaluated: (self.no_model.iter())
                .map(|side| format!("{side}: {NO_MODEL}"))
                .collect(),
        }
    }
}

/// One pair's comparison and its source's ambiguity.
#[derive(Clone)]
struct PairResult {
    result: Comparison,
    ambiguity: Option<Ambiguity>,
}

/// `source`, as it is read, compared with `target`; and its other readings compared with
/// it as it is read.
fn compare_as_read(
    shader: &Shader,
    source: &MaterialSource,
    target: &MaterialSource,
    (grid, meshes): (u32, &Meshes),
    map: TexelMap,
) -> PairResult {
    let one = std::slice::from_ref(source);
    let front = evaluate::compare_readings(shader, one, target, grid, map, meshes)
        .pop()
        .unwrap_or_else(Comparison::nothing);
    let result = match seen_from_behind(shader, source, target, (grid, meshes), map) {
        Some(back) => front_or_back(front, back),
        None => front,
    };

    let others = source.other_readings();
    // The readings' spread is a statement about the source beside the figure, not part of
    // the verdict: it is sampled no finer than AMBIGUITY_GRID, which bounds its cost to a
    // fraction of the comparison's on large textures.
    let spread_grid = evaluate::chosen_grid(&others, source, grid).min(AMBIGUITY_GRID);
    let spreads = evaluate::compare_readings(
        shader,
        &others,
        source,
        spread_grid,
        TexelMap::Dropped,
        meshes,
    );
    let ambiguity = (others.iter().zip(spreads))
        .filter_map(|(other, spread)| Some((other.reading_name()?, spread.max)))
        .max_by(|a, b| a.1.total_cmp(&b.1))
        .and_then(|(furthest, max)| {
            Some(Ambiguity {
                read_as: source.reading_name()?,
                furthest,
                max,
                grid: spread_grid,
            })
        });
    PairResult { result, ambiguity }
}

/// Where one material of a pair draws its back face and the other culls it (both say which):
/// what a viewer sees from behind, the two-sided one shaded as from the front (glTF flips a
/// back face's normal) against the background the culled one leaves.
fn seen_from_behind(
    shader: &Shader,
    source: &MaterialSource,
    target: &MaterialSource,
    (grid, meshes): (u32, &Meshes),
    map: TexelMap,
) -> Option<Comparison> {
    let (Some(first), Some(second)) = (source.double_sided(), target.double_sided()) else {
        return None;
    };
    if first == second {
        return None;
    }
    let culled = MaterialSource::invisible();
    let (source, target) = match first {
        true => (source, &culled),
        false => (&culled, target),
    };
    evaluate::compare_readings(
        shader,
        std::slice::from_ref(source),
        target,
        grid,
        map,
        meshes,
    )
    .pop()
}

/// A pair seen from the front and from behind: the figures of the view that differs most,
/// with the samples of both.
fn front_or_back(front: Comparison, back: Comparison) -> Comparison {
    let samples = front.samples + back.samples;
    let mut seen = match back.max > front.max {
        true => Comparison {
            worst: evaluate::Worst {
                behind: true,
                ..back.worst
            },
            dominant: Some("doubleSided"),
            ..back
        },
        false => front,
    };
    seen.samples = samples;
    seen
}

/// Which materials [`compare`] pairs, and how finely it samples them.
#[derive(Debug, Clone)]
#[non_exhaustive]
pub struct CompareOptions {
    /// Pairs `(i, j)`: material `i` of the first asset with material `j` of the second.
    /// Empty: every index both assets have, with itself.
    pub pairs: Vec<(usize, usize)>,
    /// UV grid per side; 0 picks the finest texture resolution involved (at least 16).
    pub grid: u32,
    /// Whether each outcome keeps its per-texel map (for heat maps).
    pub heat_maps: bool,
    /// How the first asset's 1.0 spec-gloss draft materials are read (see
    /// [`SpecGlossReading`]).
    pub draft_reading: SpecGlossReading,
}

impl Default for CompareOptions {
    fn default() -> Self {
        CompareOptions {
            pairs: Vec::new(),
            grid: 0,
            heat_maps: false,
            draft_reading: SpecGlossReading::DraftAppendix,
        }
    }
}

/// Compares the materials of two assets (glTF 2.0, or glTF 1.0 with PBR-draft materials),
/// each read with its own folder's resources.
///
/// ```
/// # fn main() -> Result<(), Box<dyn std::error::Error>> {
/// let same = "fixtures/valid/sheen-triangle.gltf";
/// let comparison = gltfmat::compare(same, same, &gltfmat::CompareOptions::default())?;
/// assert!(comparison.outcomes.iter().all(|o| o.result.max == 0.0));
/// # Ok(()) }
/// ```
pub fn compare(
    a: impl AsRef<Path>,
    b: impl AsRef<Path>,
    options: &CompareOptions,
) -> Result<Compared, Error> {
    let ((a, _), mut inputs) = materials_of(a.as_ref(), AS_STORED, false)?;
    let a: Vec<Named> = (a.into_iter())
        .map(|(name, m)| (name, m.map(|m| m.read_as(options.draft_reading))))
        .collect();
    // Where the texCoord sets differ, the points are on the second asset's meshes.
    let ((b, surfaces), inputs_of_b) = materials_of(b.as_ref(), AS_STORED, true)?;
    inputs.extend(inputs_of_b);
    let pairs = if options.pairs.is_empty() {
        (0..a.len().min(b.len())).map(|i| (i, i)).collect()
    } else {
        options.pairs.clone()
    };
    let map = if options.heat_maps {
        TexelMap::Kept
    } else {
        TexelMap::Dropped
    };
    Ok(Compared {
        outcomes: compare_pairs(&a, &b, &pairs, &surfaces, options.grid, map),
        inputs,
    })
}

/// What [`compare`] found.
#[derive(Debug, Clone)]
#[non_exhaustive]
pub struct Compared {
    /// One outcome per material pair.
    pub outcomes: Vec<Outcome>,
    /// Every file both assets were read from, by identity: what an output must not replace.
    pub inputs: Vec<FileId>,
}

/// The materials of an asset on disk, its resources read from its folder (textures no finer
/// than `finest`, as in [`load_materials`]), and every file read for them, by identity.
type Loaded = (Vec<Named>, Vec<Surface>);

fn materials_of(path: &Path, finest: u32, surfaces: bool) -> Result<(Loaded, Vec<FileId>), Error> {
    let bytes = crate::document::file::read_file(path).map_err(|source| Error::Io {
        path: path.to_path_buf(),
        source,
    })?;
    let loader = FolderResources::beside(path);
    let name = path.display().to_string();
    let materials = load_materials(bytes, &name, &loader, finest, surfaces).map_err(|reason| {
        Error::Unusable {
            path: path.to_path_buf(),
            reason,
        }
    })?;
    let inputs = FileId::of_path(path).into_iter().chain(loader.files_read());
    Ok((materials, inputs.collect()))
}

/// The finest texture detail a preview of `size` pixels a ball shows: the ball shows half
/// its texture's width across `size` pixels, so 4 · size texels a side is twice what a pixel
/// shows. Textures up to 2048² (most real ones) are sampled as stored whatever the size;
/// an 8192² one is reduced rather than held whole (201 MB) for a 64-pixel picture.
fn finest_for_preview(size: u32) -> u32 {
    size.saturating_mul(4).max(2048)
}

/// What [`render`] draws.
#[derive(Debug, Clone)]
#[non_exhaustive]
pub struct RenderOptions {
    /// A material index or name; `None`: the first.
    pub material: Option<String>,
    /// Every material on one contact sheet (four to a row, or a near-square grid past 16).
    pub all: bool,
    /// Pixels per side (per material with `all`), clamped to 8–[`MAX_SIZE`].
    pub size: u32,
}

impl Default for RenderOptions {
    fn default() -> Self {
        RenderOptions {
            material: None,
            all: false,
            size: 512,
        }
    }
}

/// A rendered picture.
#[derive(Debug, Clone)]
#[non_exhaustive]
pub struct Picture {
    /// The ball, or the contact sheet.
    pub image: RgbImage,
    /// The `(index, name)` of each material drawn, in cell order.
    pub drawn: Vec<(usize, String)>,
    /// What is not drawn of each material drawn, in the same order (inputs
    /// the evaluator does not model): empty when the picture shows all of it.
    pub not_drawn: Vec<Vec<String>>,
    /// The `(index, name)` of each material wanted but not drawn at all, having no model
    /// ([`NO_MODEL`]).
    pub skipped: Vec<(usize, String)>,
    /// Where the cells are (one cell for a single ball); its cell may be smaller than the
    /// size asked for, when the sheet would pass [`MAX_PIXELS`].
    pub layout: SheetLayout,
    /// Every file the asset was read from, by identity: what an output must not replace.
    pub inputs: Vec<FileId>,
}

/// One material's ball, drawn by [`render_each`].
#[derive(Debug, Clone)]
#[non_exhaustive]
pub struct Ball {
    /// The material's index and name.
    pub material: (usize, String),
    /// The ball; `None` when the material cannot be read for the evaluator (then `not_drawn`
    /// says why).
    pub image: Option<RgbImage>,
    /// What is not drawn of it (inputs the evaluator does not model).
    pub not_drawn: Vec<String>,
}

/// The first `at_most` materials of an asset, each drawn as its own ball of `size` pixels
/// (clamped to 8–[`MAX_SIZE`]), the asset read once and alike materials drawn once: for pages
/// that show each material beside what is said of it.
pub fn render_each(path: impl AsRef<Path>, size: u32, at_most: usize) -> Result<Vec<Ball>, Error> {
    let size = size.clamp(8, MAX_SIZE);
    let ((materials, _), _) = materials_of(path.as_ref(), finest_for_preview(size), false)?;
    let materials = &materials[..materials.len().min(at_most)];
    let shader = shader_for(materials.iter().filter_map(|(_, m)| m.as_ref()));
    let mut balls = Balls::new(&shader, size);
    let mut ball = |m: &MaterialSource| balls.of(m).clone();
    Ok((materials.iter().enumerate())
        .map(|(index, (name, material))| {
            let drawable = drawable(material);
            Ball {
                material: (index, name.clone()),
                image: drawable.map(&mut ball),
                not_drawn: match drawable {
                    Some(m) => m.unmodelled().to_vec(),
                    None => vec![NO_MODEL.into()],
                },
            }
        })
        .collect())
}

/// The material, if a ball can show it: not one without a model, nor a 1.0 material whose
/// emission and coverage alone are read (a ball of those would show a lighting it has not).
fn drawable(material: &Option<MaterialSource>) -> Option<&MaterialSource> {
    material.as_ref().filter(|m| !m.lighting_unread())
}

/// Renders a material ball (or a contact sheet of every material) of an asset.
pub fn render(path: impl AsRef<Path>, options: &RenderOptions) -> Result<Picture, Error> {
    let path = path.as_ref();
    let size = options.size.clamp(8, MAX_SIZE);
    let ((materials, _), inputs) = materials_of(path, finest_for_preview(size), false)?;
    let wanted = (materials.iter().enumerate()).filter(|(i, (name, _))| {
        match (&options.material, options.all) {
            (_, true) | (None, false) => true,
            (Some(wanted), false) => wanted == name || wanted.parse() == Ok(*i),
        }
    });
    // Without --all, the first material wanted that has a model (or the one named).
    let (mut chosen, mut skipped) = (Vec::new(), Vec::new());
    for (i, (name, m)) in wanted {
        if !options.all && !chosen.is_empty() {
            break;
        }
        match drawable(m) {
            Some(m) => chosen.push((i, name, m)),
            None => skipped.push((i, name.clone())),
        }
    }
    let unusable = |reason: String| Error::Unusable {
        path: path.to_path_buf(),
        reason,
    };
    let Some(first) = chosen.first() else {
        return Err(unusable(match skipped.first() {
            Some((i, name)) => format!("material {i} ({name}) cannot be drawn: {NO_MODEL}"),
            None if materials.is_empty() => {
                "the asset has no materials to render (its primitives draw glTF's default material)"
                    .into()
            }
            None => "no such material to render".into(),
        }));
    };
    let shader = shader_for(chosen.iter().map(|(_, _, m)| *m));
    let layout = SheetLayout::new(chosen.len(), size).ok_or_else(|| {
        unusable(format!(
            "{} materials do not fit one sheet of {MAX_PIXELS} pixels even at 8 pixels each: render them one at a time (--material)",
            chosen.len()
        ))
    })?;
    let image = if options.all {
        let named: Vec<(&str, &MaterialSource)> = chosen
            .iter()
            .map(|(_, name, m)| (name.as_str(), *m))
            .collect();
        contact_sheet(&shader, &named, layout)
    } else {
        material_ball(&shader, first.2, size)
    };
    let drawn = chosen.iter().map(|(i, n, _)| (*i, (*n).clone())).collect();
    let not_drawn = chosen
        .iter()
        .map(|(_, _, m)| m.unmodelled().to_vec())
        .collect();
    Ok(Picture {
        image,
        drawn,
        not_drawn,
        skipped,
        layout,
        inputs,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shade::sample::{decode_all, solid_png};
    use serde_json::json;

    #[test]
    fn identical_pairs_are_compared_once_and_different_ones_are_not_merged() {
        // Two images, and two materials with the same JSON reading texture 0 of different
        // texture lists: same JSON, different textures, different materials.
        let textures =
            decode_all(&[Some(Ok(solid_png([40; 3]))), Some(Ok(solid_png([220; 3])))]).unwrap();
        let json = json!({"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}, "metallicFactor": 0.0}});
        let dark = MaterialSource::gltf2(&json, &textures[0..1]);
        let light = MaterialSource::gltf2(&json, &textures[1..2]);
        assert_ne!(dark.fingerprint(), light.fingerprint());
        assert_eq!(
            dark.fingerprint(),
            MaterialSource::gltf2(&json, &textures[0..1]).fingerprint()
        );
        let named = |m: &MaterialSource| ("m".to_string(), Some(m.clone()));
        let a = [named(&dark), named(&dark), named(&light)];
        let b = [named(&light), named(&light), named(&light)];
        let outcomes = compare_pairs(&a, &b, &[(0, 0), (1, 1), (2, 2)], &[], 4, TexelMap::Kept);
        assert_eq!(outcomes[0].result.max, outcomes[1].result.max);
        assert!(outcomes[0].result.max > 10.0, "dark against light");
        assert_eq!(outcomes[2].result.max, 0.0, "light against itself");
        // Without the maps, the same figures and no map held.
        let lean = compare_pairs(&a, &b, &[(0, 0), (2, 2)], &[], 4, TexelMap::Dropped);
        assert_eq!(lean[0].result.max, outcomes[0].result.max);
        assert_eq!(lean[1].result.mean, outcomes[2].result.mean);
        assert_eq!(outcomes[0].result.per_texel.len(), 16);
        assert!(lean.iter().all(|o| o.result.per_texel.is_empty()));
    }

    /// An asset's 10^3 materials each naming its own texture of one image are one material
    /// to the evaluator: prepared once, and so proved once.
    #[test]
    fn materials_naming_different_textures_of_one_image_are_the_same_material() {
        let textures =
            decode_all(&[Some(Ok(solid_png([40; 3]))), Some(Ok(solid_png([220; 3])))]).unwrap();
        // Textures 0 and 1 read image 0; texture 2 reads image 1.
        let textures = [&textures[0], &textures[0], &textures[1]].map(Clone::clone);
        let reading = |index: usize| json!({"pbrMetallicRoughness": {"baseColorTexture": {"index": index}}, "name": index});
        let materials = crate::document::Tree::of(&(0..3).map(reading).collect());
        let materials = materials
            .root()
            .as_array()
            .into_iter()
            .flat_map(|a| a.iter());
        let prepared = crate::shade::load::prepare_materials(materials, &textures, &[], &[]);
        let [first, second, other] = &prepared[..] else {
            panic!("three materials")
        };
        assert_eq!(first.fingerprint(), second.fingerprint());
        assert_ne!(first.fingerprint(), other.fingerprint());
    }

    /// A back face drawn against one culled shows the material against the background: a
    /// difference from behind, which the front cannot show. Both drawn, or both culled, the
    /// back adds nothing; nor does a material that hides nothing.
    #[test]
    fn a_pair_of_which_one_culls_its_back_face_differs_from_behind() {
        let of = |material: serde_json::Value| {
            ("m".to_string(), Some(MaterialSource::gltf2(&material, &[])))
        };
        let red = json!({"pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.1, 0.1, 1.0]}});
        let mut two_sided = red.clone();
        two_sided["doubleSided"] = json!(true);
        let clear = json!({"alphaMode": "BLEND", "pbrMetallicRoughness": {"baseColorFactor": [1.0, 1.0, 1.0, 0.0]}});
        let mut clear_two_sided = clear.clone();
        clear_two_sided["doubleSided"] = json!(true);
        let a = [&red, &two_sided, &two_sided, &clear].map(|m| of(m.clone()));
        let b = [&two_sided, &red, &two_sided, &clear_two_sided].map(|m| of(m.clone()));
        let pairs = [(0, 0), (1, 1), (2, 2), (3, 3)];
        let outcomes = compare_pairs(&a, &b, &pairs, &[], 4, TexelMap::Dropped);
        for (culled_first, outcome) in [true, false].into_iter().zip(&outcomes) {
            assert!(!outcome.same(1.0), "culled first: {culled_first}");
            assert!(outcome.result.worst.behind);
            assert_eq!(outcome.result.dominant, Some("doubleSided"));
        }
        assert!(
            outcomes[2].same(1.0) && !outcomes[2].result.worst.behind,
            "both drawn"
        );
        assert!(
            outcomes[3].same(1.0),
            "a material that hides nothing looks the same culled"
        );
        assert!(
            outcomes[0].result.samples > outcomes[2].result.samples,
            "front and back sampled"
        );
    }
}
