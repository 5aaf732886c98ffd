//! Extension declarations and placement: extensionsUsed / extensionsRequired consistency,
//! extension objects on hosts that do not take them, and non-object extras.

use crate::check::context::{member, Context};
use crate::diagnostic::khronos;
use crate::document::{Node, StringId, Tree};
use crate::gltf::material::TEXTURE_SLOTS;
use hashbrown::HashSet;

/// Extensions the Khronos validator implements, with the objects that may carry them.
const KHRONOS_SUPPORTED: &[(&str, &[Host])] = &[
    ("EXT_texture_webp", &[Host::Texture]),
    ("KHR_animation_pointer", &[Host::ChannelTarget]),
    ("KHR_lights_punctual", &[Host::Root, Host::Node]),
    ("KHR_materials_anisotropy", &[Host::Material]),
    ("KHR_materials_clearcoat", &[Host::Material]),
    ("KHR_materials_dispersion", &[Host::Material]),
    ("KHR_materials_emissive_strength", &[Host::Material]),
    ("KHR_materials_ior", &[Host::Material]),
    ("KHR_materials_iridescence", &[Host::Material]),
    ("KHR_materials_pbrSpecularGlossiness", &[Host::Material]),
    ("KHR_materials_sheen", &[Host::Material]),
    ("KHR_materials_specular", &[Host::Material]),
    ("KHR_materials_transmission", &[Host::Material]),
    ("KHR_materials_unlit", &[Host::Material]),
    ("KHR_materials_variants", &[Host::Root, Host::Primitive]),
    ("KHR_materials_volume", &[Host::Material]),
    ("KHR_mesh_quantization", &[]),
    ("KHR_texture_transform", &[Host::TextureInfo]),
];

/// Extensions gltfmat validates beyond the released Khronos validator's list (default profile
/// only): 2.0.0-dev.3.10 reports these UNSUPPORTED_EXTENSION (KHR_node_visibility came in a
/// later build).
const GLTFMAT_SUPPORTED: &[(&str, &[Host])] = &[
    ("KHR_materials_diffuse_transmission", &[Host::Material]),
    ("KHR_node_visibility", &[Host::Node]),
    ("KHR_texture_basisu", &[Host::Texture]),
];

/// The kinds of object that can carry `extensions`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Host {
    Root,
    Other,
    Material,
    TextureInfo,
    Texture,
    Primitive,
    Node,
    ChannelTarget,
}

/// Members of each host holding child objects: (key, child host, is array).
fn children(host: Host) -> &'static [(&'static str, Host, bool)] {
    match host {
        Host::Root => &[
            ("asset", Host::Other, false),
            ("accessors", Host::Other, true),
            ("animations", Host::Other, true),
            ("buffers", Host::Other, true),
            ("bufferViews", Host::Other, true),
            ("cameras", Host::Other, true),
            ("images", Host::Other, true),
            ("materials", Host::Material, true),
            ("meshes", Host::Other, true),
            ("nodes", Host::Node, true),
            ("samplers", Host::Other, true),
            ("scenes", Host::Other, true),
            ("skins", Host::Other, true),
            ("textures", Host::Texture, true),
        ],
        Host::Material => &[("pbrMetallicRoughness", Host::Other, false)],
        _ => &[],
    }
}

/// Second-level members that are plain objects (so their extensions and extras are seen).
fn nested(collection: &str) -> &'static [&'static str] {
    match collection {
        "accessors" => &["sparse"],
        "animations" => &["channels", "samplers"],
        "cameras" => &["perspective", "orthographic"],
        "meshes" => &["primitives"],
        _ => &[],
    }
}

pub(super) fn check(ctx: &mut Context) {
    check_declarations(ctx);
    report_undeclared(ctx, |_| true);
    let root = ctx.root;
    walk(root, "", Host::Root, &mut |object, pointer, host| {
        visit(ctx, object, pointer, host)
    });
}

/// The extension objects on the objects the Khronos validator reads extensions on whose
/// names `declared` does not hold (it reports them, and reads nothing in them).
pub(crate) fn undeclared_extensions(root: Node, declared: &HashSet<&str>) -> Undeclared {
    let mut found = Undeclared::default();
    walk(root, "", Host::Root, &mut |object, pointer, _| {
        let extensions = object.get("extensions").and_then(Node::as_object);
        let names = extensions.into_iter().flat_map(|e| e.keys_with_ids());
        let mut host = None;
        for (id, _) in names.filter(|(_, name)| !declared.contains(name)) {
            let host = *host.get_or_insert_with(|| {
                found.hosts.push(member(pointer, "extensions"));
                found.hosts.len() - 1
            });
            found.members.push((host, id));
        }
    });
    found
}

/// Undeclared extension objects, each as the object holding it and its name's id in the
/// tree: 10^6 of them on one node are 10^6 pairs, not 10^6 pointers.
#[derive(Debug, Default)]
pub(crate) struct Undeclared {
    /// The `extensions` objects holding them, by pointer.
    hosts: Vec<String>,
    /// Each one's host (an index into `hosts`) and name.
    members: Vec<(usize, StringId)>,
}

impl Undeclared {
    /// How many there are.
    pub(crate) fn len(&self) -> usize {
        self.members.len()
    }

    /// The pointer of the `i`th (`tree` is the one they were found in).
    pub(crate) fn pointer(&self, i: usize, tree: &Tree) -> String {
        let (host, name) = self.members[i];
        member(&self.hosts[host], tree.text(name))
    }

    /// Keeps only those whose `extensions` object `kept` accepts (by its pointer).
    pub(crate) fn retain_hosts(&mut self, kept: impl Fn(&str) -> bool) {
        let hosts = &self.hosts;
        self.members.retain(|&(host, _)| kept(&hosts[host]));
    }

    /// Takes out of `tree` those whose value `taken` accepts.
    pub(crate) fn remove_where(&self, tree: &mut Tree, mut taken: impl FnMut(Node) -> bool) {
        // Found host by host: each host's members are one run.
        for run in self.members.chunk_by(|a, b| a.0 == b.0) {
            let names = run.iter().map(|&(_, name)| name);
            tree.remove_members(&self.hosts[run[0].0], names, &mut taken);
        }
    }

    /// The pointers of the `extensions` objects holding some.
    pub(crate) fn hosts(&self) -> impl Iterator<Item = &str> {
        self.hosts.iter().map(String::as_str)
    }

    /// Their pointers, made one at a time.
    pub(crate) fn pointers<'a>(&'a self, tree: &'a Tree) -> impl Iterator<Item = String> + 'a {
        (0..self.len()).map(|i| self.pointer(i, tree))
    }
}

/// Reports the extension objects no `extensionsUsed` declares, at the pointers `reported`
/// keeps. They were taken out of the document before the passes, as the Khronos validator
/// reads nothing of them; said here, where it says it.
pub(crate) fn report_undeclared(ctx: &mut Context, reported: impl Fn(&str) -> bool) {
    let found = std::mem::take(&mut ctx.undeclared_extensions);
    for pointer in found.pointers(ctx.root.tree()).filter(|p| reported(p)) {
        undeclared(ctx, &pointer);
    }
    // Still members of their objects for the passes that ask whether an object has any.
    ctx.undeclared_extensions = found;
}

fn undeclared(ctx: &mut Context, pointer: &str) {
    ctx.emit(
        khronos::UNDECLARED_EXTENSION,
        pointer,
        "Extension is not declared in extensionsUsed.",
    );
}

/// Whether the released Khronos validator implements extension `name` (none of which it
/// lets an image carry).
pub(crate) fn khronos_knows(name: &str) -> bool {
    KHRONOS_SUPPORTED.iter().any(|(n, _)| *n == name)
}

/// Whether the profile validates extension `name`.
pub(crate) fn knows(ctx: &Context, name: &str) -> bool {
    supported(ctx, name).is_some()
}

fn supported(ctx: &Context, name: &str) -> Option<&'static [Host]> {
    let gltfmat = if ctx.options.profile.knows_extensions_beyond_khronos() {
        GLTFMAT_SUPPORTED
    } else {
        &[][..]
    };
    KHRONOS_SUPPORTED
        .iter()
        .chain(gltfmat)
        .find(|(n, _)| *n == name)
        .map(|(_, hosts)| *hosts)
}

fn valid_name(name: &str) -> bool {
    let Some((prefix, rest)) = name.split_once('_') else {
        return false;
    };
    !prefix.is_empty()
        && prefix
            .chars()
            .all(|c| c.is_ascii_uppercase() || c.is_ascii_digit())
        && !rest.is_empty()
        && rest.chars().all(|c| c.is_ascii_alphanumeric() || c == '_')
}

/// Extensions a loader cannot ignore: using one without requiring it is an error.
const MUST_BE_REQUIRED: &[&str] = &["KHR_mesh_quantization"];

/// `extensionsUsed` and `extensionsRequired`: names, support, and what must be required.
pub(crate) fn check_declarations(ctx: &mut Context) {
    let required: Vec<&str> = ctx
        .items("extensionsRequired")
        .iter()
        .filter_map(Node::as_str)
        .collect();
    for (i, value) in ctx.items("extensionsUsed").iter().enumerate() {
        let Some(name) = value.as_str() else { continue };
        let pointer = format!("/extensionsUsed/{i}");
        if !valid_name(name) {
            ctx.emit(
                khronos::INVALID_EXTENSION_NAME_FORMAT,
                pointer.clone(),
                "Extension name has invalid format.",
            );
        }
        if supported(ctx, name).is_none() {
            ctx.emit(
                khronos::UNSUPPORTED_EXTENSION,
                pointer.clone(),
                format!("Cannot validate an extension as it is not supported by the validator: '{name}'."),
            );
        }
        if MUST_BE_REQUIRED.contains(&name) && !required.contains(&name) {
            ctx.emit(
                khronos::NON_REQUIRED_EXTENSION,
                pointer,
                format!("Extension '{name}' cannot be optional."),
            );
        }
    }
    for (i, value) in ctx.items("extensionsRequired").iter().enumerate() {
        let Some(name) = value.as_str() else { continue };
        if !ctx.uses_extension(name) {
            ctx.emit(
                khronos::UNUSED_EXTENSION_REQUIRED,
                format!("/extensionsRequired/{i}"),
                format!("Unused extension '{name}' cannot be required."),
            );
        }
    }
}

/// The extras and the extension objects of one object the validator reads them on.
fn visit(ctx: &mut Context, object: Node, pointer: &str, host: Host) {
    let Some(map) = object.as_object() else {
        return;
    };
    if let Some(extras) = map.get("extras") {
        if !extras.is_object() && !extras.is_null() {
            ctx.emit(
                khronos::NON_OBJECT_EXTRAS,
                member(pointer, "extras"),
                "Prefer JSON Objects for extras.",
            );
        }
    }
    if let Some(extensions) = map.get("extensions").and_then(Node::as_object) {
        for (name, value) in extensions {
            visit_extension(
                ctx,
                name,
                value,
                &member(&member(pointer, "extensions"), name),
                host,
            );
        }
    }
}

/// Calls `each` on `object` and every object below it that the Khronos validator reads
/// `extensions` and `extras` on (outside extension objects), with its pointer and host,
/// in document order.
fn walk(object: Node, pointer: &str, host: Host, each: &mut dyn FnMut(Node, &str, Host)) {
    let Some(map) = object.as_object() else {
        return;
    };
    each(object, pointer, host);
    for (key, child_host, is_array) in children(host) {
        let child_pointer = member(pointer, key);
        match map.get(key) {
            Some(items) if *is_array && items.is_array() => {
                for (i, item) in items.as_array().into_iter().flatten().enumerate() {
                    let item_pointer = format!("{child_pointer}/{i}");
                    walk(item, &item_pointer, *child_host, each);
                    walk_nested(key, item, &item_pointer, each);
                }
            }
            Some(child) if !is_array => walk(child, &child_pointer, *child_host, each),
            _ => {}
        }
    }
    if host == Host::Material {
        for slot in TEXTURE_SLOTS.iter().filter(|s| s.extension.is_none()) {
            if let Some(info) = slot.lookup(object) {
                let info_pointer = format!("{pointer}{}", slot.pointer());
                walk(info, &info_pointer, Host::TextureInfo, each);
            }
        }
    }
}

fn walk_nested(
    collection: &str,
    item: Node,
    pointer: &str,
    each: &mut dyn FnMut(Node, &str, Host),
) {
    for key in nested(collection) {
        let child_pointer = member(pointer, key);
        match item.get(*key) {
            Some(items) if items.is_array() => {
                for (i, child) in items.as_array().into_iter().flatten().enumerate() {
                    let host = if *key == "primitives" {
                        Host::Primitive
                    } else {
                        Host::Other
                    };
                    let p = format!("{child_pointer}/{i}");
                    walk(child, &p, host, each);
                    if *key == "channels" {
                        if let Some(target) = child.get("target") {
                            walk(target, &member(&p, "target"), Host::ChannelTarget, each);
                        }
                    }
                }
            }
            Some(child) => {
                walk(child, &child_pointer, Host::Other, each);
                // A sparse accessor's indices and values are objects of their own.
                for part in SPARSE_PARTS.iter().filter(|_| *key == "sparse") {
                    if let Some(object) = child.get(part) {
                        walk(object, &member(&child_pointer, part), Host::Other, each);
                    }
                }
            }
            None => {}
        }
    }
}

const SPARSE_PARTS: [&str; 2] = ["indices", "values"];

/// The objects inside an extension object that the validator reads as glTF properties,
/// their extras and extensions checked: (extension, its host, the array holding them, a
/// member of each that is an object of its own).
const INNER_OBJECTS: &[(&str, Host, &str, Option<&str>)] = &[
    ("KHR_lights_punctual", Host::Root, "lights", Some("spot")),
    ("KHR_materials_variants", Host::Root, "variants", None),
    ("KHR_materials_variants", Host::Primitive, "mappings", None),
];

fn visit_extension(ctx: &mut Context, name: &str, value: Node, pointer: &str, host: Host) {
    if !ctx.uses_extension(name) {
        undeclared(ctx, pointer);
    }
    let Some(hosts) = supported(ctx, name) else {
        return;
    };
    if !hosts.contains(&host) {
        ctx.emit(
            khronos::UNEXPECTED_EXTENSION_OBJECT,
            pointer,
            format!("Unexpected location for this extension object ({name})."),
        );
        return;
    }
    if value.get("extras").is_some_and(|e| !e.is_object()) {
        ctx.emit(
            khronos::NON_OBJECT_EXTRAS,
            member(pointer, "extras"),
            "Prefer JSON Objects for extras.",
        );
    }
    let inner = INNER_OBJECTS
        .iter()
        .filter(|(n, h, ..)| *n == name && *h == host);
    for &(_, _, list, part) in inner {
        let objects = value.get(list).and_then(Node::as_array);
        for (i, object) in objects.into_iter().flatten().enumerate() {
            let at = member(&member(pointer, list), &i.to_string());
            if let Some((key, part)) = part.and_then(|key| Some((key, object.get(key)?))) {
                visit(ctx, part, &member(&at, key), Host::Other);
            }
            visit(ctx, object, &at, Host::Other);
        }
    }
    for slot in TEXTURE_SLOTS.iter().filter(|s| s.extension == Some(name)) {
        if let Some(info) = value.get(slot.key) {
            walk(
                info,
                &member(pointer, slot.key),
                Host::TextureInfo,
                &mut |o, p, h| visit(ctx, o, p, h),
            );
        }
    }
}
