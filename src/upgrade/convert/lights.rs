//! KHR_materials_common lights → KHR_lights_punctual: directional, point and spot lights placed
//! by nodes (both extensions point a light along the node's −Z); ambient light has no 2.0 form.

use super::materials::linear_colour;
use crate::document::json::escape_token;
use crate::document::Node;
use crate::upgrade::builder::Builder;
use crate::upgrade::NoteKind;
use serde_json::{json, Value};

/// What the root extension calls them, and what the output's does.
const SOURCE: &str = "/extensions/KHR_materials_common/lights";
pub(in crate::upgrade) const PUNCTUAL: &str = "KHR_lights_punctual";

impl Builder<'_, '_> {
    /// The KHR_lights_punctual index of the light 1.0 node `node` places, the light converted
    /// on its first use (each decision noted once, at the light).
    pub(in crate::upgrade) fn node_light(&mut self, node_at: &str, node: Node) -> Option<usize> {
        let id = (node.get("extensions")?.get("KHR_materials_common")?)
            .get("light")?
            .as_str()?;
        if let Some(&known) = self.lights.get(id) {
            return known;
        }
        let at = format!("{SOURCE}/{}", escape_token(id));
        let converted = match self.source.root().pointer(&at) {
            Some(light) => self.punctual(&at, id, light),
            None => {
                self.note(
                    node_at,
                    NoteKind::Dropped,
                    format!("KHR_materials_common light '{id}' does not exist."),
                );
                None
            }
        };
        let index = converted.map(|light| self.push("lights", light));
        self.lights.insert(id.to_string(), index);
        index
    }

    /// Lights no node places are noted: 2.0 lights exist only where a node puts them.
    pub(in crate::upgrade) fn unplaced_lights(&mut self) {
        let unplaced: Vec<String> = (self.source.root().pointer(SOURCE))
            .and_then(Node::as_object)
            .into_iter()
            .flat_map(|all| all.keys())
            .filter(|id| !self.lights.contains_key(*id))
            .map(str::to_string)
            .collect();
        for id in unplaced {
            self.note(
                format!("{SOURCE}/{}", escape_token(&id)),
                NoteKind::Dropped,
                "light placed by no node: nothing to convert it to.",
            );
        }
    }

    /// One 1.0 light as a KHR_lights_punctual light, or None (noted) when it has no 2.0 form.
    fn punctual(&mut self, at: &str, id: &str, light: Node) -> Option<Value> {
        let kind = light.get("type").and_then(Node::as_str).unwrap_or("");
        // A light without its parameters reads every one as missing.
        let params = light.get(kind).unwrap_or(light.null());
        let mut out =
            json!({"type": kind, "name": light.get("name").and_then(Node::as_str).unwrap_or(id)});
        match kind {
            "directional" => {}
            "point" | "spot" => {
                let how = self.attenuation(params, &mut out);
                self.note(at, NoteKind::Decision, how);
            }
            "ambient" => {
                self.note(at, NoteKind::Dropped, "ambient light: KHR_lights_punctual has no ambient light (a viewer's environment lighting takes its place).");
                return None;
            }
            other => {
                self.note(
                    at,
                    NoteKind::Dropped,
                    format!("light type '{other}' is not directional, point, spot or ambient."),
                );
                return None;
            }
        }
        let colour = linear_rgb(params.get("color"));
        let clamped = colour.map(|c| c.clamp(0.0, 1.0));
        if clamped != colour {
            self.note(
                at,
                NoteKind::Decision,
                format!(
                    "colour {colour:?} clamped to 0–1, the range of KHR_lights_punctual colours."
                ),
            );
        }
        out["color"] = json!(clamped);
        if kind == "spot" {
            let how = spot_cone(params, &mut out);
            self.note(at, NoteKind::Decision, how);
        }
        self.note(at, NoteKind::Decision, format!("{kind} light → {PUNCTUAL} (colour linearised; intensity in the 1.0 light's units, which had none)."));
        Some(out)
    }

    /// 1.0 attenuation is 1 / (c + l·d + q·d²); KHR_lights_punctual's is intensity / d².
    /// Exact when only q is set (intensity 1/q); otherwise matched at distance 1.
    fn attenuation(&self, params: Node, out: &mut Value) -> String {
        let (c, l, q) = (
            number(params, &["constantAttenuation"], 0.0),
            number(params, &["linearAttenuation"], 1.0),
            number(params, &["quadraticAttenuation"], 1.0),
        );
        // A sum that is not positive, or so small its reciprocal overflows, has no strength
        // to match: the default intensity stands.
        let intensity = Some(1.0 / (c + l + q)).filter(|i| *i > 0.0 && i.is_finite());
        out["intensity"] = json!(intensity.unwrap_or(1.0));
        let distance = number(params, &["distance"], 0.0);
        if distance > 0.0 {
            out["range"] = json!(distance);
        }
        if c == 0.0 && l == 0.0 && intensity.is_some() {
            format!(
                "attenuation 1/({q:?}·d²) written exactly as intensity {:?}.",
                1.0 / q
            )
        } else {
            format!("attenuation 1/({c:?} + {l:?}·d + {q:?}·d²) has no 2.0 form: inverse-square falloff with the same strength at distance 1.")
        }
    }
}

/// A 1.0 light colour as linear RGB; the spec's default is black.
fn linear_rgb(colour: Option<Node>) -> [f64; 3] {
    let [r, g, b, _] = colour
        .and_then(|c| linear_colour(&c.to_value()))
        .unwrap_or_default();
    [r, g, b]
}

/// The cone: the 1.0 fall-off angle is the full opening (Cesium's 1.0 shaders compare with
/// cos(angle / 2)), default π; 2.0's outer cone angle is the half-angle, at most π/2. The
/// fall-off exponent has no 2.0 form: exponent 0 (a hard edge) becomes an inner cone just
/// inside the outer one, a positive exponent a smooth fall-off from the axis.
fn spot_cone(params: Node, out: &mut Value) -> String {
    let angle = number(
        params,
        &["falloffAngle", "fallOffAngle"],
        std::f64::consts::PI,
    );
    let exponent = number(params, &["falloffExponent", "fallOffExponent"], 0.0);
    let outer = (angle / 2.0).clamp(1e-6, std::f64::consts::FRAC_PI_2);
    let inner = if exponent > 0.0 { 0.0 } else { outer * 0.99 };
    out["spot"] = json!({"innerConeAngle": inner, "outerConeAngle": outer});
    if exponent > 0.0 {
        format!("spot fall-off angle {angle:?} → outer cone {outer:?}; fall-off exponent {exponent:?} has no 2.0 form: a smooth fall-off from the axis (inner cone 0).")
    } else {
        format!("spot fall-off angle {angle:?} → outer cone {outer:?} with a hard edge (inner cone 0.99 of it).")
    }
}

/// The first of `keys` (spellings of one property) that `params` holds as a number.
fn number(params: Node, keys: &[&str], default: f64) -> f64 {
    (keys.iter())
        .find_map(|key| params.get(*key).and_then(Node::as_f64))
        .unwrap_or(default)
}
