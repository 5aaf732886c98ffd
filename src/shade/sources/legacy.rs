//! A glTF 1.0 asset's PBR-draft materials, sampled by their own model.

use super::sample::{self, LitLegacy, MaterialSource, Texture};
use super::surface::{surface_points, MeshData, Surface};
use crate::document::tree::Node;
use crate::document::uri::ResourceLoader;
use crate::gltf::color::srgb_to_linear;
use crate::legacy::blend::{self, technique_blend, Blend};
use crate::legacy::pbr;
use crate::legacy::source::{self, NotGltf1};
use crate::shade::material::SpecGlossReading;
use crate::shade::pairing::Named;
use std::collections::HashMap;

/// Why a 1.0 asset's materials cannot be sampled.
#[derive(Debug, thiserror::Error)]
pub(crate) enum LegacyMaterialsError {
    /// Not a 1.0 asset at all: the caller may read it as 2.0.
    #[error(transparent)]
    NotGltf1(#[from] NotGltf1),
    /// A texture the materials use cannot be read or decoded.
    #[error("/textures: {0}")]
    Textures(String),
}

/// The PBR-draft materials of a glTF 1.0 asset as the shading evaluator samples them (their
/// own model), in material order, with their ids; `None` for materials without a PBR block.
/// Textures no finer than `finest` (see [`sample::decode_each_at_most`]).
/// With `surfaces`, also each material's meshes (see [`surface_points`]).
pub(crate) fn legacy_materials(
    bytes: &[u8],
    loader: &dyn ResourceLoader,
    finest: u32,
    surfaces: bool,
) -> Result<(Vec<Named>, Vec<Surface>), LegacyMaterialsError> {
    let source = source::read_for_materials(bytes.into(), loader, surfaces)?;
    let parsed: Vec<Parsed> = (source.dictionary("materials").into_iter())
        .map(|(id, material)| Parsed::read(&source, id, material))
        .collect();
    let textures = DecodedTextures::of(&source, &parsed, finest)?;
    let meshes = match surfaces {
        true => surface_points(&Gltf1Meshes { source: &source }),
        false => Vec::new(),
    };
    let materials = (parsed.into_iter())
        .map(|parsed| (parsed.id.to_string(), textures.sampled(parsed)))
        .collect();
    Ok((materials, meshes))
}

/// A glTF 1.0 asset's meshes: its materials in document order, its accessors and views by id.
struct Gltf1Meshes<'s, 'a> {
    source: &'s source::Source<'a>,
}

impl<'s> MeshData<'s> for Gltf1Meshes<'s, '_> {
    fn drawing(&self) -> Vec<Vec<Node<'s>>> {
        let materials: HashMap<&str, usize> = (self.source.dictionary("materials").iter())
            .enumerate()
            .map(|(i, (id, _))| (*id, i))
            .collect();
        let mut drawn = vec![Vec::new(); materials.len()];
        let primitives = (self.source.dictionary("meshes").into_iter())
            .filter_map(|(_, mesh)| mesh.get("primitives")?.as_array())
            .flat_map(|primitives| primitives.iter());
        for primitive in primitives {
            let material = primitive.get("material").and_then(Node::as_str);
            if let Some(&i) = material.and_then(|id| materials.get(id)) {
                drawn[i].push(primitive);
            }
        }
        drawn
    }

    fn accessor(&self, reference: Node<'s>) -> Option<Node<'s>> {
        self.source.object("accessors", reference.as_str()?)
    }

    fn bytes(&self, accessor: Node<'s>) -> Option<(&[u8], Option<usize>)> {
        let view = accessor.get("bufferView")?.as_str()?;
        let stride = accessor.get("byteStride").and_then(Node::as_u64);
        Some((self.source.view(view).ok()?, stride.map(|s| s as usize)))
    }
}

/// The textures a 1.0 asset's materials use, each decoded once and on its own: a PBR
/// material whose texture cannot be had is not evaluated (its pair is named so, never the
/// same), nor is a lit one; the others are.
struct DecodedTextures<'s> {
    source: &'s source::Source<'s>,
    pbr: Vec<Result<Option<Texture>, String>>,
    pbr_position: HashMap<String, usize>,
    lit: Vec<Result<Option<Texture>, String>>,
    lit_position: HashMap<String, usize>,
}

impl<'s> DecodedTextures<'s> {
    fn of(
        source: &'s source::Source<'s>,
        parsed: &[Parsed],
        finest: u32,
    ) -> Result<Self, LegacyMaterialsError> {
        let image_of = |id: &String| {
            let image = (source.object("textures", id))
                .and_then(|texture| texture.get("source")?.as_str())
                .and_then(|image| source.object("images", image))
                .ok_or_else(|| "it names no image".to_string());
            Some(image.and_then(|image| source.image_bytes(image)))
        };
        let pbr_ids = (parsed.iter().filter_map(|p| p.pbr.as_ref()))
            .flat_map(|pbr| [&pbr.colour_texture, &pbr.data_texture]);
        let (ids, pbr_position) = distinct(pbr_ids);
        let encoded: Vec<sample::Wanted<_>> = ids.iter().map(image_of).collect();
        let pbr = sample::decode_each_at_most(&encoded, finest)
            .map_err(LegacyMaterialsError::Textures)?;
        let lit_ids = (parsed.iter().filter_map(|p| p.lit.as_ref()))
            .flat_map(|lit| [&lit.emission_texture, &lit.alpha_texture]);
        let (lit_ids, lit_position) = distinct(lit_ids);
        let encoded: Vec<sample::Wanted<_>> = lit_ids.iter().map(image_of).collect();
        // The decoding budget, passed, fails each lit material's textures alone.
        let lit = sample::decode_each_at_most(&encoded, finest)
            .unwrap_or_else(|why| vec![Err(why); lit_ids.len()]);
        Ok(DecodedTextures {
            source,
            pbr,
            pbr_position,
            lit,
            lit_position,
        })
    }

    /// The sampler texture `id` is read through: 1.0 samplers use the GL enums and
    /// defaults of 2.0's (LINEAR, REPEAT).
    fn sampler(&self, id: &Option<String>) -> sample::Sampler {
        sample::Sampler::of(id.as_deref().and_then(|id| self.source.texture_sampler(id)))
    }

    /// A PBR material's texture `id` (`Ok(None)`: none named), or why it cannot be had.
    fn pbr_texture(&self, id: &Option<String>) -> Result<Option<Texture>, String> {
        let Some(id) = id.as_deref() else {
            return Ok(None);
        };
        match self.pbr_position.get(id).map(|&at| &self.pbr[at]) {
            Some(Err(why)) => Err(format!("texture '{id}' ({why})")),
            Some(Ok(texture)) => Ok(texture.clone()),
            None => Ok(None),
        }
    }

    /// A lit material's texture `id` with its sampler (`Some(None)`: no texture named;
    /// `None`: the texture could not be had).
    fn lit_texture(&self, id: &Option<String>) -> Option<Option<(Texture, sample::Sampler)>> {
        let Some(at) = id.as_deref().map(|id| self.lit_position.get(id)) else {
            return Some(None);
        };
        match self.lit.get(*at?) {
            Some(Ok(Some(texture))) => Some(Some((texture.clone(), self.sampler(id)))),
            _ => None,
        }
    }

    /// The material as the evaluator samples it (`None`: nothing of it can be).
    fn sampled(&self, parsed: Parsed) -> Option<MaterialSource> {
        let Parsed {
            pbr,
            lit,
            double_sided,
            ..
        } = parsed;
        if let Some(pbr) = pbr {
            let (colour, data) = (
                self.pbr_texture(&pbr.colour_texture),
                self.pbr_texture(&pbr.data_texture),
            );
            let unread = [&colour, &data]
                .into_iter()
                .filter_map(|t| t.as_ref().err().cloned());
            return Some(MaterialSource::Legacy {
                unread: unread.collect(),
                colour: colour.ok().flatten(),
                data: data.ok().flatten(),
                samplers: [
                    self.sampler(&pbr.colour_texture),
                    self.sampler(&pbr.data_texture),
                ],
                pbr: Box::new(pbr),
                reading: SpecGlossReading::DraftAppendix,
                double_sided,
            });
        }
        let text = lit?;
        Some(MaterialSource::lit_legacy(LitLegacy {
            emission: text.emission,
            emission_texture: self.lit_texture(&text.emission_texture)?,
            alpha: text.alpha,
            alpha_texture: self.lit_texture(&text.alpha_texture)?,
            blend: text.blend,
            double_sided,
        }))
    }
}

/// A 1.0 material as read: its PBR block, or what a lit one says of its emission and
/// coverage, and whether it draws both sides.
struct Parsed<'s> {
    id: &'s str,
    pbr: Option<pbr::LegacyPbr>,
    lit: Option<LitText>,
    double_sided: Option<bool>,
}

impl<'s> Parsed<'s> {
    fn read(source: &source::Source, id: &'s str, material: Node) -> Self {
        let pbr = pbr::find(material).and_then(|(name, block)| pbr::parse(name, block));
        let lit = match pbr {
            Some(_) => None,
            None => lit_text(source, material),
        };
        Parsed {
            id,
            pbr,
            lit,
            double_sided: blend::double_sided(source, material),
        }
    }
}

/// The distinct texture ids among `ids` (in order), and the position of each.
fn distinct<'a>(
    ids: impl Iterator<Item = &'a Option<String>>,
) -> (Vec<String>, HashMap<String, usize>) {
    let ids: Vec<String> = (ids.flatten().cloned())
        .collect::<std::collections::BTreeSet<_>>()
        .into_iter()
        .collect();
    let position = (ids.iter().enumerate())
        .map(|(at, id)| (id.clone(), at))
        .collect();
    (ids, position)
}

/// What a lit 1.0 material says of its emission and coverage (see [`LitLegacy`]), its
/// textures by id.
struct LitText {
    emission: [f64; 3],
    emission_texture: Option<String>,
    alpha: f64,
    alpha_texture: Option<String>,
    blend: Option<Blend>,
}

/// Reads a 1.0 material without a PBR block: KHR_materials_common's values, a technique's
/// (material values over the technique's parameter defaults, named as COLLADA2GLTF names
/// them: `emission`, `diffuse`, `transparency`), or the default material ("50% gray emissive
/// color", written to the framebuffer as it is). Colours are display values, linearised.
/// Coverage is the diffuse alpha times `transparency` where the material blends.
fn lit_text(source: &source::Source, material: Node) -> Option<LitText> {
    let common = (material.get("extensions")).and_then(|e| e.get("KHR_materials_common"));
    let technique = (material.get("technique").and_then(Node::as_str))
        .and_then(|t| source.object("techniques", t));
    let (values, blend) = match (common, technique) {
        (Some(common), _) => common_values(common),
        (None, Some(technique)) => technique_values(technique, material),
        (None, None) if material.get("technique").is_none() => {
            return Some(LitText {
                emission: [srgb_to_linear(0.5); 3],
                emission_texture: None,
                alpha: 1.0,
                alpha_texture: None,
                blend: None,
            });
        }
        // A technique id that names nothing: nothing says what it draws.
        (None, None) => return None,
    };
    let colour = |name: &str| {
        let value = values.get(name)?;
        if let Some(texture) = value.as_str() {
            return Some((None, Some(texture.to_string())));
        }
        let c = value.as_array()?;
        let at = |i: usize, default: f64| c.get(i).and_then(Node::as_f64).unwrap_or(default);
        let linear = [0, 1, 2].map(|i| srgb_to_linear(at(i, 0.0)));
        Some((Some((linear, at(3, 1.0))), None))
    };
    let colour = |name: &str| colour(name).unwrap_or((None, None));
    let (emission, emission_texture) = colour("emission");
    let (diffuse, diffuse_texture) = colour("diffuse");
    let opacity = (values.get("transparency").and_then(|o| o.as_f64())).unwrap_or(1.0);
    let diffuse_alpha = diffuse.map_or(1.0, |(_, alpha)| alpha);
    let emission = match (emission, &emission_texture) {
        (Some((colour, _)), _) => colour,
        // A texture alone is the emission.
        (None, Some(_)) => [1.0; 3],
        (None, None) => [0.0; 3],
    };
    Some(LitText {
        emission,
        emission_texture,
        alpha: if blend.is_some() {
            diffuse_alpha * opacity
        } else {
            1.0
        },
        alpha_texture: diffuse_texture.filter(|_| blend.is_some()),
        blend,
    })
}

/// KHR_materials_common's values (the early form {type, value} read by its value) and how
/// it blends.
fn common_values(common: Node<'_>) -> (HashMap<&str, Node<'_>>, Option<Blend>) {
    let own = common.get("values").and_then(Node::as_object);
    let mut values: HashMap<&str, Node> = own.into_iter().flat_map(|o| o.iter()).collect();
    for value in values.values_mut() {
        if let Some(inner) = value.get("value").filter(|_| value.get("type").is_some()) {
            *value = inner;
        }
    }
    // "Applies To": the constant model reads no diffuse.
    if common.get("technique").and_then(Node::as_str) == Some("CONSTANT") {
        values.remove("diffuse");
    }
    let transparent = common.get("transparent").and_then(Node::as_bool) == Some(true);
    let opacity = values.get("transparency").and_then(|o| o.as_f64());
    // "transparent … corresponds to enabling the BLEND render state", with the
    // implementation note's functions ONE, ONE_MINUS_SRC_ALPHA; an opacity below 1 is read
    // as asking for the same.
    let blend = (transparent || opacity.is_some_and(|o| o < 1.0)).then_some(Blend::Premultiplied);
    (values, blend)
}

/// A technique material's values over its technique's parameter defaults, and how the
/// technique blends.
fn technique_values<'t>(
    technique: Node<'t>,
    material: Node<'t>,
) -> (HashMap<&'t str, Node<'t>>, Option<Blend>) {
    let parameters = technique.get("parameters").and_then(Node::as_object);
    let mut values = HashMap::new();
    for (name, parameter) in parameters.into_iter().flat_map(|p| p.iter()) {
        if let Some(value) = parameter.get("value") {
            values.insert(name, value);
        }
    }
    let own = material.get("values").and_then(Node::as_object);
    values.extend(own.into_iter().flat_map(|o| o.iter()));
    (values, technique_blend(technique))
}
