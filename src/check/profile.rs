//! What each profile reports of what the passes find: the one place where gltfmat's default
//! profile departs from the Khronos report.
//!
//! The Khronos passes emit what the Khronos validator emits; gltfmat's rules declare, in their
//! own files, which Khronos findings they supersede (`rules::Supersession`) and which Khronos code
//! the validator would use for theirs (`Rule::khronos_name`). This module applies both as each
//! finding is emitted:
//! - the default profile drops a superseded finding its rule's filter rejects, and every
//!   finding of a code the newer Khronos validator retired ([`khronos::RETIRED`]);
//! - the Khronos profile drops gltfmat's own codes (or renames them to the validator's code
//!   for the same finding) and the codes the released validator does not have.
//!
//! Where the default profile reads the document differently (not a filter), the passes ask
//! the [`Profile`] by name; each such reading is listed in [`READINGS`] with its reason.

use super::context::{Context, Reporting};
use super::rules::RULES;
use super::Profile;
use crate::diagnostic::{khronos, Code, Diagnostic};
use std::collections::HashMap;

impl Profile {
    /// Whether a texture binding's texCoord is read through its KHR_texture_transform
    /// override, as a renderer samples it (the Khronos validator reads the raw `texCoord`).
    pub(crate) fn reads_texcoord_override(self) -> bool {
        self == Profile::Default
    }

    /// Whether the extensions gltfmat validates beyond the Khronos list are validated.
    pub(crate) fn knows_extensions_beyond_khronos(self) -> bool {
        self == Profile::Default
    }

    /// Whether gltfmat's rules run (and the passes keep what only they read, such as the
    /// images' bytes).
    pub(crate) fn runs_rules(self) -> bool {
        self == Profile::Default
    }

    /// Whether a skin's common roots are found as the Khronos validator finds them: an
    /// intersection of the joints' lines that starts afresh when it becomes empty.
    pub(crate) fn refills_emptied_common_roots(self) -> bool {
        self == Profile::Khronos
    }

    /// Whether a KTX2 image is read as one (the released Khronos validator recognises no KTX2,
    /// with or without KHR_texture_basisu).
    pub(crate) fn recognises_ktx2(self) -> bool {
        self == Profile::Default
    }

    /// Whether the data walks keep a bounded number of findings per accessor and per pass
    /// (the rest counted): the Khronos validator lists every one, and so does its profile
    /// unless `--max-issues` says otherwise.
    pub(crate) fn caps_data_findings(self) -> bool {
        self == Profile::Default
    }

    /// Whether a material's extension objects count among its extensions (as several
    /// extensions, or as one that transmits light) as the document writes them, undeclared
    /// or mistyped ones too, as the Khronos validator counts them; the default profile reads
    /// those as absent.
    pub(crate) fn counts_extensions_as_written(self) -> bool {
        self == Profile::Khronos
    }

    /// Whether link findings after an animation channel without a sampler index are named
    /// by the path the Khronos validator leaves unwound (see `khronos::LinkPath`); the
    /// default profile names each at its own pointer.
    pub(crate) fn names_link_findings_as_the_validator(self) -> bool {
        self == Profile::Khronos
    }

    /// Whether an image with any extension object, as written, is read: the Khronos
    /// validator leaves such an image to its extension and neither fetches nor parses it.
    pub(crate) fn reads_images_with_extensions(self) -> bool {
        self == Profile::Default
    }

    /// Whether the document is read no further than the Khronos validator reads it when a
    /// data URI's base64 ends in bits past its data (see `khronos::stops_at_data_uri`); the
    /// default profile reports that URI and reads on.
    pub(crate) fn stops_where_the_validator_stops(self) -> bool {
        self == Profile::Khronos
    }

    /// Whether the texture bindings inside a material extension the profile does not read
    /// count: each member named `…Texture` that holds an `index` (as every glTF binding is
    /// named) marks its texture and texCoord sets used, and such a material's tangent need is
    /// left unjudged. The Khronos validator reads nothing in an extension it does not know.
    pub(crate) fn reads_bindings_in_unknown_extensions(self) -> bool {
        self == Profile::Default
    }

    /// Whether an attribute semantic named after an extension `extensionsUsed` declares,
    /// `<extension>:<name>` (KHR_gaussian_splatting's `KHR_gaussian_splatting:SCALE`), is
    /// that extension's. The released Khronos validator knows only the core semantics and
    /// application-specific ones starting with `_`.
    pub(crate) fn reads_extension_attribute_semantics(self) -> bool {
        self == Profile::Default
    }

    /// Whether a glTF 1.0 document gets the 1.0 checks instead of the 2.0 passes.
    pub(crate) fn checks_gltf1(self) -> bool {
        self == Profile::Default
    }
}

/// Why link findings after an animation channel without a sampler index are at their own
/// pointers in the default profile (see `khronos::LinkPath`).
const OWN_POINTERS: &str = "Reported at its own pointer. After an animation channel without a sampler index, the Khronos validator names what it links next (the animation's unused samplers, later channels and animations, scenes, the node checks) by a path it did not unwind, such as /animations/2/channels/0/samplers/0 or /animations/nodes/0.";

/// Why an object is unused differently in the default profile: where link findings are
/// named (see `khronos::LinkPath`) and what an unknown extension binds (see
/// [`Profile::reads_bindings_in_unknown_extensions`]).
const UNUSED: &str = "Reported at its own pointer after an animation channel without a sampler index, where the Khronos validator names an unused sampler by a path it did not unwind (/animations/2/channels/0/samplers/0). A texture bound inside a material extension gltfmat does not read (a member named …Texture holding an index, as KHR_materials_coat's coatNormalTexture) is used, and so are the texCoord sets below 64 it reads; an index there that names nothing is not reported. The Khronos validator reads nothing in an extension it does not know.";

/// The Khronos codes whose findings differ in the default profile because it reads the
/// document differently, and why.
pub(crate) static READINGS: &[(Code, &str)] = &[
    (khronos::UNUSED_OBJECT, UNUSED),
    (khronos::UNRESOLVED_REFERENCE, OWN_POINTERS),
    (khronos::NODE_EMPTY, OWN_POINTERS),
    (khronos::NODE_LOOP, OWN_POINTERS),
    (khronos::SCENE_NON_ROOT_NODE, OWN_POINTERS),
    (khronos::ANIMATION_CHANNEL_TARGET_NODE_SKIN, OWN_POINTERS),
    (khronos::ANIMATION_CHANNEL_TARGET_NODE_MATRIX, OWN_POINTERS),
    (khronos::ANIMATION_CHANNEL_TARGET_NODE_WEIGHTS_NO_MORPHS, OWN_POINTERS),
    (khronos::ANIMATION_DUPLICATE_TARGETS, OWN_POINTERS),
    (khronos::ANIMATION_SAMPLER_ACCESSOR_WITH_BYTESTRIDE, OWN_POINTERS),
    (khronos::ANIMATION_SAMPLER_INPUT_ACCESSOR_INVALID_FORMAT, OWN_POINTERS),
    (khronos::ANIMATION_SAMPLER_INPUT_ACCESSOR_TOO_FEW_ELEMENTS, OWN_POINTERS),
    (khronos::ANIMATION_SAMPLER_INPUT_ACCESSOR_WITHOUT_BOUNDS, OWN_POINTERS),
    (khronos::ANIMATION_SAMPLER_OUTPUT_ACCESSOR_INVALID_COUNT, OWN_POINTERS),
    (khronos::ANIMATION_SAMPLER_OUTPUT_ACCESSOR_INVALID_FORMAT, OWN_POINTERS),
    (khronos::ACCESSOR_ANIMATION_INPUT_NEGATIVE, OWN_POINTERS),
    (khronos::ACCESSOR_ANIMATION_INPUT_NON_INCREASING, OWN_POINTERS),
    (khronos::ACCESSOR_ANIMATION_SAMPLER_OUTPUT_NON_NORMALIZED_QUATERNION, OWN_POINTERS),
    (
        khronos::KHR_MATERIALS_ANISOTROPY_ANISOTROPY_TEXTURE_TEXCOORD,
        "Compares the texCoord a renderer samples, i.e. with KHR_texture_transform's texCoord override applied.",
    ),
    (
        khronos::KHR_MATERIALS_CLEARCOAT_CLEARCOAT_NORMAL_TEXTURE_TEXCOORD,
        "Compares the texCoord a renderer samples, i.e. with KHR_texture_transform's texCoord override applied.",
    ),
    (
        khronos::IMAGE_UNRECOGNIZED_FORMAT,
        "A KTX2 image is read as KTX2 (a texture then says that its source needs KHR_texture_basisu); the released Khronos validator recognises no KTX2 and reports the image's format as unrecognized.",
    ),
    (
        khronos::VALUE_NOT_IN_LIST,
        "An image's mimeType 'image/ktx2' is valid where KHR_texture_basisu is used, as that extension's schema adds it; the released Khronos validator knows only PNG, JPEG and (with EXT_texture_webp) WebP.",
    ),
    (
        khronos::INVALID_URI,
        "A data URI whose base64 ends in bits past its data (its last character is not the one that encodes the data, as in 'Ra==' for 'E') is reported here, decoded as browsers decode it, and the rest of the document is checked. The Khronos validator's decoder refuses it and stops reading the file there: its report is INVALID_JSON and what it found before.",
    ),
    (
        khronos::MESH_PRIMITIVE_INVALID_ATTRIBUTE,
        "An attribute semantic named after an extension extensionsUsed declares, <extension>:<name> (KHR_gaussian_splatting:SCALE, KHR_gaussian_splatting:SH_DEGREE_0_COEF_0), is that extension's, as KHR_gaussian_splatting defines them. The released Khronos validator (2.0.0-dev.3.10) knows only the core semantics and application-specific ones starting with '_', and reports these as invalid.",
    ),
    (
        khronos::SKIN_NO_COMMON_ROOT,
        "Reported for every skin whose joints share no root. The Khronos validator starts its intersection of the joints' lines afresh once it is empty, so joints in separate trees pass when the last ones share a tree.",
    ),
    (
        khronos::UNSUPPORTED_EXTENSION,
        "The default profile validates extensions the released Khronos validator (2.0.0-dev.3.10) does not know: KHR_materials_diffuse_transmission, KHR_node_visibility and KHR_texture_basisu.",
    ),
    (
        khronos::UNEXPECTED_PROPERTY,
        "The objects of the extensions the default profile knows beyond the released Khronos validator (KHR_materials_diffuse_transmission, KHR_node_visibility, KHR_texture_basisu) are read member by member; the released validator reads nothing in them.",
    ),
    (
        khronos::UNEXPECTED_EXTENSION_OBJECT,
        "An extension the default profile knows (KHR_node_visibility, KHR_materials_diffuse_transmission, KHR_texture_basisu) is also checked for the objects it may extend; the released validator knows none of them.",
    ),
    (
        khronos::KHR_MATERIALS_VOLUME_NO_TRANSMISSION,
        "An extension object extensionsUsed does not declare, or one that is no object, is absent (UNDECLARED_EXTENSION or TYPE_MISMATCH reports it): it does not stand in for the transmission the volume needs, as it does for the Khronos validator.",
    ),
    (
        khronos::IMAGE_DATA_INVALID,
        "An image with an extension object (KHR_xmp_json_ld metadata, say) is read and its data checked like any other's (a missing file is an IO_ERROR, a broken one IMAGE_DATA_INVALID); the Khronos validator leaves such an image to its extension and neither fetches nor parses it.",
    ),
    (
        super::rules::gltf1::RULE.code(),
        "On a glTF 1.0 document the 2.0 passes do not run: every Khronos code is replaced by GLTF_1_0_ASSET and the 1.0 PBR checks.",
    ),
];

/// What a profile does with findings of one code.
#[derive(Clone, Copy)]
enum Treatment {
    Drop,
    Rename(Code),
    Filter(fn(&Context, &Diagnostic) -> bool),
}

/// The treatments of one profile, looked up once per finding.
pub(crate) struct Filters(HashMap<Code, Treatment>);

impl Filters {
    pub(crate) fn of(profile: Profile) -> Filters {
        let treatments: Vec<(Code, Treatment)> = match profile {
            Profile::Khronos => (RULES.iter())
                .map(|rule| match rule.khronos_name {
                    Some((name, _)) => (rule.code(), Treatment::Rename(name)),
                    None => (rule.code(), Treatment::Drop),
                })
                .chain(
                    khronos::UNRELEASED
                        .iter()
                        .map(|(c, _)| (*c, Treatment::Drop)),
                )
                .collect(),
            Profile::Default => (RULES.iter())
                .flat_map(|rule| rule.supersedes)
                .map(|s| (s.code, Treatment::Filter(s.keeps)))
                .chain(khronos::RETIRED.iter().map(|(c, _)| (*c, Treatment::Drop)))
                .collect(),
        };
        Filters(treatments.into_iter().collect())
    }
}

impl Reporting for Filters {
    fn report(&self, ctx: &Context, mut diagnostic: Diagnostic) -> Option<Diagnostic> {
        match self.0.get(&diagnostic.code) {
            None => Some(diagnostic),
            Some(Treatment::Drop) => None,
            Some(Treatment::Rename(code)) => {
                diagnostic.code = *code;
                Some(diagnostic)
            }
            Some(Treatment::Filter(keeps)) => keeps(ctx, &diagnostic).then_some(diagnostic),
        }
    }
}

/// Why the default profile reports `code` differently from the Khronos validator, if it does.
pub(crate) fn why_different(code: &str) -> Option<&'static str> {
    let superseded = (RULES.iter().flat_map(|rule| rule.supersedes))
        .find(|s| s.code.name() == code)
        .map(|s| s.why);
    let renamed = || {
        (RULES.iter().filter_map(|rule| rule.khronos_name))
            .find(|(c, _)| c.name() == code)
            .map(|(_, why)| why)
    };
    let khronos_own = || {
        (khronos::RETIRED
            .iter()
            .chain(khronos::UNRELEASED)
            .chain(READINGS))
        .find(|(c, _)| c.name() == code)
        .map(|(_, why)| *why)
    };
    superseded.or_else(renamed).or_else(khronos_own)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::check::code_info::Origin;
    use crate::check::registry;

    fn origin(code: Code) -> Origin {
        registry::find(code.name()).expect("registered").origin
    }

    #[test]
    fn rules_supersede_and_are_renamed_to_khronos_codes_only() {
        for rule in RULES {
            for superseded in rule.supersedes {
                assert_eq!(origin(superseded.code), Origin::Khronos, "{}", rule.code());
            }
            if let Some((name, _)) = rule.khronos_name {
                assert_eq!(origin(name), Origin::Khronos, "{}", rule.code());
            }
        }
    }

    #[test]
    fn every_departure_is_declared_once_and_explained_by_its_own_reason() {
        let declared = (RULES
            .iter()
            .flat_map(|r| r.supersedes.iter().map(|s| (s.code, s.why))))
        .chain(RULES.iter().filter_map(|r| r.khronos_name))
        .chain(khronos::RETIRED.iter().chain(khronos::UNRELEASED).copied())
        .chain(READINGS.iter().copied());
        let mut seen = std::collections::HashSet::new();
        for (code, why) in declared {
            assert!(seen.insert(code), "{code} departs in two places");
            assert!(!why.is_empty(), "{code} has no reason");
            assert_eq!(why_different(code.name()), Some(why), "{code}");
        }
    }
}
