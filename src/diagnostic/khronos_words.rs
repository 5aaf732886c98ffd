//! Every Khronos code in words: what it means (one sentence, no placeholders) and what to do
//! about it (why it matters, how to fix it), for `explain`, `rules` and SARIF. The validator
//! documents its codes by their message templates only; these texts are gltfmat's own,
//! written from the glTF 2.0 specification.

/// What a Khronos code means and what to do about it.
#[derive(Debug, Clone, Copy)]
pub struct Words {
    /// One sentence: what the code reports.
    pub meaning: &'static str,
    /// Why it matters and how to fix it.
    pub advice: &'static str,
}

macro_rules! words {
    ($($code:ident: $meaning:literal => $advice:literal;)*) => {
        /// Every Khronos code's words, by code name.
        pub static WORDS: &[(&str, Words)] = &[
            $((stringify!($code), Words { meaning: $meaning, advice: $advice }),)*
        ];
    };
}

/// The words of the Khronos code named `code`.
pub fn of(code: &str) -> Option<Words> {
    WORDS
        .iter()
        .find(|(name, _)| *name == code)
        .map(|(_, w)| *w)
}

words! {
    IO_ERROR: "A file the asset names (a buffer or an image) could not be read." => "Everything that depends on the file goes unchecked and will not load in a viewer. Put the file where the URI says, relative to the asset, or embed it.";
    ARRAY_LENGTH_NOT_IN_LIST: "An array has a length the schema does not allow (a colour with 2 components, a matrix without 16)." => "Readers index the array by position and will read past it or misread it. Give the array exactly the number of elements its property takes.";
    ARRAY_TYPE_MISMATCH: "An array holds an element of the wrong JSON type (a string among numbers, say)." => "The element is unusable and the validator treats the whole array as absent. Write every element with the type the property takes.";
    DUPLICATE_ELEMENTS: "An array that must hold distinct values repeats one (an extension listed twice, a node in two places)." => "Repeats make lists ambiguous; some loaders reject them. Remove the duplicate.";
    EMPTY_ENTITY: "An object or array that must have content is empty." => "An empty entity carries no meaning and some loaders reject it. Remove it, or fill it in.";
    INVALID_INDEX: "An index into an array of the asset is negative or not an integer." => "Nothing can be looked up with it. Write a non-negative integer that names an existing element.";
    INVALID_JSON: "The file is not valid JSON (or the GLB's JSON chunk is not)." => "Nothing else can be checked or loaded. Fix the syntax at the reported place; the parser's words say what it expected.";
    INVALID_URI: "A URI cannot be parsed, or is a data URI whose media type or content is not understood." => "The resource cannot be fetched, so the buffer or image is missing. Percent-encode reserved characters, or use a data URI of a supported media type with valid base64.";
    ONE_OF_MISMATCH: "An object defines none, or more than one, of a set of properties it must define exactly one of (an image's uri or bufferView)." => "A reader cannot tell where the data is. Define exactly one of the listed properties.";
    PATTERN_MISMATCH: "A string does not have the form the schema requires (an extension name, a version)." => "Readers parse the value and fail or misread it. Write the value in the required form.";
    TYPE_MISMATCH: "A property has the wrong JSON type (a string where a number is required, say)." => "The value is unusable and is read as absent. Write the property with the type the specification gives it.";
    UNDEFINED_PROPERTY: "A required property is missing." => "Readers need it to use the object at all. Add the property with a valid value.";
    UNEXPECTED_PROPERTY: "An object has a property its schema does not define." => "Readers ignore it, so whatever it was meant to do does not happen; it is often a misspelling. Rename it to a defined property, or move custom data into extras or an extension.";
    UNSATISFIED_DEPENDENCY: "A property is present without another property it depends on (byteStride with no bufferView, say)." => "The first property cannot be interpreted alone. Add the property it depends on, or remove it.";
    VALUE_MULTIPLE_OF: "A number is not a multiple of the step its property requires (a byteStride not a multiple of 4)." => "Readers rely on the alignment and misread the data. Use a multiple of the required step.";
    VALUE_NOT_IN_LIST: "A value is not one of those its property allows (an unknown alphaMode or interpolation)." => "Readers do not know what to do with it and fall back to a default. Use one of the listed values.";
    VALUE_NOT_IN_RANGE: "A number is outside its property's range (a factor above 1, a negative count)." => "Readers clamp it or reject the asset, so it does not look as intended. Bring the value into the range the specification gives.";
    ACCESSOR_MATRIX_ALIGNMENT: "A matrix accessor's columns are not aligned to 4-byte boundaries." => "The specification requires each column to start on a 4-byte boundary, and GPUs read matrices that way. Pad each column of byte or short matrices to 4 bytes.";
    ACCESSOR_NORMALIZED_INVALID: "An accessor of float or 32-bit integer components is marked normalized." => "Only 8- and 16-bit integers can be normalized; readers ignore or reject the flag. Remove normalized, or store the data as (unsigned) bytes or shorts.";
    ACCESSOR_OFFSET_ALIGNMENT: "An accessor's byteOffset is not a multiple of its component size." => "Typed reads of unaligned data fail or are slow in WebGL and GPUs. Move the data so the offset is a multiple of the component size.";
    ACCESSOR_SPARSE_COUNT_OUT_OF_RANGE: "A sparse accessor replaces more elements than the accessor has." => "The extra replacements have nowhere to go. Make sparse.count at most the accessor's count.";
    ANIMATION_CHANNEL_TARGET_NODE_SKIN: "An animation moves (translation, rotation, scale) the node that holds a skinned mesh." => "A skinned mesh is placed by its joints, not by its node, so the animation has no visible effect. Animate the joints, or the skeleton's root, instead.";
    ASSET_MIN_VERSION_GREATER_THAN_VERSION: "asset.minVersion is greater than asset.version." => "No reader can satisfy it. Set minVersion to at most the asset's version, or drop it.";
    BUFFER_DATA_URI_MIME_TYPE_INVALID: "A buffer's data URI has a media type other than application/octet-stream or application/gltf-buffer." => "Readers may refuse to decode it. Use one of the two buffer media types.";
    BUFFER_VIEW_INVALID_BYTE_STRIDE: "A bufferView that does not hold vertex attributes has a byteStride." => "Only vertex data may be interleaved; readers ignore or reject the stride elsewhere. Remove byteStride from views of indices, images, animation or skin data.";
    BUFFER_VIEW_TOO_BIG_BYTE_STRIDE: "A bufferView's byteStride is larger than its byteLength." => "Not even one element fits; the view is unusable. Fix the stride or the length.";
    CAMERA_XMAG_YMAG_NEGATIVE: "An orthographic camera has a negative xmag or ymag." => "Negative magnifications mirror the picture, which viewers treat differently. Use positive values and flip the node instead, if a mirror is meant.";
    CAMERA_XMAG_YMAG_ZERO: "An orthographic camera has an xmag or ymag of zero." => "The projection divides by it: nothing can be drawn. Use the half-width and half-height of the view, both non-zero.";
    CAMERA_YFOV_GEQUAL_PI: "A perspective camera's vertical field of view is π radians (180°) or more." => "No perspective projection covers that; viewers break or clamp it. Give yfov in radians, below π (a degrees value written by mistake is a common cause).";
    CAMERA_ZFAR_LEQUAL_ZNEAR: "A camera's zfar is not greater than its znear." => "The depth range is empty and nothing is drawn. Make zfar greater than znear.";
    EXTRA_PROPERTY: "A property is set where it has no effect (a sampler property no texture reads, a byteStride on a view it does not apply to)." => "Readers ignore it; whatever it was meant to change does not change. Remove it, or move it where it applies.";
    INVALID_EXTENSION_NAME_FORMAT: "An extension name does not have the PREFIX_name form." => "Readers match extensions by exact name; a malformed one matches nothing. Use a registered prefix (KHR_, EXT_, a vendor's) and an underscore.";
    INVALID_GL_VALUE: "A number that must be a GL enum (a component type, a filter, a wrap mode) is not one the property allows." => "Readers cannot map it to a GPU setting. Use one of the values the specification lists.";
    KHR_ANIMATION_POINTER_ANIMATION_CHANNEL_TARGET_NODE: "A KHR_animation_pointer channel also names a target node." => "The pointer says what is animated; a node beside it is contradictory. Remove target.node.";
    KHR_ANIMATION_POINTER_ANIMATION_CHANNEL_TARGET_PATH: "A KHR_animation_pointer channel's target path is not \"pointer\"." => "Readers would animate the path and ignore the pointer. Set target.path to \"pointer\".";
    KHR_LIGHTS_PUNCTUAL_LIGHT_SPOT_ANGLES: "A spot light's outer cone angle is not greater than its inner cone angle." => "The falloff between the cones is undefined; viewers draw a hard edge or nothing. Make outerConeAngle greater than innerConeAngle.";
    KHR_MATERIALS_ANISOTROPY_ANISOTROPY_TEXTURE_TEXCOORD: "The anisotropy texture reads other texture coordinates than the normal texture." => "Both are expressed in the tangent frame of the normal map's coordinates; another set gives a wrong direction. Read both through the same texCoord.";
    KHR_MATERIALS_CLEARCOAT_CLEARCOAT_NORMAL_TEXTURE_TEXCOORD: "The clearcoat normal texture reads other texture coordinates than the normal texture." => "Both are in the tangent frame of one set of coordinates; another set tilts the coat wrongly. Read both through the same texCoord.";
    KHR_MATERIALS_DISPERSION_NO_VOLUME: "A material has KHR_materials_dispersion without KHR_materials_volume." => "Dispersion happens inside a volume; without one it has no effect. Add KHR_materials_volume (with transmission), or remove dispersion.";
    KHR_MATERIALS_EMISSIVE_STRENGTH_ZERO_FACTOR: "A material has KHR_materials_emissive_strength but its emissive factor is zero." => "Strength multiplies the emissive colour, so zero times anything is no emission. Set emissiveFactor, or remove the extension.";
    KHR_MATERIALS_IRIDESCENCE_THICKNESS_RANGE_WITHOUT_TEXTURE: "An iridescence thickness minimum is set without a thickness texture." => "Without the texture the thickness is the maximum everywhere, so the minimum does nothing. Add the texture, or drop the minimum.";
    KHR_MATERIALS_IRIDESCENCE_THICKNESS_TEXTURE_UNUSED: "An iridescence thickness texture is given but the thickness minimum equals the maximum." => "The texture only blends between the two, so it changes nothing. Set different bounds, or drop the texture.";
    KHR_MATERIALS_VOLUME_DOUBLE_SIDED: "A material with KHR_materials_volume is double-sided." => "A volume needs an inside and an outside; double-sided surfaces have neither, so refraction is wrong. Make the material single-sided and the mesh closed.";
    KHR_MATERIALS_VOLUME_NO_TRANSMISSION: "A material has KHR_materials_volume but neither transmission nor diffuse transmission." => "Light must enter the surface to cross the volume; without transmission the volume is never seen. Add KHR_materials_transmission (or diffuse transmission), or remove the volume.";
    MATERIAL_ALPHA_CUTOFF_INVALID_MODE: "alphaCutoff is set on a material whose alphaMode is not MASK." => "Only MASK uses the cutoff, so it has no effect. Set alphaMode to MASK, or remove alphaCutoff.";
    MESH_INVALID_WEIGHTS_COUNT: "A mesh's default morph weights are not one per morph target." => "Readers pair weights with targets by position and will misapply them. Give exactly one weight per target.";
    MESH_PRIMITIVES_UNEQUAL_TARGETS_COUNT: "The primitives of one mesh have different numbers of morph targets." => "One weights array drives every primitive, which needs the same number of targets in each. Give every primitive the same targets.";
    MESH_PRIMITIVE_INDEXED_SEMANTIC_CONTINUITY: "Numbered attributes (TEXCOORD_n, COLOR_n, JOINTS_n, WEIGHTS_n) do not start at 0 or skip a number." => "Readers look them up from 0 upwards and stop at the first gap. Number the sets 0, 1, 2 … without gaps.";
    MESH_PRIMITIVE_INVALID_ATTRIBUTE: "An attribute name is not one glTF defines and does not start with an underscore." => "Readers ignore it. Use a defined semantic, or prefix an application-specific attribute with an underscore.";
    MESH_PRIMITIVE_JOINTS_WEIGHTS_MISMATCH: "A primitive has a different number of JOINTS_n and WEIGHTS_n sets." => "Each joint set is weighted by the matching weight set; an unmatched one is unusable. Give each JOINTS_n its WEIGHTS_n.";
    MESH_PRIMITIVE_NO_POSITION: "A primitive has no POSITION attribute." => "Without positions nothing is drawn; readers may reject it. Add positions, or remove the primitive.";
    MESH_PRIMITIVE_TANGENT_WITHOUT_NORMAL: "A primitive has TANGENT but no NORMAL." => "A tangent frame needs the normal too; readers then compute flat normals and ignore the tangents. Add NORMAL.";
    MULTIPLE_EXTENSIONS: "An object uses several extensions that may not combine." => "Viewers may apply only one of them, and not the same one. Keep one, or check that the extensions' texts allow them together.";
    NODE_EMPTY: "A node has no mesh, camera, children, skin, light or extension." => "It does nothing (unless an animation or a skin uses it). Remove it, or give it content.";
    NODE_MATRIX_DEFAULT: "A node's matrix is the identity." => "It changes nothing and costs a read. Remove it.";
    NODE_MATRIX_NON_TRS: "A node's matrix cannot be split into translation, rotation and scale (it shears or projects)." => "The specification requires a decomposable matrix; animation and many engines store nodes as TRS and will distort it. Bake the shear into the mesh.";
    NODE_MATRIX_TRS: "A node has both a matrix and translation, rotation or scale." => "The specification allows one or the other; readers disagree about which wins. Keep one form.";
    NODE_SKINNED_MESH_LOCAL_TRANSFORMS: "A node with a skinned mesh has its own translation, rotation or scale." => "A skinned mesh is placed by its joints, so these transforms have no effect. Move the transform to the skeleton's root.";
    NODE_SKINNED_MESH_NON_ROOT: "A node with a skinned mesh is not a root node." => "Its parents' transforms do not reach a skinned mesh, which its joints place. Make it a root, or expect the parents to be ignored.";
    NODE_SKINNED_MESH_PARENT_TRANSFORMS: "A node with a skinned mesh has ancestors with transforms." => "Those transforms do not reach a skinned mesh, so it does not move with its parents. Move the transforms onto the joints' root, or remove them.";
    NODE_SKIN_NO_SCENE: "A skinned mesh is used in a scene that contains none of its joints." => "The joints are never placed, so the mesh cannot be posed. Add the skeleton to the same scene.";
    NON_OBJECT_EXTRAS: "An extras value is not a JSON object." => "Tools that merge extras expect an object and may drop it. Wrap the value in an object.";
    NON_RELATIVE_URI: "A URI is absolute (a scheme, an absolute path or a drive letter)." => "The asset depends on a place outside itself, which other machines do not have; many loaders refuse it. Use a path relative to the asset, or embed the data.";
    NON_REQUIRED_EXTENSION: "An extension that cannot be optional is in extensionsUsed but not in extensionsRequired." => "A reader without it would load the asset wrongly instead of refusing it. List it in extensionsRequired.";
    ROTATION_NON_UNIT: "A node's rotation quaternion is not of unit length." => "Non-unit quaternions scale and skew when applied; readers differ in whether they normalise. Normalise it.";
    SKIN_NO_COMMON_ROOT: "A skin's joints are not all below one common root node." => "The skeleton cannot be placed as one; viewers pose it differently. Put the joints under one root.";
    SKIN_SKELETON_INVALID: "A skin's skeleton node is not an ancestor of all its joints." => "The skeleton property names the root the joints hang from; a wrong one misplaces the mesh. Point it at the joints' common root, or remove it.";
    UNKNOWN_ASSET_MAJOR_VERSION: "asset.version has a major version other than 2." => "A glTF 2.0 reader cannot read another major version. Convert the asset (`gltfmat upgrade` converts 1.0).";
    UNKNOWN_ASSET_MINOR_VERSION: "asset.version has a minor version this validator does not know." => "Newer minor versions may add things this check does not know. Check with a validator of that version.";
    UNUSED_EXTENSION_REQUIRED: "An extension is required but not listed in extensionsUsed." => "Every required extension must also be used; readers refuse an asset over one it does not use. Add it to extensionsUsed, or remove it from extensionsRequired.";
    ACCESSOR_SMALL_BYTESTRIDE: "A bufferView's byteStride is smaller than one element of an accessor that reads it." => "Elements overlap and read each other's bytes. Make the stride at least the element size.";
    ACCESSOR_TOO_LONG: "An accessor reads past the end of its bufferView." => "The last elements are garbage or the read fails. Fix the accessor's count or offset, or the view's length.";
    ACCESSOR_TOTAL_OFFSET_ALIGNMENT: "An accessor's offset plus its bufferView's offset is not a multiple of its component size." => "The data is unaligned in the buffer, which typed-array readers cannot read. Align the bufferView or the accessor.";
    ACCESSOR_USAGE_OVERRIDE: "One accessor is used for two different kinds of data (indices and vertex data, say)." => "Readers upload it to one GPU buffer type; the other use breaks. Use separate accessors.";
    ANIMATION_CHANNEL_TARGET_NODE_MATRIX: "An animation targets translation, rotation or scale of a node defined by a matrix." => "A matrix node has no TRS to animate. Store the node as translation, rotation and scale.";
    ANIMATION_CHANNEL_TARGET_NODE_WEIGHTS_NO_MORPHS: "An animation targets morph weights of a node whose mesh has no morph targets." => "There is nothing to weight. Remove the channel, or add the targets.";
    ANIMATION_DUPLICATE_TARGETS: "Two channels of one animation animate the same property of the same node." => "Only one can win, and viewers disagree about which. Keep one channel per property.";
    ANIMATION_SAMPLER_ACCESSOR_WITH_BYTESTRIDE: "An animation sampler's accessor reads a bufferView with a byteStride." => "Animation data must be tightly packed. Remove the stride (and the interleaving).";
    ANIMATION_SAMPLER_INPUT_ACCESSOR_INVALID_FORMAT: "An animation's time accessor is not scalar floats." => "Key times are seconds as 32-bit floats. Store them so.";
    ANIMATION_SAMPLER_INPUT_ACCESSOR_TOO_FEW_ELEMENTS: "An animation sampler has fewer keyframes than its interpolation needs." => "Cubic splines need at least two keys, the others one; with fewer the curve is undefined. Add keys, or change the interpolation.";
    ANIMATION_SAMPLER_INPUT_ACCESSOR_WITHOUT_BOUNDS: "An animation's time accessor has no min and max." => "Readers use them for the animation's length without reading the data. Write min and max.";
    ANIMATION_SAMPLER_OUTPUT_ACCESSOR_INVALID_COUNT: "An animation's values do not match its keyframes (one per key, three per key for cubic splines, times the morph targets for weights)." => "Keys and values are paired by position; a mismatch shifts the whole animation. Write the right number of values.";
    ANIMATION_SAMPLER_OUTPUT_ACCESSOR_INVALID_FORMAT: "An animation's values have a type the animated property does not take (a VEC3 for a rotation, say)." => "The values cannot be applied. Store rotations as VEC4, translations and scales as VEC3, weights as scalars.";
    BUFFER_MISSING_GLB_DATA: "A buffer without a URI refers to a GLB binary chunk that is missing." => "Its data is nowhere, so everything that reads it is empty. Write the BIN chunk, or give the buffer a URI.";
    BUFFER_VIEW_TARGET_MISSING: "A bufferView of vertex or index data has no target." => "Engines that create GPU buffers from views need to know which kind. Set target to 34962 (vertices) or 34963 (indices).";
    BUFFER_VIEW_TARGET_OVERRIDE: "One bufferView is used both as vertex and as index data (or with a target that contradicts its use)." => "A GPU buffer has one kind; the other use fails. Split the view.";
    BUFFER_VIEW_TOO_LONG: "A bufferView reaches past the end of its buffer." => "The bytes past the end do not exist. Fix the view's offset or length, or the buffer's byteLength.";
    IMAGE_BUFFER_VIEW_WITH_BYTESTRIDE: "A bufferView holding an image has a byteStride." => "Images are plain bytes; a stride means nothing there. Remove it.";
    INCOMPLETE_EXTENSION_SUPPORT: "The validator checks this extension only in part." => "Problems in it may go unreported. Check the extension's own rules by hand or with its tools.";
    INVALID_IBM_ACCESSOR_COUNT: "A skin has fewer inverse bind matrices than joints." => "Each joint needs its matrix; the ones without are undefined. Write one matrix per joint.";
    KHR_MATERIALS_VARIANTS_NON_UNIQUE_VARIANT: "One variant is mapped to two materials of the same primitive." => "The primitive can show only one material per variant. Map each variant once.";
    MESH_PRIMITIVE_ACCESSOR_UNALIGNED: "Vertex data is not aligned to 4-byte boundaries." => "GPU vertex fetch requires 4-byte alignment; WebGL refuses the buffer. Pad the data so each attribute starts on 4 bytes.";
    MESH_PRIMITIVE_ACCESSOR_WITHOUT_BYTESTRIDE: "Several vertex accessors share a bufferView that has no byteStride." => "Interleaved data needs the stride to find each vertex. Set byteStride.";
    MESH_PRIMITIVE_ATTRIBUTES_ACCESSOR_INVALID_FORMAT: "A vertex attribute has a type or component type its semantic does not allow (a VEC2 NORMAL, float JOINTS)." => "Readers expect the specified format and misread others. Store the attribute in one of the listed formats.";
    MESH_PRIMITIVE_ATTRIBUTES_ACCESSOR_UNSIGNED_INT: "A vertex attribute uses 32-bit unsigned integers." => "glTF vertex attributes may not (only indices may). Use floats, or 8/16-bit integers.";
    MESH_PRIMITIVE_GENERATED_TANGENT_SPACE: "A material needs tangents (a normal map) but the primitive has none, so viewers generate them." => "Generated tangents differ between viewers (MikkTSpace or not), so the normal map shades differently. Export TANGENT with the mesh, computed as the normal map was baked.";
    MESH_PRIMITIVE_INCOMPATIBLE_MODE: "A primitive's vertex or index count does not fit its drawing mode (triangles need a multiple of 3)." => "The last, incomplete primitive is dropped or garbage. Fix the count or the mode.";
    MESH_PRIMITIVE_INDICES_ACCESSOR_INVALID_FORMAT: "Indices are not unsigned bytes, shorts or ints, or are not scalars." => "Index buffers take only those. Store them so.";
    MESH_PRIMITIVE_INDICES_ACCESSOR_WITH_BYTESTRIDE: "An indices accessor reads a bufferView with a byteStride." => "Indices must be tightly packed. Remove the stride.";
    MESH_PRIMITIVE_MORPH_TARGET_INVALID_ATTRIBUTE_COUNT: "A morph target's attribute has a different count from the primitive's attribute." => "Targets displace vertex by vertex; a different count cannot be paired. Give targets the primitive's vertex count.";
    MESH_PRIMITIVE_MORPH_TARGET_NO_BASE_ACCESSOR: "A morph target displaces an attribute the primitive does not have." => "There is nothing to displace. Add the base attribute, or remove it from the target.";
    MESH_PRIMITIVE_NO_TANGENT_SPACE: "A material needs a tangent space (anisotropy, say) but the primitive has neither tangents nor a normal map to derive them." => "The effect cannot be oriented and renders wrongly or not at all. Export TANGENT.";
    MESH_PRIMITIVE_POSITION_ACCESSOR_WITHOUT_BOUNDS: "A POSITION accessor has no min and max." => "Readers use them for bounds and culling; the specification requires them. Write min and max.";
    MESH_PRIMITIVE_TOO_FEW_TEXCOORDS: "A material reads a TEXCOORD set the primitive does not have." => "The texture is sampled at undefined coordinates. Add the set, or point the texture at one that exists.";
    MESH_PRIMITIVE_UNEQUAL_ACCESSOR_COUNT: "The attributes of one primitive have different counts." => "Vertices are assembled from every attribute at the same index; unequal counts leave some undefined. Give every attribute the same count.";
    NODE_LOOP: "A node is its own ancestor (the hierarchy has a cycle)." => "Transforms cannot be computed and loaders hang or refuse. Break the cycle.";
    NODE_PARENT_OVERRIDE: "A node is listed as a child of two parents." => "The node hierarchy must be a tree; one parent wins and the other loses its child. Duplicate the node, or keep one parent.";
    NODE_SKINNED_MESH_WITHOUT_SKIN: "A node uses a mesh with joints and weights but has no skin." => "The mesh cannot be posed and draws in its bind pose or not at all. Add the skin, or remove the skinning attributes.";
    NODE_SKIN_WITH_NON_SKINNED_MESH: "A node has a skin but its mesh has no joints or weights." => "The skin does nothing. Remove it, or add the skinning attributes.";
    NODE_WEIGHTS_INVALID: "A node's morph weights are not one per morph target of its mesh." => "Readers pair weights with targets by position. Give exactly one weight per target.";
    SCENE_NON_ROOT_NODE: "A scene lists a node that is a child of another node." => "Scenes list roots; a child listed again is drawn twice or the list is refused. List only root nodes.";
    SKIN_IBM_ACCESSOR_WITH_BYTESTRIDE: "The inverse bind matrices are in a bufferView with a byteStride." => "Matrices must be tightly packed. Remove the stride.";
    SKIN_IBM_INVALID_FORMAT: "The inverse bind matrices are not MAT4 of floats." => "Readers read them as 4×4 float matrices. Store them so.";
    TEXTURE_INVALID_IMAGE_MIME_TYPE: "A texture's image has a media type the texture may not use (KTX2 or WebP without its extension)." => "Viewers without the extension cannot decode it. Use PNG or JPEG, or declare KHR_texture_basisu / EXT_texture_webp with a fallback.";
    UNDECLARED_EXTENSION: "An extension object is used but not listed in extensionsUsed." => "Readers decide what to load from extensionsUsed and ignore the object. List the extension.";
    UNEXPECTED_EXTENSION_OBJECT: "An extension is placed on an object it does not apply to." => "Readers look for it only where its specification puts it. Move it there.";
    UNRESOLVED_REFERENCE: "An index names an element that does not exist." => "The reference is broken: what it names is missing in every viewer. Point it at an existing element.";
    UNSUPPORTED_EXTENSION: "The validator does not know this extension." => "Its content is not checked. Check it with the extension's own rules.";
    UNUSED_MESH_TANGENT: "A primitive has tangents but its material has no normal map (or other need of them)." => "Nothing reads them; they only cost size. Remove them, or add the normal map they were made for.";
    UNUSED_MESH_WEIGHTS: "A mesh's default morph weights are always replaced by the node's weights." => "They never take effect. Remove one of the two.";
    UNUSED_OBJECT: "An object is not used by any scene, mesh, material or animation." => "It is never shown and only adds size; it can also be a sign of a broken reference. Remove it, or reference it.";
    ACCESSOR_ANIMATION_INPUT_NEGATIVE: "An animation keyframe time is negative." => "Time starts at 0; negative keys are unreachable. Shift the times.";
    ACCESSOR_ANIMATION_INPUT_NON_INCREASING: "An animation's keyframe times do not strictly increase." => "Interpolation between keys is undefined where they repeat or go back. Sort the keys and remove duplicates.";
    ACCESSOR_ANIMATION_SAMPLER_OUTPUT_NON_NORMALIZED_QUATERNION: "An animated rotation is not a unit quaternion." => "Non-unit rotations scale and skew; viewers differ in whether they normalise. Normalise the keys.";
    ACCESSOR_ELEMENT_OUT_OF_MAX_BOUND: "Accessor elements exceed the accessor's declared max." => "Readers trust max for bounds and culling; data outside it is clipped or culled. Write the real maximum.";
    ACCESSOR_ELEMENT_OUT_OF_MIN_BOUND: "Accessor elements are below the accessor's declared min." => "Readers trust min for bounds and culling; data outside it is clipped or culled. Write the real minimum.";
    ACCESSOR_INDEX_OOB: "An index points past the last vertex." => "It reads memory that is not a vertex: a GPU error or garbage triangles. Fix the indices or add the vertices.";
    ACCESSOR_INDEX_PRIMITIVE_RESTART: "Indices contain the primitive restart value (the maximum of their type)." => "glTF does not use primitive restart, but GPUs with it enabled cut the strip there. Use a wider index type, or remove the value.";
    ACCESSOR_INDEX_TRIANGLE_DEGENERATE: "Some triangles repeat a vertex and have no area." => "They draw nothing and cost time. Remove them.";
    ACCESSOR_INVALID_FLOAT: "A float element is NaN or infinite." => "It poisons everything computed from it (bounds, shading, skinning). Replace it with a finite number.";
    ACCESSOR_INVALID_IBM: "An inverse bind matrix holds an invalid value (its last row is not 0, 0, 0, 1)." => "Inverse bind matrices are affine; anything else distorts the skin. Write affine matrices.";
    ACCESSOR_INVALID_SIGN: "A tangent's w (the bitangent's sign) is not 1 or −1." => "The bitangent direction is undefined and normal maps flip. Write ±1.";
    ACCESSOR_JOINTS_INDEX_DUPLICATE: "A vertex names the same joint twice." => "Its influence is counted twice or not at all, depending on the viewer. Merge the two entries and add their weights.";
    ACCESSOR_JOINTS_INDEX_OOB: "A joint index is past the last joint of the skin." => "It reads a matrix that does not exist: a GPU error or a flying vertex. Fix the index.";
    ACCESSOR_JOINTS_USED_ZERO_WEIGHT: "A joint with zero weight is not index 0." => "Unused slots should be zero so that they read a valid joint; other values may be out of range. Set them to 0.";
    ACCESSOR_MAX_MISMATCH: "An accessor's declared max differs from the data's real maximum." => "Readers trust max for bounds and culling. Write the real maximum.";
    ACCESSOR_MIN_MISMATCH: "An accessor's declared min differs from the data's real minimum." => "Readers trust min for bounds and culling. Write the real minimum.";
    ACCESSOR_NON_CLAMPED: "A value that must lie in 0..1 (a colour, a weight) does not." => "Viewers clamp it differently. Bring the data into 0..1.";
    ACCESSOR_SPARSE_INDEX_OOB: "A sparse index is past the accessor's last element." => "The replacement has no element to replace. Fix the index.";
    ACCESSOR_SPARSE_INDICES_NON_INCREASING: "Sparse indices do not strictly increase." => "Readers merge them in order; repeats and reversals are undefined. Sort them and remove duplicates.";
    ACCESSOR_VECTOR3_NON_UNIT: "A normal or tangent is not of unit length." => "Shading assumes unit vectors; others make the surface too bright or too dark. Normalise the vectors.";
    ACCESSOR_WEIGHTS_NEGATIVE: "A skin weight is negative." => "Negative influences pull vertices the wrong way. Use weights from 0 to 1.";
    ACCESSOR_WEIGHTS_NON_NORMALIZED: "A vertex's skin weights do not sum to 1." => "The vertex shrinks or grows when posed, and viewers that renormalise differ from those that do not. Normalise each vertex's weights.";
    BUFFER_BYTE_LENGTH_MISMATCH: "A buffer's data is shorter than its byteLength." => "Reads past the real end get nothing. Fix byteLength, or supply the whole file.";
    BUFFER_GLB_CHUNK_TOO_BIG: "The GLB's BIN chunk is longer than its buffer, beyond the padding allowed." => "The extra bytes are wasted and suggest a wrong byteLength. Trim the chunk to the buffer plus at most 3 bytes of padding.";
    DATA_URI_GLB: "A GLB asset embeds data as a base64 data URI." => "Data URIs are a third larger and slower to decode; a GLB has its BIN chunk for that. Move the data into the BIN chunk.";
    IMAGE_DATA_INVALID: "An image's data is broken (a corrupt PNG or JPEG)." => "Viewers show nothing or a default. Re-export the image.";
    IMAGE_FEATURES_UNSUPPORTED: "An image has colour-space information, non-square pixels or animation, which glTF ignores." => "The image may not look as its author saw it. Save it as plain sRGB (or linear data) without those features.";
    IMAGE_MIME_TYPE_INVALID: "An image's data is in another format than its declared mimeType." => "Viewers that trust the type fail to decode it. Fix mimeType, or convert the image.";
    IMAGE_NON_ENABLED_MIME_TYPE: "An image uses a format (KTX2, WebP) whose extension the asset does not declare." => "Viewers without the extension cannot decode it. Declare the extension, or use PNG or JPEG.";
    IMAGE_NPOT_DIMENSIONS: "An image's width or height is not a power of two." => "Older WebGL cannot mipmap or repeat it, so it looks blurry or wrong there. Resize to powers of two if such viewers matter.";
    IMAGE_UNEXPECTED_EOS: "An image's data ends before the image does." => "The image is truncated: viewers show part of it or nothing. Supply the whole file.";
    IMAGE_UNRECOGNIZED_FORMAT: "An image is in no format glTF knows (not PNG, JPEG, KTX2 or WebP)." => "Viewers cannot decode it. Convert it to PNG or JPEG.";
    URI_GLB: "A GLB asset's buffer or image refers to an external file." => "A GLB is meant to be one file; external files get lost when it is copied. Embed them in the BIN chunk.";
    GLB_CHUNK_LENGTH_UNALIGNED: "A GLB chunk's length is not a multiple of 4." => "The next chunk starts unaligned, which readers reject. Pad the chunk (spaces for JSON, zeros for BIN).";
    GLB_CHUNK_TOO_BIG: "A GLB chunk claims to be longer than the file." => "The file is truncated or the length is wrong; the chunk cannot be read. Re-export the file.";
    GLB_DUPLICATE_CHUNK: "A GLB has two chunks of the same kind." => "Readers use one and ignore the other. Keep one JSON and at most one BIN chunk.";
    GLB_EMPTY_BIN_CHUNK: "A GLB has an empty BIN chunk." => "It carries nothing. Omit it.";
    GLB_EMPTY_CHUNK: "A GLB chunk has zero length." => "An empty JSON chunk is no asset. Write the chunk's content, or omit the chunk.";
    GLB_EXTRA_DATA: "Bytes follow the end of the GLB that its header declares." => "They are ignored, and suggest a wrong length. Trim them, or fix the header's length.";
    GLB_INVALID_MAGIC: "The file does not start with the GLB magic \"glTF\"." => "It is not a GLB (or is damaged). Check the file's type.";
    GLB_INVALID_VERSION: "The GLB header's version is not 2." => "glTF 2.0 readers read only GLB version 2 (`gltfmat upgrade` converts version 1).";
    GLB_LENGTH_MISMATCH: "The GLB header's length differs from the file's size." => "The file is truncated or padded. Re-export it, or fix the header.";
    GLB_LENGTH_TOO_SMALL: "The GLB header declares a length too small for a header and a chunk." => "Nothing can be read. Re-export the file.";
    GLB_UNEXPECTED_BIN_CHUNK: "The BIN chunk is not the second chunk of the GLB." => "Readers look for it right after the JSON. Put it there.";
    GLB_UNEXPECTED_END_OF_CHUNK_DATA: "A GLB chunk's data ends before its declared length." => "The file is truncated. Re-export it.";
    GLB_UNEXPECTED_END_OF_CHUNK_HEADER: "The file ends inside a GLB chunk header." => "The file is truncated. Re-export it.";
    GLB_UNEXPECTED_END_OF_HEADER: "The file ends inside the 12-byte GLB header." => "The file is truncated, or not a GLB. Re-export it.";
    GLB_UNEXPECTED_FIRST_CHUNK: "The first GLB chunk is not the JSON chunk." => "Readers need the JSON first. Put it first.";
    GLB_UNKNOWN_CHUNK_TYPE: "A GLB chunk has a type neither JSON nor BIN." => "Readers skip it; whatever it holds is lost. Remove it, or use an extension to carry the data.";
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::diagnostic::khronos::CATALOGUE;

    #[test]
    fn every_khronos_code_has_words_and_only_khronos_codes_do() {
        for entry in CATALOGUE {
            assert!(
                of(entry.code.name()).is_some(),
                "{} has no words",
                entry.code.name()
            );
        }
        assert_eq!(
            WORDS.len(),
            CATALOGUE.len(),
            "words for a code the catalogue does not hold"
        );
    }

    #[test]
    fn the_words_are_sentences_without_placeholders() {
        for (code, words) in WORDS {
            for text in [words.meaning, words.advice] {
                assert!(!text.contains('%'), "{code}: a placeholder in {text:?}");
                assert!(
                    text.ends_with('.') || text.ends_with(").") || text.ends_with(')'),
                    "{code}: {text:?}"
                );
                assert!(text.len() > 20, "{code}: {text:?}");
            }
        }
    }
}
