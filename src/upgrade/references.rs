//! The references between materials, textures, images and samplers, found and renumbered:
//! what removing the textures, images and samplers nothing uses needs, for 1.0 and 2.0 inputs.

use serde_json::{json, Value};

/// Every texture index a material reads (the `index` of each member named `…Texture`, in the
/// core object and in any extension), handed to `found`, which may change it.
pub(super) fn visit_texture_indices(value: &mut Value, found: &mut impl FnMut(&mut usize)) {
    match value {
        Value::Object(members) => {
            for (key, member) in members.iter_mut() {
                let index = (key.ends_with("Texture"))
                    .then(|| member.get("index").and_then(Value::as_u64))
                    .flatten();
                match index {
                    Some(old) => {
                        let mut index = old as usize;
                        found(&mut index);
                        member["index"] = json!(index);
                    }
                    None => visit_texture_indices(member, found),
                }
            }
        }
        Value::Array(items) => items
            .iter_mut()
            .for_each(|item| visit_texture_indices(item, found)),
        _ => {}
    }
}

/// The texture indices a material reads.
pub(super) fn texture_indices(material: &Value) -> Vec<usize> {
    let mut found = Vec::new();
    visit_texture_indices(&mut material.clone(), &mut |index| found.push(*index));
    found
}

/// Gives each texture index a material reads its new number (`map[old]`; indices the map
/// does not cover are left alone).
pub(super) fn renumber_textures(material: &mut Value, map: &[Option<usize>]) {
    visit_texture_indices(material, &mut |index| {
        if let Some(Some(new)) = map.get(*index) {
            *index = *new;
        }
    });
}

/// Gives a texture's image (`source`, also inside its extensions) and sampler their new
/// numbers.
pub(super) fn renumber_texture_members(
    texture: &mut Value,
    images: &[Option<usize>],
    samplers: &[Option<usize>],
) {
    let renumber = |holder: &mut Value, key: &str, map: &[Option<usize>]| {
        let old = holder.get(key).and_then(Value::as_u64);
        if let Some(Some(new)) = old.and_then(|old| map.get(old as usize)) {
            holder[key] = json!(new);
        }
    };
    renumber(texture, "sampler", samplers);
    renumber(texture, "source", images);
    if let Some(extensions) = texture.get_mut("extensions").and_then(Value::as_object_mut) {
        for extension in extensions.values_mut() {
            renumber(extension, "source", images);
        }
    }
}
