//! Khronos parity: the passes that reproduce the Khronos glTF-Validator, one file per glTF object
//! type (like its `base/`) and one folder per extension (`ext/`, like its `ext/`). gltfmat's own
//! behaviour lives in `check/rules/`; nothing here depends on the profile except where the
//! Khronos validator itself would.

pub(crate) mod accessor_data;
mod accessor_fast;
pub(crate) mod accessor_usage;
pub(crate) mod animations;
mod cameras;
pub(crate) mod ext;
mod extensions;
mod influences;
mod link_path;
pub(crate) mod materials;
mod nodes;
pub(crate) use nodes::is_trs_decomposable;
mod objects;
pub(crate) mod primitives;
pub(crate) mod resources;
mod skins;
mod sparse;
mod unused;
mod view_usage;

use super::context::Context;
pub(crate) use ext::lights::take_unread_spots;
pub(crate) use extensions::{
    check_declarations as check_extension_lists, report_undeclared, undeclared_extensions,
    Undeclared,
};
pub(crate) use link_path::LinkPath;
pub(crate) use materials::extensions_as_written;
pub(crate) use objects::{
    check_asset, has_supported_version, read_before_asset, read_before_data_uri, stops_at_data_uri,
    take_unread_bounds, take_unread_offsets, take_unread_projections, take_unread_sparse,
};
pub(crate) use primitives::mode_of;
pub(crate) use resources::images_with_extensions;

/// A double as the validator's messages print it (Dart's `double.toString`): the shortest
/// digits that read back to it, in decimal from 10⁻⁶ up to 10²¹ with at least one digit
/// after the point, otherwise as an exponent with its sign (`1e+21`, `1e-7`).
pub(crate) struct Dart(pub f64);

impl std::fmt::Display for Dart {
    fn fmt(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        let v = self.0;
        if v.is_nan() {
            return f.write_str("NaN");
        }
        if v.is_infinite() {
            return f.write_str(if v > 0.0 { "Infinity" } else { "-Infinity" });
        }
        if v == 0.0 || (1e-6..1e21).contains(&v.abs()) {
            let decimal = v.to_string();
            let point = if decimal.contains('.') { "" } else { ".0" };
            return write!(f, "{decimal}{point}");
        }
        let exponential = format!("{v:e}");
        match exponential.split_once('e') {
            Some((digits, power)) if !power.starts_with('-') => write!(f, "{digits}e+{power}"),
            _ => f.write_str(&exponential),
        }
    }
}

/// One pass over the document, recording findings and what later passes need in the context.
pub(crate) type Pass = fn(&mut Context);

/// The Khronos link order: each pass may read what the passes before it stored in the context
/// (buffer bytes before accessor data, image headers before materials, …).
pub(crate) const PASSES: &[(&str, Pass)] = &[
    ("extensions", extensions::check),
    ("asset", objects::check_asset),
    ("buffers", resources::check_buffers),
    ("bufferViews", resources::check_buffer_views),
    ("accessors", objects::check_accessors),
    ("accessor data", accessor_data::check),
    ("sparse indices", sparse::check_indices),
    ("skin influences", influences::check),
    ("images", resources::check_images),
    ("textures", materials::check_textures),
    ("materials", materials::check_materials),
    ("meshes", objects::check_meshes),
    ("mesh primitives", primitives::check),
    ("bufferView usage", view_usage::check),
    ("nodes and scenes", objects::check_nodes_and_scenes),
    ("node rules", nodes::check),
    ("cameras", cameras::check),
    ("animations", animations::check),
    ("skins", skins::check),
    ("KHR_lights_punctual", ext::lights::check),
    (
        "skins, animations, cameras",
        objects::check_skins_animations_cameras,
    ),
    ("unused objects", unused::check),
];

#[cfg(test)]
mod tests {
    use super::Dart;

    #[test]
    fn doubles_read_as_the_validator_prints_them() {
        let cases = [
            (2.0, "2.0"),
            (-0.5, "-0.5"),
            (0.0, "0.0"),
            (-0.0, "-0.0"),
            (1e-6, "0.000001"),
            (1.0000000116860974e-7, "1.0000000116860974e-7"),
            (10000000272564224.0, "10000000272564224.0"),
            (1e21, "1e+21"),
            (9.999999680285692e37, "9.999999680285692e+37"),
            (f64::NAN, "NaN"),
            (f64::NEG_INFINITY, "-Infinity"),
        ];
        for (v, text) in cases {
            assert_eq!(Dart(v).to_string(), text);
        }
    }
}
