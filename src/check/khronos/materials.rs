//! Textures and materials: references, texCoord sets and tangent needs recorded for the mesh
//! pass, and the Khronos material-extension rules.

use super::resources::declared_mime;
use crate::check::context::{member, number, unsigned, Context, MaterialNeeds, TexcoordNeed};
// Defined beside the context, which caches the slot uses; named here, where they are made.
pub(crate) use crate::check::context::{extension, SlotUse};
use crate::diagnostic::khronos;
use crate::document::{Node, Object};
use crate::gltf::as_index;
use crate::gltf::material::TEXTURE_SLOTS;
use crate::gltf::material::{effective_texcoord, texture_transform};
use std::collections::HashMap;
use std::sync::Arc;

pub(crate) fn check_textures(ctx: &mut Context) {
    for (_, pointer, texture) in ctx.objects("textures") {
        ctx.reference(texture, "sampler", &pointer, "samplers");
        if let Some(image) = ctx.reference(texture, "source", &pointer, "images") {
            check_texture_source_mime(
                ctx,
                image,
                &member(&pointer, "source"),
                &["image/jpeg", "image/png"],
            );
        }
        let mut sources = vec![("EXT_texture_webp", "image/webp")];
        if ctx.options.profile.knows_extensions_beyond_khronos() {
            sources.push(("KHR_texture_basisu", "image/ktx2"));
        }
        for (name, mime) in sources {
            let Some(holder) =
                (texture.get("extensions").and_then(|e| e.get(name))).filter(|h| h.is_object())
            else {
                continue;
            };
            let holder_pointer = format!("{pointer}/extensions/{name}");
            if let Some(image) = ctx.reference(holder, "source", &holder_pointer, "images") {
                check_texture_source_mime(ctx, image, &member(&holder_pointer, "source"), &[mime]);
            }
        }
    }
}

fn check_texture_source_mime(ctx: &mut Context, image: usize, pointer: &str, valid: &[&str]) {
    let declared = declared_mime(ctx.items("images").at(image)).or_else(|| {
        ctx.images[image]
            .as_ref()
            .map(|i| i.format.mime_type().to_string())
    });
    if let Some(mime) = declared.filter(|m| !valid.contains(&m.as_str())) {
        ctx.emit(
            khronos::TEXTURE_INVALID_IMAGE_MIME_TYPE,
            pointer,
            format!("Invalid MIME type '{mime}' for the texture source. Valid MIME types are {valid:?}."),
        );
    }
}

pub(crate) fn check_materials(ctx: &mut Context) {
    ctx.material_needs.clear();
    let as_written = std::mem::take(&mut ctx.extensions_as_written);
    for (i, pointer, material) in ctx.objects("materials") {
        let needs = texture_needs(ctx, material, &pointer);
        if needs != MaterialNeeds::default() {
            ctx.material_needs.insert(i, needs);
        }
        check_alpha_cutoff(ctx, material, &pointer);
        let written = as_written.get(&i).map_or(&[][..], Vec::as_slice);
        check_extension_rules(ctx, material, &pointer, written);
    }
}

/// The names in each material's `extensions` as the document writes them, for the materials
/// whose rules count their neighbours (a standalone extension, a volume): before undeclared
/// and mistyped ones are taken out, as the Khronos validator counts every member.
pub(crate) fn extensions_as_written(root: Node) -> HashMap<usize, Vec<String>> {
    let counted = [
        "KHR_materials_pbrSpecularGlossiness",
        "KHR_materials_unlit",
        "KHR_materials_volume",
    ];
    let materials = root.get("materials").and_then(Node::as_array);
    (materials.into_iter().flatten().enumerate())
        .filter_map(|(i, material)| {
            let extensions = material.get("extensions")?.as_object()?;
            counted
                .iter()
                .any(|name| extensions.contains_key(name))
                .then(|| (i, extensions.keys().map(str::to_string).collect()))
        })
        .collect()
}

fn texture_needs(ctx: &mut Context, material: Node, pointer: &str) -> MaterialNeeds {
    let mut needs = MaterialNeeds::default();
    for (at, slot) in TEXTURE_SLOTS.iter().enumerate() {
        let Some(info) = slot.lookup(material) else {
            continue;
        };
        let info_pointer = format!("{pointer}{}", slot.pointer());
        ctx.reference(info, "index", &info_pointer, "textures");
        // The Khronos validator checks both the binding's own set and a
        // KHR_texture_transform override, each under its own pointer.
        let need = |set, from_transform| TexcoordNeed {
            slot: at,
            from_transform,
            set,
        };
        // An invalid texCoord (reported by the schema pass) needs no set.
        let set = info.get("texCoord").map_or(Some(0), as_index);
        needs.texcoords.extend(set.map(|set| need(set, false)));
        if let Some(set) = texture_transform(info).and_then(|t| unsigned(t, "texCoord")) {
            needs.texcoords.push(need(set, true));
        }
        if slot.is_normal() || slot.key == "anisotropyTexture" {
            needs.needs_tangent = true;
        }
    }
    needs.can_generate_tangent = material.get("normalTexture").is_some_and(Node::is_object);
    needs.anisotropy = extension(material, "KHR_materials_anisotropy").is_some();
    if ctx.options.profile.reads_bindings_in_unknown_extensions() {
        read_unknown_bindings(ctx, material, &mut needs);
    }
    needs
}

/// The texture bindings inside the material's declared extensions that the profile does not
/// read: a member named `…Texture` holding an `index`, at any depth, as glTF names every
/// binding. Each marks its texture used and its texCoord sets read; an index that names
/// nothing is not reported, since the extension's own rules are unknown.
fn read_unknown_bindings(ctx: &mut Context, material: Node, needs: &mut MaterialNeeds) {
    let extensions = material.get("extensions").and_then(Node::as_object);
    let mut pending: Vec<Node> = (extensions.into_iter().flat_map(|e| e.iter()))
        .filter(|&(name, _)| ctx.uses_extension(name) && !super::extensions::knows(ctx, name))
        .map(|(_, object)| object)
        .collect();
    needs.unread_extension = !pending.is_empty();
    while let Some(node) = pending.pop() {
        if let Some(array) = node.as_array() {
            pending.extend(array.iter());
        }
        for (key, value) in node.as_object().into_iter().flat_map(|o| o.iter()) {
            let texture = (value.get("index").and_then(as_index))
                .filter(|&i| key.ends_with("Texture") && ctx.element("textures", i).is_some());
            if let Some(texture) = texture {
                ctx.mark_used("textures", texture as usize);
                let own = unsigned(value, "texCoord").or(Some(0));
                let transform = texture_transform(value).and_then(|t| unsigned(t, "texCoord"));
                for set in own.into_iter().chain(transform).filter(|&s| s < 64) {
                    needs.unread_sets |= 1 << set;
                }
            }
            pending.push(value);
        }
    }
}

fn check_alpha_cutoff(ctx: &mut Context, material: Node, pointer: &str) {
    let mode = material
        .get("alphaMode")
        .and_then(Node::as_str)
        .unwrap_or("OPAQUE");
    if material.get("alphaCutoff").is_some() && mode != "MASK" {
        ctx.emit(
            khronos::MATERIAL_ALPHA_CUTOFF_INVALID_MODE,
            member(pointer, "alphaCutoff"),
            "Alpha cutoff is supported only for 'MASK' alpha mode.",
        );
    }
}

/// `written`: the names of the material's extension objects as the document wrote them, where
/// the profile counts them all as the Khronos validator does (an undeclared or mistyped one is
/// out of the document by now); empty otherwise.
fn check_extension_rules(ctx: &mut Context, material: Node, pointer: &str, written: &[String]) {
    let Some(extensions) = material.get("extensions").and_then(Node::as_object) else {
        return;
    };
    let at = |name: &str| format!("{pointer}/extensions/{name}");
    check_standalone_extensions(ctx, extensions, written, at);
    check_emissive_strength(ctx, material, at);
    check_volume(ctx, material, extensions, written, at);
    if extension(material, "KHR_materials_dispersion").is_some()
        && !extensions.contains_key("KHR_materials_volume")
    {
        ctx.emit(
            khronos::KHR_MATERIALS_DISPERSION_NO_VOLUME,
            at("KHR_materials_dispersion"),
            "The dispersion extension needs to be combined with the volume extension.",
        );
    }
    check_iridescence(ctx, material, at);
    check_texcoord_pairs(ctx, material, pointer);
}

/// Spec-gloss and unlit replace the material's model: beside any other extension object.
fn check_standalone_extensions(
    ctx: &mut Context,
    extensions: Object,
    written: &[String],
    at: impl Fn(&str) -> String,
) {
    for standalone in ["KHR_materials_pbrSpecularGlossiness", "KHR_materials_unlit"] {
        let count = extensions.len().max(written.len());
        if extensions.contains_key(standalone) && count > 1 {
            ctx.emit(
                khronos::MULTIPLE_EXTENSIONS,
                at(standalone),
                "This extension may be incompatible with other extensions for the object.",
            );
        }
    }
}

fn check_emissive_strength(ctx: &mut Context, material: Node, at: impl Fn(&str) -> String) {
    let strength = extension(material, "KHR_materials_emissive_strength")
        .and_then(|e| e.get("emissiveStrength"));
    if !strength.and_then(Node::as_f64).is_some_and(|s| s >= 0.0) {
        return;
    }
    // Absent is black; an invalid factor (reported by the schema pass) is no colour.
    let zero = material.get("emissiveFactor").is_none_or(|factor| {
        factor
            .as_array()
            .is_some_and(|f| f.len() == 3 && f.iter().all(|c| c.as_f64() == Some(0.0)))
    });
    if zero {
        ctx.emit(
            khronos::KHR_MATERIALS_EMISSIVE_STRENGTH_ZERO_FACTOR,
            at("KHR_materials_emissive_strength"),
            "Emissive strength has no effect when the emissive factor is zero or undefined.",
        );
    }
}

fn check_volume(
    ctx: &mut Context,
    material: Node,
    extensions: Object,
    written: &[String],
    at: impl Fn(&str) -> String,
) {
    let Some(volume) = extension(material, "KHR_materials_volume") else {
        return;
    };
    // An extension this validator does not know may well be the one that transmits.
    let transmits = extensions
        .keys()
        .chain(written.iter().map(String::as_str))
        .any(|name| {
            matches!(
                name,
                "KHR_materials_transmission" | "KHR_materials_diffuse_transmission"
            ) || !name.starts_with("KHR_materials_")
        });
    if !transmits {
        ctx.emit(
            khronos::KHR_MATERIALS_VOLUME_NO_TRANSMISSION,
            at("KHR_materials_volume"),
            "The volume extension needs to be combined with an extension that allows light to transmit through the surface.",
        );
    }
    let thick = number(volume, "thicknessFactor", 0.0) > 0.0;
    if thick && material.get("doubleSided").and_then(Node::as_bool) == Some(true) {
        ctx.emit(
            khronos::KHR_MATERIALS_VOLUME_DOUBLE_SIDED,
            at("KHR_materials_volume"),
            "The volume extension should not be used with double-sided materials.",
        );
    }
}

fn check_iridescence(ctx: &mut Context, material: Node, at: impl Fn(&str) -> String) {
    let Some(iridescence) = extension(material, "KHR_materials_iridescence") else {
        return;
    };
    let p = at("KHR_materials_iridescence");
    let has_texture = iridescence.get("iridescenceThicknessTexture").is_some();
    if iridescence.get("iridescenceThicknessMinimum").is_some() && !has_texture {
        ctx.emit(
            khronos::KHR_MATERIALS_IRIDESCENCE_THICKNESS_RANGE_WITHOUT_TEXTURE,
            member(&p, "iridescenceThicknessMinimum"),
            "Thickness minimum has no effect when a thickness texture is not defined.",
        );
    }
    let min = number(iridescence, "iridescenceThicknessMinimum", 100.0);
    let max = number(iridescence, "iridescenceThicknessMaximum", 400.0);
    if has_texture && min == max {
        ctx.emit(
            khronos::KHR_MATERIALS_IRIDESCENCE_THICKNESS_TEXTURE_UNUSED,
            member(&p, "iridescenceThicknessTexture"),
            "Thickness texture has no effect when the thickness minimum is equal to the thickness maximum.",
        );
    }
}

/// Normal and anisotropy / clearcoat-normal textures should share texCoords. The Khronos
/// validator compares the raw `texCoord`; gltfmat's default profile applies the
/// KHR_texture_transform override, which is what a renderer samples.
fn check_texcoord_pairs(ctx: &mut Context, material: Node, pointer: &str) {
    let Some(normal) = material.get("normalTexture").filter(|n| n.is_object()) else {
        return;
    };
    let transformed = ctx.options.profile.reads_texcoord_override();
    // An invalid texCoord (none here) is a set of its own, as the validator's -1.
    let texcoord = |info: Node| {
        if transformed {
            Some(effective_texcoord(info))
        } else {
            info.get("texCoord").map_or(Some(0), as_index)
        }
    };
    let pairs = [
        (
            "KHR_materials_anisotropy",
            "anisotropyTexture",
            khronos::KHR_MATERIALS_ANISOTROPY_ANISOTROPY_TEXTURE_TEXCOORD,
            "Normal and anisotropy textures should use the same texture coords.",
        ),
        (
            "KHR_materials_clearcoat",
            "clearcoatNormalTexture",
            khronos::KHR_MATERIALS_CLEARCOAT_CLEARCOAT_NORMAL_TEXTURE_TEXCOORD,
            "Normal and clearcoat normal textures should use the same texture coords.",
        ),
    ];
    let normal_set = texcoord(normal);
    for (ext, key, code, message) in pairs {
        let Some(info) = extension(material, ext)
            .and_then(|e| e.get(key))
            .filter(|i| i.is_object())
        else {
            continue;
        };
        if texcoord(info) != normal_set {
            ctx.emit(code, format!("{pointer}/extensions/{ext}/{key}"), message);
        }
    }
}

/// Every resolvable texture binding in the document, in material and slot order.
/// Computed once per document (the rules share it); see [`collect_slot_uses`].
pub(crate) fn slot_uses<'a>(ctx: &Context<'a>) -> Arc<[SlotUse<'a>]> {
    ctx.slot_uses
        .get_or_init(|| collect_slot_uses(ctx).into())
        .clone()
}

/// The texture uses of each image, in document order: `by_image(uses, n)[i]` are the uses
/// that may sample image `i` (one pass over the uses, not one per image).
pub(crate) fn by_image<'u, 'a>(
    uses: &'u [SlotUse<'a>],
    image_count: usize,
) -> Vec<Vec<&'u SlotUse<'a>>> {
    let mut grouped: Vec<Vec<&SlotUse>> = vec![Vec::new(); image_count];
    for slot_use in uses {
        for image in slot_use.images() {
            // A texture may name one image twice (`source` and an extension's).
            let group = grouped.get_mut(image);
            if let Some(group) =
                group.filter(|g| !g.last().is_some_and(|&u| std::ptr::eq(u, slot_use)))
            {
                group.push(slot_use);
            }
        }
    }
    grouped
}

fn collect_slot_uses<'a>(ctx: &Context<'a>) -> Vec<SlotUse<'a>> {
    let textures = ctx.items("textures");
    let image_count = ctx.items("images").len();
    let mut uses = Vec::new();
    for (material_index, _, material) in ctx.objects("materials") {
        for slot in TEXTURE_SLOTS {
            let Some(info) = slot.lookup(material) else {
                continue;
            };
            let texture = unsigned(info, "index").and_then(|i| textures.get(i as usize));
            let Some(texture) = texture else {
                continue;
            };
            uses.push(SlotUse {
                material,
                material_index,
                slot,
                texture,
                image_count,
            });
        }
    }
    uses
}
