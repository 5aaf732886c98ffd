//! gltfmat's own rules, one per file, all registered in [`RULES`]. Each file holds its rule's
//! metadata and documentation (What it does / Why / Example), which `gltfmat rules`,
//! `gltfmat explain` and SARIF read from this table.

use std::sync::Arc;
mod alpha_constant;
mod alpha_missing;
mod anisotropy_direction;
mod anisotropy_tangent;
mod anisotropy_zero_strength;
mod base_color_range;
mod colour_space_conflict;
mod decode_limit;
mod dispersion_thin_walled;
mod duplicate_key;
pub(crate) mod exclusion;
pub(crate) mod gltf1;
mod greyscale_packed;
mod ktx2_dimensions;
mod ktx2_layout;
mod ktx2_mipmaps;
mod ktx2_transfer;
mod layer_disabled;
mod linear_in_srgb;
mod lossy_direction;
mod metallic_mixed;
mod normal_below_surface;
mod not_decoded;
pub(crate) mod outside_folder;
pub(crate) mod resource_not_read;
mod seen;
mod sheen_disabled;
mod sheen_zero_roughness;
mod specular_on_metal;
mod srgb_in_linear;
pub(crate) mod texels;
mod transmission_on_metal;
mod undecodable;
mod unlit_ignored;

use super::code_info::{CodeInfo, Origin};
use super::context::Context;
use super::khronos::materials::{by_image, slot_uses, SlotUse};
use crate::diagnostic::{Code, Diagnostic, Severity};
use crate::document::image_header::ImageInfo;
use texels::Sampled;

pub(crate) struct Rule {
    pub info: CodeInfo,
    pub run: Run,
    /// The Khronos findings this rule corrects, each with the filter the default profile
    /// applies to them (see `check::profile`).
    pub supersedes: &'static [Supersession],
    /// The Khronos code the validator gives the same finding, and why gltfmat's differs: the
    /// Khronos profile reports the rule's findings under that code (the others not at all).
    pub khronos_name: Option<(Code, &'static str)>,
}

/// A Khronos finding that gltfmat's default profile reports only where `keeps` says so,
/// declared by the rule that corrects it (and applied by `check::profile`).
pub(crate) struct Supersession {
    /// The Khronos code.
    pub code: Code,
    /// Why the default profile differs, for `gltfmat explain` and the conformance test.
    pub why: &'static str,
    /// Whether the default profile still reports this finding.
    pub keeps: fn(&Context, &Diagnostic) -> bool,
}

/// How a rule runs. A rule with neither part is emitted by a core pass (reading, resources).
pub(crate) struct Run {
    /// Reads the document.
    pub document: Option<fn(&mut Context)>,
    /// With `--deep`: inspects the decoded texels of each texture binding it applies to.
    pub pixels: Option<PixelCheck>,
}

pub(crate) struct PixelCheck {
    pub applies: fn(&SlotUse) -> bool,
    pub inspect: fn(&mut Context, &SlotUse, &Sampled),
}

impl Run {
    pub(crate) const CORE: Run = Run {
        document: None,
        pixels: None,
    };

    pub(crate) const fn document(check: fn(&mut Context)) -> Run {
        Run {
            document: Some(check),
            pixels: None,
        }
    }

    pub(crate) const fn pixels(
        applies: fn(&SlotUse) -> bool,
        inspect: fn(&mut Context, &SlotUse, &Sampled),
    ) -> Run {
        Run {
            document: None,
            pixels: Some(PixelCheck { applies, inspect }),
        }
    }

    /// A document check (factors) plus a pixel check (`--deep`, textures) under one code.
    pub(crate) const fn both(
        check: fn(&mut Context),
        applies: fn(&SlotUse) -> bool,
        inspect: fn(&mut Context, &SlotUse, &Sampled),
    ) -> Run {
        Run {
            document: Some(check),
            pixels: Some(PixelCheck { applies, inspect }),
        }
    }
}

impl Rule {
    /// The code this rule emits.
    pub(crate) const fn code(&self) -> Code {
        self.info.code
    }

    pub(crate) const fn new(
        name: &'static str,
        severity: Severity,
        group: &'static str,
        summary: &'static str,
        doc: &'static str,
        run: Run,
    ) -> Rule {
        Rule::documenting(Code::new(name, severity), group, summary, doc, run)
    }

    /// The rule of a code defined where a core pass can name it (see `check::pass_codes`).
    pub(crate) const fn documenting(
        code: Code,
        group: &'static str,
        summary: &'static str,
        doc: &'static str,
        run: Run,
    ) -> Rule {
        Rule {
            info: CodeInfo {
                code,
                group,
                summary,
                doc,
                origin: Origin::Gltfmat,
                own_logic: run.document.is_some() || run.pixels.is_some(),
            },
            run,
            supersedes: &[],
            khronos_name: None,
        }
    }

    /// The rule, correcting the Khronos findings `supersedes`.
    pub(crate) const fn superseding(self, supersedes: &'static [Supersession]) -> Rule {
        Rule { supersedes, ..self }
    }

    /// The rule, whose findings the Khronos validator reports as `code` (for the reason `why`).
    pub(crate) const fn khronos_name(self, code: Code, why: &'static str) -> Rule {
        Rule {
            khronos_name: Some((code, why)),
            ..self
        }
    }
}

pub(crate) static RULES: &[&Rule] = &[
    &duplicate_key::RULE,
    &outside_folder::RULE,
    &resource_not_read::RULE,
    &gltf1::RULE,
    &gltf1::PBR_RULE,
    &exclusion::RULE,
    &anisotropy_tangent::RULE,
    &alpha_missing::RULE,
    &greyscale_packed::RULE,
    &lossy_direction::RULE,
    &colour_space_conflict::RULE,
    &linear_in_srgb::RULE,
    &srgb_in_linear::RULE,
    &ktx2_transfer::RULE,
    &ktx2_dimensions::RULE,
    &ktx2_layout::RULE,
    &ktx2_mipmaps::RULE,
    &sheen_disabled::RULE,
    &sheen_zero_roughness::RULE,
    &anisotropy_zero_strength::RULE,
    &unlit_ignored::RULE,
    &specular_on_metal::RULE,
    &transmission_on_metal::RULE,
    &layer_disabled::RULE,
    &dispersion_thin_walled::RULE,
    &undecodable::RULE,
    &decode_limit::RULE,
    &not_decoded::RULE,
    &anisotropy_direction::RULE,
    &normal_below_surface::RULE,
    &alpha_constant::RULE,
    &base_color_range::RULE,
    &metallic_mixed::RULE,
];

/// Groups whose rules run only when asked for: opinions about plausible values, which no
/// spec sentence makes a defect, stay out of the default report.
pub static OPT_IN_GROUPS: &[&str] = &["plausibility"];

/// Whether `group` is one of the [`OPT_IN_GROUPS`].
pub fn is_opt_in(group: &str) -> bool {
    OPT_IN_GROUPS.iter().any(|g| g.eq_ignore_ascii_case(group))
}

fn enabled(ctx: &Context, rule: &Rule) -> bool {
    let named = |groups: &[String]| {
        groups
            .iter()
            .any(|g| g.eq_ignore_ascii_case(rule.info.group))
    };
    let wanted = !is_opt_in(rule.info.group) || named(&ctx.options.enabled_groups);
    wanted && !named(&ctx.options.disabled_groups)
}

/// Runs every enabled document rule, then (with `--deep`) every enabled pixel rule.
pub(crate) fn run_all(ctx: &mut Context) {
    let checks: Vec<_> = RULES
        .iter()
        .filter(|r| enabled(ctx, r))
        .filter_map(|r| r.run.document)
        .collect();
    for check in checks {
        check(ctx);
    }
    if ctx.options.deep {
        run_pixel_rules(ctx);
    }
}

fn run_pixel_rules(ctx: &mut Context) {
    let pixel_rules: Vec<_> = RULES
        .iter()
        .filter(|r| enabled(ctx, r))
        .filter_map(|rule| rule.run.pixels.as_ref())
        .map(|check| (check.applies, check.inspect))
        .collect();
    let uses = slot_uses(ctx);
    let mut sight = seen::Sight::new(ctx);
    for (image, on_image) in by_image(&uses, ctx.items("images").len())
        .into_iter()
        .enumerate()
    {
        let wanted: Vec<(&SlotUse, Vec<_>)> = (on_image.into_iter())
            .map(|u| {
                let inspections = (pixel_rules.iter())
                    .filter(|(applies, _)| applies(u))
                    .map(|(_, inspect)| *inspect);
                (u, inspections.collect())
            })
            .filter(|(_, inspections): &(_, Vec<_>)| !inspections.is_empty())
            .collect();
        if wanted.is_empty() {
            continue;
        }
        // Decoded here and dropped at the end of the iteration: one image in memory at a time.
        let Some(texels) = texels::decode(ctx, image) else {
            continue;
        };
        let (width, height) = texels.size();
        for (slot_use, inspections) in wanted {
            let seen = sight.seen(ctx, slot_use, width, height);
            for inspect in inspections {
                inspect(ctx, slot_use, &texels.as_seen(seen.as_ref()));
            }
        }
    }
}

/// Each texture binding paired with each image it may sample whose header could be read:
/// indices into the shared slot uses, so that 10^5 bindings copy no binding.
struct BoundImages<'a> {
    uses: Arc<[SlotUse<'a>]>,
    bound: Vec<(usize, usize, ImageInfo)>,
}

impl<'a> BoundImages<'a> {
    fn iter(&self) -> impl Iterator<Item = (&SlotUse<'a>, usize, &ImageInfo)> {
        (self.bound.iter()).map(|(at, image, info)| (&self.uses[*at], *image, info))
    }
}

fn bound_images<'a>(ctx: &Context<'a>) -> BoundImages<'a> {
    let uses = slot_uses(ctx);
    let bound = (uses.iter().enumerate())
        .flat_map(|(at, slot_use)| {
            (slot_use.images()).filter_map(move |i| Some((at, i, ctx.images.get(i)?.clone()?)))
        })
        .collect();
    BoundImages { uses, bound }
}

/// The images a texture reads through KHR_texture_basisu (its `source`), whose layout that
/// extension constrains; a KTX2 read otherwise (another extension's, or none) is not bound
/// by it.
fn basisu_images(ctx: &Context) -> std::collections::BTreeSet<usize> {
    let source = |texture: crate::document::Node| {
        let basisu = texture.get("extensions")?.get("KHR_texture_basisu")?;
        crate::gltf::unsigned(basisu, "source").map(|i| i as usize)
    };
    ctx.items("textures").iter().filter_map(source).collect()
}

/// The share of texels above which a plausibility rule reports a texture ("large areas").
const LARGE_AREA: f64 = 0.1;
