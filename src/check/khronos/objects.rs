//! Asset version, accessors, meshes, nodes, scenes, skins, animations and cameras: references
//! and the structural rules a material checker depends on (texCoords, tangent space).

use super::primitives::indexed_sets;
use super::resources::fits_in_view;
use crate::check::context::{elements, member, unsigned, Context, MaterialNeeds};
use crate::diagnostic::{khronos, Code, Diagnostic, Sink};
use crate::document::uri::has_stray_bits;
use crate::document::{Array, Node, Object, Tree};
use crate::gltf::accessor::{component_count, component_size, element_lengths};
use crate::gltf::gl;
use crate::gltf::{as_index, COLLECTIONS};
use std::collections::{BTreeSet, HashSet};

fn version(text: &str) -> Option<(u64, u64)> {
    let (major, minor) = text.split_once('.')?;
    Some((major.parse().ok()?, minor.parse().ok()?))
}

/// Whether `asset.version` says glTF 2.x: the other passes assume it.
pub(crate) fn has_supported_version(root: Node) -> bool {
    root.get("asset")
        .and_then(|a| a.get("version"))
        .and_then(Node::as_str)
        .and_then(version)
        .is_some_and(|(major, _)| major == 2)
}

/// Which schema findings of a document whose `asset` is missing or not 2.x the Khronos
/// validator gives: it reads the root's members, the extension lists and `asset`, then
/// stops. So: unexpected root members, anything of `extensionsUsed` / `extensionsRequired`,
/// anything inside `asset`, and, when it is missing, the root's one missing member (the
/// root schema requires `asset` alone).
pub(crate) fn read_before_asset(root: Node) -> impl Fn(&Diagnostic) -> bool {
    let missing = root.get("asset").is_none();
    move |diagnostic| {
        let Some(pointer) = diagnostic.pointer() else {
            return false;
        };
        let under = |member: &str| {
            pointer == member
                || pointer
                    .strip_prefix(member)
                    .is_some_and(|r| r.starts_with('/'))
        };
        let root_member = pointer.len() > 1 && !pointer[1..].contains('/');
        match diagnostic.code {
            _ if under("/asset") || under("/extensionsUsed") || under("/extensionsRequired") => {
                true
            }
            khronos::UNEXPECTED_PROPERTY => root_member,
            khronos::UNDEFINED_PROPERTY => missing && matches!(pointer, "" | "/"),
            _ => false,
        }
    }
}

/// Where the Khronos validator stops reading a glTF 2.x document: at the first buffer, then
/// image, whose data URI ends in bits past its data ([`has_stray_bits`]), which its base64
/// decoder refuses as a failure of the whole file (INVALID_JSON).
pub(crate) fn stops_at_data_uri(root: Node) -> Option<(&'static str, usize)> {
    ["buffers", "images"].into_iter().find_map(|collection| {
        let elements = root.get(collection)?.as_array()?;
        let stray = |e: Node| {
            e.get("uri")
                .and_then(Node::as_str)
                .is_some_and(has_stray_bits)
        };
        let index = elements.iter().position(stray)?;
        Some((collection, index))
    })
}

/// Whether the Khronos validator gives a finding of `code` at `pointer` (the schema's, an
/// undeclared extension's) before it stops at the data URI of
/// `/collection/index` ([`stops_at_data_uri`]): unexpected root members, the extension
/// lists and `asset`, the collections it reads first (see [`COLLECTIONS`]) and the
/// elements before; of that element, its unexpected members, a missing byteLength and the
/// members read before the uri (a buffer's byteLength, an image's bufferView and mimeType).
pub(crate) fn read_before_data_uri(
    (collection, index): (&'static str, usize),
    code: Code,
    pointer: &str,
) -> bool {
    let mut segments = pointer.split('/').skip(1);
    let member = segments.next().unwrap_or_default();
    let before = COLLECTIONS.iter().take_while(|c| **c != collection);
    if matches!(member, "asset" | "extensionsUsed" | "extensionsRequired")
        || before.into_iter().any(|c| *c == member)
    {
        return true;
    }
    let Some(element) = segments.next() else {
        return code == khronos::UNEXPECTED_PROPERTY;
    };
    if member != collection {
        return false;
    }
    let read_first: &[&str] = match collection {
        "buffers" => &["byteLength"],
        _ => &["bufferView", "mimeType"],
    };
    let inside = segments.next();
    match (element.parse::<usize>().map(|i| i.cmp(&index)), inside) {
        (Ok(std::cmp::Ordering::Less), _) => true,
        (Ok(std::cmp::Ordering::Equal), None) => code == khronos::UNDEFINED_PROPERTY,
        (Ok(std::cmp::Ordering::Equal), Some(inside)) => {
            read_first.contains(&inside)
                || (segments.next().is_none() && code == khronos::UNEXPECTED_PROPERTY)
        }
        _ => false,
    }
}

/// The `asset` object: version and minVersion (run alone when the version is not 2.x).
pub(crate) fn check_asset(ctx: &mut Context) {
    let Some(asset) = ctx.root.get("asset") else {
        return;
    };
    let Some((major, minor)) = asset
        .get("version")
        .and_then(Node::as_str)
        .and_then(version)
    else {
        return;
    };
    if major != 2 {
        // (The default profile checks a 1.0 document as such: GLTF_1_0_ASSET says to upgrade.)
        ctx.emit(
            khronos::UNKNOWN_ASSET_MAJOR_VERSION,
            "/asset/version",
            format!("Unknown glTF major asset version: {major}."),
        );
    } else if minor > 0 {
        ctx.emit(
            khronos::UNKNOWN_ASSET_MINOR_VERSION,
            "/asset/version",
            format!("Unknown glTF minor asset version: {minor}."),
        );
    }
    if let Some((min_major, min_minor)) = asset
        .get("minVersion")
        .and_then(Node::as_str)
        .and_then(version)
    {
        if (min_major, min_minor) > (major, minor) {
            ctx.emit(
                khronos::ASSET_MIN_VERSION_GREATER_THAN_VERSION,
                "/asset/minVersion",
                format!("Asset minVersion '{min_major}.{min_minor}' is greater than version '{major}.{minor}'."),
            );
        }
    }
}

pub(super) fn check_accessors(ctx: &mut Context) {
    for (_, pointer, accessor) in ctx.objects("accessors") {
        check_accessor_format(ctx, accessor, &pointer);
        if !is_linked(accessor) {
            continue;
        }
        if let Some(view) = ctx.reference(accessor, "bufferView", &pointer, "bufferViews") {
            check_accessor_fits(ctx, accessor, view, &pointer);
        }
        super::sparse::check_structure(ctx, accessor, &pointer);
    }
}

/// Whether the Khronos validator links the accessor to its bufferView and sparse parts: only
/// with a valid componentType, a count and a type (any string). Otherwise its bufferView is
/// neither resolved nor used by it.
pub(super) fn is_linked(accessor: Node) -> bool {
    unsigned(accessor, "componentType").is_some_and(|c| component_size(c).is_some())
        && unsigned(accessor, "count").is_some_and(|n| n >= 1)
        && accessor.get("type").is_some_and(Node::is_string)
}

/// Takes out of the tree the accessors' `min` and `max` that the Khronos validator does not
/// read: all of them when the accessor's `type` or `componentType` is not a valid one
/// (nothing is reported),
/// and one whose length is not the type's component count (reported here, as the only
/// finding about that array).
pub(crate) fn take_unread_bounds(tree: &mut Tree, sink: &mut dyn Sink) {
    let mut unread = Vec::new();
    let accessors = tree.root().get("accessors").and_then(Node::as_array);
    for (i, accessor) in accessors.into_iter().flatten().enumerate() {
        if !accessor.is_object() {
            continue;
        }
        let component_type = accessor.get("componentType").and_then(Node::as_u64);
        // Bounds are read as a list of the component type's values for the type's count of
        // components: under an invalid type or component type they are not read at all.
        let components = (accessor.get("type").and_then(Node::as_str))
            .and_then(component_count)
            .filter(|_| component_type.and_then(component_size).is_some());
        let integer_range = component_type.and_then(gl::integer_range);
        for key in ["min", "max"] {
            let Some(bounds) = accessor.get(key) else {
                continue;
            };
            let length = bounds.as_array().map(Array::len);
            match (components, length) {
                (None, _) => {}
                // Empty float bounds are empty to the validator; integer ones (read as a
                // list of integers first) are of a wrong length.
                (Some(_), Some(0)) if integer_range.is_none() => sink.push(Diagnostic::at(
                    khronos::EMPTY_ENTITY,
                    format!("/accessors/{i}/{key}"),
                    "Entity cannot be empty.",
                )),
                (Some(n), Some(length)) if length != n => sink.push(Diagnostic::at(
                    khronos::ARRAY_LENGTH_NOT_IN_LIST,
                    format!("/accessors/{i}/{key}"),
                    format!("Invalid array length {length}. Valid lengths are: ({n})."),
                )),
                _ if integer_range.is_some_and(|range| !holds(range, bounds, key, i, sink)) => {}
                _ => continue,
            }
            unread.push(format!("/accessors/{i}/{key}"));
        }
    }
    for pointer in unread {
        tree.remove(&pointer);
    }
}

/// Takes out of the tree each accessor's `byteOffset` whose `bufferView` is no index (absent,
/// mistyped or negative): the Khronos validator then reads no byteOffset and reports only that
/// it needs a bufferView (reported here, as the only finding about it).
pub(crate) fn take_unread_offsets(tree: &mut Tree, sink: &mut dyn Sink) {
    let mut unread = Vec::new();
    let accessors = tree.root().get("accessors").and_then(Node::as_array);
    for (i, accessor) in accessors.into_iter().flatten().enumerate() {
        let view = accessor.get("bufferView").and_then(as_index);
        if accessor.get("byteOffset").is_none() || view.is_some() {
            continue;
        }
        let pointer = format!("/accessors/{i}/byteOffset");
        sink.push(Diagnostic::at(
            khronos::UNSATISFIED_DEPENDENCY,
            pointer.clone(),
            "Dependency failed. 'bufferView' must be defined.",
        ));
        unread.push(pointer);
    }
    for pointer in unread {
        tree.remove(&pointer);
    }
}

/// Takes out of the tree the camera projections the Khronos validator does not read: it
/// reads only the one `type` names (and reports a camera holding both, reported here as the
/// only finding about the other one).
pub(crate) fn take_unread_projections(tree: &mut Tree, sink: &mut dyn Sink) {
    let mut unread = Vec::new();
    let cameras = tree.root().get("cameras").and_then(Node::as_array);
    for (i, camera) in cameras.into_iter().flatten().enumerate() {
        let kind = camera.get("type").and_then(Node::as_str);
        let keys = ["perspective", "orthographic"];
        if keys.iter().all(|key| camera.get(key).is_some()) {
            sink.push(Diagnostic::at(
                khronos::ONE_OF_MISMATCH,
                format!("/cameras/{i}"),
                "Exactly one of ('orthographic', 'perspective') properties must be defined.",
            ));
        }
        for key in keys {
            if camera.get(key).is_some() && kind != Some(key) {
                unread.push(format!("/cameras/{i}/{key}"));
            }
        }
    }
    for pointer in unread {
        tree.remove(&pointer);
    }
}

/// Takes out of the tree each accessor's `sparse` that the Khronos validator drops after
/// reporting what is wrong in it: one without a `count` of at least 1 or without `indices`
/// and `values` objects. Its views are then not used by it, and the accessor's data is read
/// without it.
pub(crate) fn take_unread_sparse(tree: &mut Tree) {
    let accessors = tree.root().get("accessors").and_then(Node::as_array);
    let unread: Vec<String> = (accessors.into_iter().flatten().enumerate())
        .filter(|(_, accessor)| {
            accessor.get("sparse").is_some_and(|sparse| {
                let object = |key| sparse.get(key).is_some_and(Node::is_object);
                !(unsigned(sparse, "count").is_some_and(|n| n >= 1)
                    && object("indices")
                    && object("values"))
            })
        })
        .map(|(i, _)| format!("/accessors/{i}/sparse"))
        .collect();
    for pointer in unread {
        tree.remove(&pointer);
    }
}

/// Whether every number of an integer accessor's bounds (`key`, `bounds`) is an integer its
/// component type (`range`: name, lowest, highest) can hold. Where one is not, the Khronos
/// validator does not read the array, and every element it could not take is reported here
/// in order (ARRAY_TYPE_MISMATCH for one that is no integer, INVALID_GL_VALUE for one out of
/// range); where all can, elements that are no number are the schema's to report.
fn holds(
    (name, lowest, highest): (&str, f64, f64),
    bounds: Node,
    key: &str,
    i: usize,
    sink: &mut dyn Sink,
) -> bool {
    let elements = || bounds.as_array().into_iter().flatten();
    let finding = |value: Node| match value.as_f64() {
        Some(number) if number.fract() == 0.0 && (lowest..=highest).contains(&number) => None,
        Some(number) if number.fract() == 0.0 => Some((
            khronos::INVALID_GL_VALUE,
            format!("Invalid value {value} for GL type '{name}'."),
        )),
        _ => Some((
            khronos::ARRAY_TYPE_MISMATCH,
            format!("Type mismatch. Array element {value} is not a 'integer'."),
        )),
    };
    let unread = elements().any(|v| v.as_f64().is_some() && finding(v).is_some());
    if !unread {
        return true;
    }
    for (code, message) in elements().filter_map(finding) {
        sink.push(Diagnostic::at(
            code,
            format!("/accessors/{i}/{key}"),
            message,
        ));
    }
    false
}

/// What an accessor's own members must agree on, whatever its bufferView.
fn check_accessor_format(ctx: &mut Context, accessor: Node, pointer: &str) {
    // A byteOffset without a bufferView index was reported and taken out before the passes
    // (see `take_unread_offsets`).
    let component_type = unsigned(accessor, "componentType");
    let normalized = accessor.get("normalized").and_then(Node::as_bool) == Some(true);
    if normalized && matches!(component_type, Some(gl::FLOAT | gl::UNSIGNED_INT)) {
        ctx.emit(
            khronos::ACCESSOR_NORMALIZED_INVALID,
            member(pointer, "normalized"),
            "Only (u)byte and (u)short accessors can be normalized.",
        );
    }
    let is_matrix = accessor
        .get("type")
        .and_then(Node::as_str)
        .is_some_and(|t| t.starts_with("MAT"));
    // Only an offset into a bufferView (resolved or not) is checked, as the validator does.
    let viewed = accessor.get("bufferView").is_some();
    if is_matrix && viewed && unsigned(accessor, "byteOffset").is_some_and(|o| o % 4 != 0) {
        ctx.emit(
            khronos::ACCESSOR_MATRIX_ALIGNMENT,
            member(pointer, "byteOffset"),
            "Matrix accessors must be aligned to 4-byte boundaries.",
        );
    }
}

/// The accessor inside its bufferView: stride, alignment of its own and total offset, and
/// ACCESSOR_TOO_LONG, the last element ending inside the view. Computed with checked
/// arithmetic, so a count of 2^31 or 2^64 − 1 is a finding, not an overflow.
fn check_accessor_fits(ctx: &mut Context, accessor: Node, view: usize, pointer: &str) {
    let Some(component_size) = unsigned(accessor, "componentType").and_then(component_size) else {
        return;
    };
    // A type the validator does not know (VALUE_NOT_IN_LIST) has no components: its
    // elements are 0 bytes long, and only the offsets and a stride can place it past the end.
    let Some(kind) = accessor.get("type").and_then(Node::as_str) else {
        return;
    };
    // A view without its byteLength (a schema error) is judged as holding nothing, as the
    // Khronos validator judges it (see `fits_in_view`).
    let Some(count) = unsigned(accessor, "count").filter(|c| *c > 0) else {
        return;
    };
    let (element, last) = element_lengths(kind, component_size);
    let view_object = ctx.items("bufferViews").at(view);
    let declared_stride = unsigned(view_object, "byteStride");
    // An element's data ends after its last column (the padding after it is never read): a
    // stride that reaches that far holds it, as the validator measures.
    if declared_stride.is_some_and(|s| s < last) {
        ctx.emit(
            khronos::ACCESSOR_SMALL_BYTESTRIDE,
            pointer,
            format!("Referenced bufferView's byteStride value {} is less than accessor element's length {last}.", declared_stride.unwrap_or_default()),
        );
    }
    let stride = declared_stride.unwrap_or(element);
    // An invalid byteOffset (not an absent one) places the accessor nowhere: the validator
    // checks neither its alignment nor its length.
    let written = accessor
        .get("byteOffset")
        .map(|_| unsigned(accessor, "byteOffset"));
    let Some(offset) = written.unwrap_or(Some(0)) else {
        return;
    };
    let length = (count - 1)
        .checked_mul(stride)
        .and_then(|n| n.checked_add(last));
    fits_in_view(ctx, pointer, view, offset, component_size as u64, length);
}

pub(super) fn check_meshes(ctx: &mut Context) {
    let variant_count = ctx
        .root
        .get("extensions")
        .and_then(|e| e.get("KHR_materials_variants"))
        .and_then(|v| v.get("variants"))
        .and_then(Node::as_array)
        .map_or(0, Array::len);
    for (_, pointer, mesh) in ctx.objects("meshes") {
        let Some(primitives) = mesh.get("primitives").and_then(Node::as_array) else {
            continue;
        };
        for (j, primitive) in primitives.iter().enumerate().filter(|(_, p)| p.is_object()) {
            let p = format!("{pointer}/primitives/{j}");
            check_primitive(ctx, primitive, &p, variant_count);
        }
    }
}

fn check_primitive(ctx: &mut Context, primitive: Node, pointer: &str, variant_count: usize) {
    let attributes = primitive.get("attributes").and_then(Node::as_object);
    reference_accessors(ctx, primitive, attributes, pointer);
    let has = |name: &str| attributes.is_some_and(|a| a.contains_key(name));
    let texcoord_sets = attributes.map_or(0, |a| indexed_sets(a, "TEXCOORD"));
    let mut texcoords_used = BTreeSet::new();
    let mut read_by = |ctx: &mut Context, material: usize, at: &str| {
        let needs = ctx
            .material_needs
            .get(&material)
            .cloned()
            .unwrap_or_default();
        read_texcoords(
            ctx,
            (material, &needs),
            at,
            texcoord_sets,
            &mut texcoords_used,
        );
        let mut unread = needs.unread_sets;
        while unread != 0 {
            texcoords_used.insert(u64::from(unread.trailing_zeros()));
            unread &= unread - 1;
        }
        needs
    };
    match ctx.reference(primitive, "material", pointer, "materials") {
        Some(material) => {
            let material_pointer = member(pointer, "material");
            let needs = read_by(ctx, material, &material_pointer);
            check_tangent_space(
                ctx,
                &needs,
                &material_pointer,
                has("NORMAL"),
                has("TANGENT"),
            );
            if has("TANGENT") && !needs.needs_tangent {
                unused_tangent(ctx, pointer);
            }
        }
        // No material, or one that does not resolve: nothing reads the tangents.
        None if has("TANGENT") => unused_tangent(ctx, pointer),
        None => {}
    }
    for (material, at) in check_variant_mappings(ctx, primitive, pointer, variant_count) {
        read_by(ctx, material, &at);
    }
    for set in (0..texcoord_sets).filter(|s| !texcoords_used.contains(s)) {
        ctx.emit(
            khronos::UNUSED_OBJECT,
            format!("{pointer}/attributes/TEXCOORD_{set}"),
            "This object may be unused.",
        );
    }
    if has("TANGENT") && !has("NORMAL") {
        ctx.emit(
            khronos::MESH_PRIMITIVE_TANGENT_WITHOUT_NORMAL,
            format!("{pointer}/attributes/TANGENT"),
            "TANGENT attribute without NORMAL found.",
        );
    }
}

/// The accessors a primitive names: its attributes', its morph targets' and its indices.
fn reference_accessors(
    ctx: &mut Context,
    primitive: Node,
    attributes: Option<Object>,
    pointer: &str,
) {
    for (name, value) in attributes.into_iter().flatten() {
        let at = member(&member(pointer, "attributes"), name);
        ctx.reference_value(value, &at, "accessors");
    }
    if let Some(targets) = super::primitives::morph_targets(primitive) {
        for (t, target) in targets.iter().enumerate() {
            for (name, value) in target.as_object().into_iter().flatten() {
                ctx.reference_value(value, &format!("{pointer}/targets/{t}/{name}"), "accessors");
            }
        }
    }
    ctx.reference(primitive, "indices", pointer, "accessors");
}

/// A material that needs a tangent space on a primitive without both NORMAL and TANGENT.
fn check_tangent_space(
    ctx: &mut Context,
    needs: &MaterialNeeds,
    material_pointer: &str,
    has_normal: bool,
    has_tangent: bool,
) {
    if !needs.needs_tangent || (has_normal && has_tangent) {
        return;
    }
    if needs.can_generate_tangent {
        ctx.emit(
            khronos::MESH_PRIMITIVE_GENERATED_TANGENT_SPACE,
            material_pointer,
            "Material requires a tangent space but the mesh primitive does not provide it. Runtime-generated tangent space may be non-portable across implementations.",
        );
    } else {
        ctx.emit(
            khronos::MESH_PRIMITIVE_NO_TANGENT_SPACE,
            material_pointer,
            "Material requires a tangent space but the mesh primitive does not provide it and the material does not contain a normal map to generate it.",
        );
    }
}

/// Marks the texCoord sets a material's bindings read as used, and reports each binding that
/// reads a set the primitive does not have (at `at`, the pointer to the material reference).
fn read_texcoords(
    ctx: &mut Context,
    (material, needs): (usize, &MaterialNeeds),
    at: &str,
    sets: u64,
    used: &mut BTreeSet<u64>,
) {
    for need in &needs.texcoords {
        if need.set < sets {
            used.insert(need.set);
        } else {
            ctx.emit(
                khronos::MESH_PRIMITIVE_TOO_FEW_TEXCOORDS,
                at,
                format!("Material is incompatible with mesh primitive: Texture binding '{}' needs 'TEXCOORD_{}' attribute.", need.binding(material), need.set),
            );
        }
    }
}

fn unused_tangent(ctx: &mut Context, pointer: &str) {
    ctx.emit(
        khronos::UNUSED_MESH_TANGENT,
        format!("{pointer}/attributes/TANGENT"),
        "Unused TANGENT attribute: the material does not need a tangent space.",
    );
}

/// Checks the KHR_materials_variants mappings; returns each mapped material with the
/// pointer to its reference.
fn check_variant_mappings(
    ctx: &mut Context,
    primitive: Node,
    pointer: &str,
    variant_count: usize,
) -> Vec<(usize, String)> {
    let mut mapped = Vec::new();
    let Some(ext) = primitive
        .get("extensions")
        .and_then(|e| e.get("KHR_materials_variants"))
    else {
        return mapped;
    };
    let Some(mappings) = ext.get("mappings").and_then(Node::as_array) else {
        return mapped;
    };
    let root_declares_variants = ctx
        .root
        .get("extensions")
        .and_then(|e| e.get("KHR_materials_variants"))
        .is_some();
    let mut seen = HashSet::new();
    for (m, mapping) in mappings.iter().enumerate().filter(|(_, m)| m.is_object()) {
        let mp = format!("{pointer}/extensions/KHR_materials_variants/mappings/{m}");
        if !root_declares_variants {
            ctx.emit(
                khronos::UNSATISFIED_DEPENDENCY,
                mp,
                "Dependency failed. The root KHR_materials_variants extension must define the variants.",
            );
            continue;
        }
        if let Some(material) = ctx.reference(mapping, "material", &mp, "materials") {
            mapped.push((material, member(&mp, "material")));
        }
        for (v, variant) in elements(mapping, "variants") {
            let vp = format!("{mp}/variants/{v}");
            let Some(index) = as_index(variant) else {
                continue;
            };
            if index as usize >= variant_count {
                ctx.emit(
                    khronos::UNRESOLVED_REFERENCE,
                    vp,
                    format!("Unresolved reference: {index}."),
                );
                continue;
            }
            ctx.mark_used("variants", index as usize);
            if !seen.insert(index) {
                ctx.emit(
                    khronos::KHR_MATERIALS_VARIANTS_NON_UNIQUE_VARIANT,
                    vp,
                    "This variant is used more than once for this mesh primitive.",
                );
            }
        }
    }
    mapped
}

pub(super) fn check_nodes_and_scenes(ctx: &mut Context) {
    let joints: HashSet<u64> = ctx
        .items("skins")
        .iter()
        .flat_map(|skin| elements(skin, "joints"))
        .filter_map(|(_, joint)| as_index(joint))
        .collect();
    // The nodes' `extensions` objects that held undeclared extensions.
    let hosting: HashSet<String> = (ctx.undeclared_extensions.hosts())
        .filter(|host| host.starts_with("/nodes/"))
        .map(str::to_string)
        .collect();
    for (index, pointer, node) in ctx.objects("nodes") {
        let mesh = ctx.reference(node, "mesh", &pointer, "meshes");
        let camera = ctx.reference(node, "camera", &pointer, "cameras");
        ctx.reference(node, "skin", &pointer, "skins");
        for (c, child) in elements(node, "children") {
            ctx.reference_value(child, &format!("{pointer}/children/{c}"), "nodes");
        }
        // As the Khronos validator sees it: a skin alone leaves a node empty; children,
        // even unresolved ones, do not; a name does not count (its gltf.dart ignores it, and
        // Blender writes named empty nodes).
        let has_children = node
            .get("children")
            .and_then(Node::as_array)
            .is_some_and(|c| !c.is_empty());
        let extras = node.get("extras").is_some_and(|e| !e.is_null());
        // Extensions as written: an empty object is none, an undeclared one (out of the
        // document by now) is one.
        let extensions = node.get("extensions").is_some_and(|e| {
            e.as_object().is_none_or(|e| !e.is_empty())
                || hosting.contains(member(&pointer, "extensions").as_str())
        });
        // A joint is not empty: skinning reads its transform.
        let empty = !joints.contains(&(index as u64))
            && mesh.is_none()
            && camera.is_none()
            && !has_children
            && !extensions
            && !extras;
        if empty {
            ctx.emit(
                khronos::NODE_EMPTY,
                pointer.clone(),
                "Empty node encountered.",
            );
        }
    }
    for (_, pointer, scene) in ctx.objects("scenes") {
        for (n, node) in elements(scene, "nodes") {
            ctx.reference_value(node, &format!("{pointer}/nodes/{n}"), "nodes");
        }
    }
    if let Some(scene) = ctx.root.get("scene") {
        ctx.reference_value(scene, "/scene", "scenes");
    }
}

pub(super) fn check_skins_animations_cameras(ctx: &mut Context) {
    for (_, pointer, skin) in ctx.objects("skins") {
        ctx.reference(skin, "inverseBindMatrices", &pointer, "accessors");
        if let Some(skeleton) = skin.get("skeleton") {
            ctx.resolve(skeleton, &member(&pointer, "skeleton"), "nodes");
        }
        for (j, joint) in elements(skin, "joints") {
            ctx.reference_value(joint, &format!("{pointer}/joints/{j}"), "nodes");
        }
    }
    for (_, pointer, animation) in ctx.objects("animations") {
        let Some((samplers, channels)) = super::animations::linked(animation) else {
            continue;
        };
        let mut sampler_used = vec![false; samplers.len()];
        for (s, sampler) in samplers.iter().enumerate() {
            let sp = format!("{pointer}/samplers/{s}");
            ctx.reference(sampler, "input", &sp, "accessors");
            ctx.reference(sampler, "output", &sp, "accessors");
        }
        for (c, channel) in channels.iter().enumerate() {
            let cp = format!("{pointer}/channels/{c}");
            if let Some(s) = unsigned(channel, "sampler") {
                if (s as usize) < samplers.len() {
                    sampler_used[s as usize] = true;
                } else {
                    ctx.emit(
                        khronos::UNRESOLVED_REFERENCE,
                        member(&cp, "sampler"),
                        format!("Unresolved reference: {s}."),
                    );
                }
            }
            if let Some(target) = channel.get("target") {
                ctx.reference(target, "node", &member(&cp, "target"), "nodes");
            }
        }
        for (s, used) in sampler_used.iter().enumerate() {
            if !used && samplers.at(s).is_object() {
                ctx.emit(
                    khronos::UNUSED_OBJECT,
                    format!("{pointer}/samplers/{s}"),
                    "This object may be unused.",
                );
            }
        }
    }
}
