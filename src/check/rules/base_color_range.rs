//! Dielectric base colours outside the plausible albedo range.

use super::texels::Sampled;
use super::{Rule, Run, LARGE_AREA};
use crate::check::context::{number, Context};
use crate::check::khronos::materials::{extension, SlotUse};
use crate::diagnostic::Severity;
use crate::document::Array;
use crate::document::Node;
use crate::gltf::color::{linear_to_srgb, luminance, srgb_to_linear};

pub(super) const RULE: Rule = Rule::new(
    "PBR_BASE_COLOR_RANGE",
    Severity::Hint,
    "plausibility",
    "A dielectric base colour is darker than sRGB 30 or brighter than sRGB 240.",
    DOC,
    Run::both(check_factor, applies, inspect),
);

const DOC: &str = "\
## What it does
For dielectric materials (`metallicFactor` ≤ 0.1, so no texel can be more metallic), computes
the base colour's luminance and encodes it as 8-bit sRGB. Reports values below 30 or above
240: from a `baseColorFactor` written in the file when there is no texture, and with `--deep`
from the texture times the factor when more than 10% of its texels are out of range.
Materials that transmit light (KHR_materials_transmission with a factor above 0 or a
texture) are left out: their base colour also tints the transmitted light, and clear glass
is white. Unlit materials are left out too.

## Why
Real non-metals reflect between about 2% (charcoal) and 90% (fresh snow) of light. Darker
albedos make surfaces look like holes under any lighting; brighter ones glow and break
exposure. The range is the one Substance's PBR Validate and Khronos's asset auditor use.
It is an opinion, not a spec rule: it runs only with `--enable-group plausibility`.

## Example
```json
{\"pbrMetallicRoughness\": {\"baseColorFactor\": [0.005, 0.005, 0.005, 1], \"metallicFactor\": 0}}
```
";

const DARKEST: f64 = 30.0;
const BRIGHTEST: f64 = 240.0;

fn is_dielectric(material: Node) -> bool {
    let pbr = material.get("pbrMetallicRoughness");
    pbr.map_or(1.0, |p| number(p, "metallicFactor", 1.0)) <= 0.1
}

/// Whether the material lets light through: its base colour is then the tint of the
/// transmitted light as well (KHR_materials_transmission §Base Color), and clear glass must
/// be white.
fn transmits(material: Node) -> bool {
    extension(material, "KHR_materials_transmission").is_some_and(|t| {
        number(t, "transmissionFactor", 0.0) > 0.0 || t.get("transmissionTexture").is_some()
    })
}

/// Whether a base colour is judged at all: a dielectric that does not transmit light and is
/// not unlit.
fn judged(material: Node) -> bool {
    is_dielectric(material)
        && !transmits(material)
        && extension(material, "KHR_materials_unlit").is_none()
}

fn written_factor(material: Node) -> Option<Array> {
    material
        .get("pbrMetallicRoughness")
        .and_then(|p| p.get("baseColorFactor"))
        .and_then(Node::as_array)
}

fn factor(material: Node) -> [f64; 3] {
    let list = written_factor(material);
    let channel = |i: usize| {
        list.and_then(|l| l.get(i))
            .and_then(Node::as_f64)
            .unwrap_or(1.0)
    };
    [channel(0), channel(1), channel(2)]
}

/// Luminance of a linear colour, as an 8-bit sRGB value.
fn srgb_level(linear: [f64; 3]) -> f64 {
    255.0 * linear_to_srgb(luminance(linear).clamp(0.0, 1.0))
}

fn implausible(level: f64) -> bool {
    !(DARKEST..=BRIGHTEST).contains(&level)
}

fn check_factor(ctx: &mut Context) {
    for (_, pointer, material) in ctx.objects("materials") {
        let pbr = material.get("pbrMetallicRoughness");
        let textured = pbr.is_some_and(|p| p.get("baseColorTexture").is_some());
        // An absent factor is the default white, which nobody chose: nothing to point at.
        if textured || written_factor(material).is_none() || !judged(material) {
            continue;
        }
        let level = srgb_level(factor(material));
        if implausible(level) {
            ctx.emit(
                RULE.code(),
                format!("{pointer}/pbrMetallicRoughness/baseColorFactor"),
                format!("Dielectric base colour has sRGB luminance {level:.0}, outside the plausible {DARKEST}–{BRIGHTEST}."),
            );
        }
    }
}

fn applies(slot_use: &SlotUse) -> bool {
    slot_use.slot.key == "baseColorTexture" && judged(slot_use.material)
}

fn inspect(ctx: &mut Context, slot_use: &SlotUse, texels: &Sampled) {
    let [fr, fg, fb] = factor(slot_use.material);
    // Compare in linear space, with the sRGB decode tabulated: 16 M powf calls per 4096²
    // texture would dominate `--deep`. 4096 steps are finer than any 8- or 12-bit source.
    let table: Vec<f64> = (0..=4095)
        .map(|i| srgb_to_linear(f64::from(i) / 4095.0))
        .collect();
    let decode = |c: f32| table[(c.clamp(0.0, 1.0) * 4095.0).round() as usize];
    let (dark, bright) = (
        srgb_to_linear(DARKEST / 255.0),
        srgb_to_linear(BRIGHTEST / 255.0),
    );
    let tally = texels.tally(|[r, g, b, _]| {
        let y = luminance([decode(r) * fr, decode(g) * fg, decode(b) * fb]);
        y < dark || y > bright
    });
    if tally.fraction() > LARGE_AREA {
        ctx.emit(
            RULE.code(),
            slot_use.pointer(),
            format!(
                "Dielectric base colour is outside sRGB luminance {DARKEST}–{BRIGHTEST} in {}.",
                tally.describe()
            ),
        );
    }
}
