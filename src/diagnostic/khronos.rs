//! The Khronos glTF-Validator issue catalogue (codes, default severities, groups, message
//! templates), transcribed from its ISSUES.md. gltfmat reuses these codes wherever the concept
//! is the same. Each code is a constant, so a misspelt code does not compile.

use super::{Code, Severity};

/// One catalogue entry: the code (with its default severity), its Khronos group and template.
#[derive(Debug, Clone, Copy)]
pub struct Entry {
    /// The code and its default severity.
    pub code: Code,
    /// The Khronos issue group, in the style of gltfmat's rule groups: `schema`, `link`, `data`,
    /// `semantic`, `glb`, `io` (the validator's own `SchemaError`, `LinkError`, …).
    pub group: &'static str,
    /// The Khronos message template.
    pub template: &'static str,
}

macro_rules! catalogue {
    ($($name:ident $severity:ident $group:ident $template:literal;)*) => {
        $(
            #[doc = $template]
            pub const $name: Code = Code::new(stringify!($name), Severity::$severity);
        )*
        /// Every Khronos code, in the order of ISSUES.md.
        pub static CATALOGUE: &[Entry] = &[
            $(Entry { code: $name, group: stringify!($group), template: $template },)*
        ];
    };
}

catalogue! {
    IO_ERROR Error io "%1";
    ARRAY_LENGTH_NOT_IN_LIST Error schema "Invalid array length %1. Valid lengths are: ('%a', '%b', '%c').";
    ARRAY_TYPE_MISMATCH Error schema "Type mismatch. Array element '%1' is not a '%2'.";
    DUPLICATE_ELEMENTS Error schema "Duplicate element.";
    EMPTY_ENTITY Error schema "Entity cannot be empty.";
    INVALID_INDEX Error schema "Index must be a non-negative integer.";
    INVALID_JSON Error schema "Invalid JSON data. Parser output: %1";
    INVALID_URI Error schema "Invalid URI '%1'. Parser output: %2";
    ONE_OF_MISMATCH Error schema "Exactly one of ('%1', '%2', '%3', '%4', '%5') properties must be defined.";
    PATTERN_MISMATCH Error schema "Value '%1' does not match regexp pattern '%2'.";
    TYPE_MISMATCH Error schema "Type mismatch. Property value '%1' is not a '%2'.";
    UNDEFINED_PROPERTY Error schema "Property '%1' must be defined.";
    UNEXPECTED_PROPERTY Warning schema "Unexpected property.";
    UNSATISFIED_DEPENDENCY Error schema "Dependency failed. '%1' must be defined.";
    VALUE_MULTIPLE_OF Error schema "Value %1 is not a multiple of %2.";
    VALUE_NOT_IN_LIST Warning schema "Invalid value '%1'. Valid values are ('%a', '%b', '%c').";
    VALUE_NOT_IN_RANGE Error schema "Value %1 is out of range.";
    ACCESSOR_MATRIX_ALIGNMENT Error semantic "Matrix accessors must be aligned to 4-byte boundaries.";
    ACCESSOR_NORMALIZED_INVALID Error semantic "Only (u)byte and (u)short accessors can be normalized.";
    ACCESSOR_OFFSET_ALIGNMENT Error semantic "Offset %1 is not a multiple of componentType length %2.";
    ACCESSOR_SPARSE_COUNT_OUT_OF_RANGE Error semantic "Sparse accessor overrides more elements (%1) than the base accessor contains (%2).";
    ANIMATION_CHANNEL_TARGET_NODE_SKIN Warning semantic "Animated TRS properties will not affect a skinned mesh.";
    ASSET_MIN_VERSION_GREATER_THAN_VERSION Error semantic "Asset minVersion '%1' is greater than version '%2'.";
    BUFFER_DATA_URI_MIME_TYPE_INVALID Error semantic "Data URI media type must be 'application/octet-stream' or 'application/gltf-buffer'. Found '%1' instead.";
    BUFFER_VIEW_INVALID_BYTE_STRIDE Error semantic "Only buffer views with raw vertex data can have byteStride.";
    BUFFER_VIEW_TOO_BIG_BYTE_STRIDE Error semantic "Buffer view's byteStride (%1) is greater than byteLength (%2).";
    CAMERA_XMAG_YMAG_NEGATIVE Warning semantic "xmag and ymag should not be negative.";
    CAMERA_XMAG_YMAG_ZERO Error semantic "xmag and ymag must not be zero.";
    CAMERA_YFOV_GEQUAL_PI Warning semantic "yfov should be less than Pi.";
    CAMERA_ZFAR_LEQUAL_ZNEAR Error semantic "zfar must be greater than znear.";
    EXTRA_PROPERTY Info semantic "This property should not be defined as it will not be used.";
    INVALID_EXTENSION_NAME_FORMAT Warning semantic "Extension name has invalid format.";
    INVALID_GL_VALUE Error semantic "Invalid value %1 for GL type '%2'.";
    KHR_ANIMATION_POINTER_ANIMATION_CHANNEL_TARGET_NODE Error semantic "This extension requires the animation channel target node to be undefined.";
    KHR_ANIMATION_POINTER_ANIMATION_CHANNEL_TARGET_PATH Error semantic "This extension requires the animation channel target path to be 'pointer'. Found '%1' instead.";
    KHR_LIGHTS_PUNCTUAL_LIGHT_SPOT_ANGLES Error semantic "outerConeAngle (%2) is less than or equal to innerConeAngle (%1).";
    KHR_MATERIALS_ANISOTROPY_ANISOTROPY_TEXTURE_TEXCOORD Warning semantic "Normal and anisotropy textures should use the same texture coords.";
    KHR_MATERIALS_CLEARCOAT_CLEARCOAT_NORMAL_TEXTURE_TEXCOORD Warning semantic "Normal and clearcoat normal textures should use the same texture coords.";
    KHR_MATERIALS_DISPERSION_NO_VOLUME Warning semantic "The dispersion extension needs to be combined with the volume extension.";
    KHR_MATERIALS_EMISSIVE_STRENGTH_ZERO_FACTOR Warning semantic "Emissive strength has no effect when the emissive factor is zero or undefined.";
    KHR_MATERIALS_IRIDESCENCE_THICKNESS_RANGE_WITHOUT_TEXTURE Info semantic "Thickness minimum has no effect when a thickness texture is not defined.";
    KHR_MATERIALS_IRIDESCENCE_THICKNESS_TEXTURE_UNUSED Info semantic "Thickness texture has no effect when the thickness minimum is equal to the thickness maximum.";
    KHR_MATERIALS_VOLUME_DOUBLE_SIDED Warning semantic "The volume extension should not be used with double-sided materials.";
    KHR_MATERIALS_VOLUME_NO_TRANSMISSION Warning semantic "The volume extension needs to be combined with an extension that allows light to transmit through the surface.";
    MATERIAL_ALPHA_CUTOFF_INVALID_MODE Warning semantic "Alpha cutoff is supported only for 'MASK' alpha mode.";
    MESH_INVALID_WEIGHTS_COUNT Error semantic "The length of weights array (%1) does not match the number of morph targets (%2).";
    MESH_PRIMITIVES_UNEQUAL_TARGETS_COUNT Error semantic "All primitives must have the same number of morph targets.";
    MESH_PRIMITIVE_INDEXED_SEMANTIC_CONTINUITY Error semantic "Indices for indexed attribute semantic '%1' must start with 0 and be continuous. Total expected indices: %2, total provided indices: %3.";
    MESH_PRIMITIVE_INVALID_ATTRIBUTE Error semantic "Invalid attribute name.";
    MESH_PRIMITIVE_JOINTS_WEIGHTS_MISMATCH Error semantic "Number of JOINTS attribute semantics (%1) does not match the number of WEIGHTS (%2).";
    MESH_PRIMITIVE_NO_POSITION Warning semantic "No POSITION attribute found.";
    MESH_PRIMITIVE_TANGENT_WITHOUT_NORMAL Warning semantic "TANGENT attribute without NORMAL found.";
    MULTIPLE_EXTENSIONS Warning semantic "This extension may be incompatible with other extensions for the object.";
    NODE_EMPTY Info semantic "Empty node encountered.";
    NODE_MATRIX_DEFAULT Info semantic "Do not specify default transform matrix.";
    NODE_MATRIX_NON_TRS Error semantic "Matrix must be decomposable to TRS.";
    NODE_MATRIX_TRS Error semantic "A node can have either a matrix or any combination of translation/rotation/scale (TRS) properties.";
    NODE_SKINNED_MESH_LOCAL_TRANSFORMS Warning semantic "Local transforms will not affect a skinned mesh.";
    NODE_SKINNED_MESH_NON_ROOT Warning semantic "Node with a skinned mesh is not root. Parent transforms will not affect a skinned mesh.";
    NODE_SKINNED_MESH_PARENT_TRANSFORMS Warning semantic "Node with a skinned mesh has parent nodes with transforms. Parent transforms will not affect a skinned mesh.";
    NODE_SKIN_NO_SCENE Error semantic "A node with a skinned mesh is used in a scene that does not contain joint nodes.";
    NON_OBJECT_EXTRAS Info semantic "Prefer JSON Objects for extras.";
    NON_RELATIVE_URI Warning semantic "Non-relative URI found: '%1'.";
    NON_REQUIRED_EXTENSION Error semantic "Extension '%1' cannot be optional.";
    ROTATION_NON_UNIT Error semantic "Rotation quaternion must be normalized.";
    SKIN_NO_COMMON_ROOT Error semantic "Joints do not have a common root.";
    SKIN_SKELETON_INVALID Error semantic "Skeleton node is not a common root.";
    UNKNOWN_ASSET_MAJOR_VERSION Error semantic "Unknown glTF major asset version: %1.";
    UNKNOWN_ASSET_MINOR_VERSION Warning semantic "Unknown glTF minor asset version: %1.";
    UNUSED_EXTENSION_REQUIRED Error semantic "Unused extension '%1' cannot be required.";
    ACCESSOR_SMALL_BYTESTRIDE Error link "Referenced bufferView's byteStride value %1 is less than accessor element's length %2.";
    ACCESSOR_TOO_LONG Error link "Accessor (offset: %1, length: %2) does not fit referenced bufferView [%3] length %4.";
    ACCESSOR_TOTAL_OFFSET_ALIGNMENT Error link "Accessor's total byteOffset %1 isn't a multiple of componentType length %2.";
    ACCESSOR_USAGE_OVERRIDE Error link "Override of previously set accessor usage. Initial: '%1', new: '%2'.";
    ANIMATION_CHANNEL_TARGET_NODE_MATRIX Error link "Animation channel cannot target TRS properties of a node with defined matrix.";
    ANIMATION_CHANNEL_TARGET_NODE_WEIGHTS_NO_MORPHS Error link "Animation channel cannot target WEIGHTS when mesh does not have morph targets.";
    ANIMATION_DUPLICATE_TARGETS Error link "Animation channel has the same target as channel %1.";
    ANIMATION_SAMPLER_ACCESSOR_WITH_BYTESTRIDE Error link "bufferView.byteStride must not be defined for buffer views used by animation sampler accessors.";
    ANIMATION_SAMPLER_INPUT_ACCESSOR_INVALID_FORMAT Error link "Invalid Animation sampler input accessor format '%1'. Must be one of ('%a', '%b', '%c').";
    ANIMATION_SAMPLER_INPUT_ACCESSOR_TOO_FEW_ELEMENTS Error link "Animation sampler output accessor with '%1' interpolation must have at least %2 elements. Got %3.";
    ANIMATION_SAMPLER_INPUT_ACCESSOR_WITHOUT_BOUNDS Error link "accessor.min and accessor.max must be defined for animation input accessor.";
    ANIMATION_SAMPLER_OUTPUT_ACCESSOR_INVALID_COUNT Error link "Animation sampler output accessor of count %1 expected. Found %2.";
    ANIMATION_SAMPLER_OUTPUT_ACCESSOR_INVALID_FORMAT Error link "Invalid animation sampler output accessor format '%1' for path '%3'. Must be one of ('%a', '%b', '%c').";
    BUFFER_MISSING_GLB_DATA Error link "Buffer refers to an unresolved GLB binary chunk.";
    BUFFER_VIEW_TARGET_MISSING Hint link "bufferView.target should be set for vertex or index data.";
    BUFFER_VIEW_TARGET_OVERRIDE Error link "Override of previously set bufferView target or usage. Initial: '%1', new: '%2'.";
    BUFFER_VIEW_TOO_LONG Error link "BufferView does not fit buffer (%1) byteLength (%2).";
    IMAGE_BUFFER_VIEW_WITH_BYTESTRIDE Error link "bufferView.byteStride must not be defined for buffer views containing image data.";
    INCOMPLETE_EXTENSION_SUPPORT Info link "Validation support for this extension is incomplete; the asset may have undetected issues.";
    INVALID_IBM_ACCESSOR_COUNT Error link "IBM accessor must have at least %1 elements. Found %2.";
    KHR_MATERIALS_VARIANTS_NON_UNIQUE_VARIANT Error link "This variant is used more than once for this mesh primitive.";
    MESH_PRIMITIVE_ACCESSOR_UNALIGNED Error link "Vertex attribute data must be aligned to 4-byte boundaries.";
    MESH_PRIMITIVE_ACCESSOR_WITHOUT_BYTESTRIDE Error link "bufferView.byteStride must be defined when two or more accessors use the same buffer view.";
    MESH_PRIMITIVE_ATTRIBUTES_ACCESSOR_INVALID_FORMAT Error link "Invalid accessor format '%1' for this attribute semantic. Must be one of ('%a', '%b', '%c').";
    MESH_PRIMITIVE_ATTRIBUTES_ACCESSOR_UNSIGNED_INT Error link "Mesh attributes cannot use UNSIGNED_INT component type.";
    MESH_PRIMITIVE_GENERATED_TANGENT_SPACE Warning link "Material requires a tangent space but the mesh primitive does not provide it. Runtime-generated tangent space may be non-portable across implementations.";
    MESH_PRIMITIVE_INCOMPATIBLE_MODE Warning link "Number of vertices or indices (%1) is not compatible with used drawing mode ('%2').";
    MESH_PRIMITIVE_INDICES_ACCESSOR_INVALID_FORMAT Error link "Invalid indices accessor format '%1'. Must be one of ('%a', '%b', '%c'). ";
    MESH_PRIMITIVE_INDICES_ACCESSOR_WITH_BYTESTRIDE Error link "bufferView.byteStride must not be defined for indices accessor.";
    MESH_PRIMITIVE_MORPH_TARGET_INVALID_ATTRIBUTE_COUNT Error link "Base accessor has different count.";
    MESH_PRIMITIVE_MORPH_TARGET_NO_BASE_ACCESSOR Error link "The mesh primitive does not define this attribute semantic.";
    MESH_PRIMITIVE_NO_TANGENT_SPACE Error link "Material requires a tangent space but the mesh primitive does not provide it and the material does not contain a normal map to generate it.";
    MESH_PRIMITIVE_POSITION_ACCESSOR_WITHOUT_BOUNDS Error link "accessor.min and accessor.max must be defined for POSITION attribute accessor.";
    MESH_PRIMITIVE_TOO_FEW_TEXCOORDS Error link "Material is incompatible with mesh primitive: Texture binding '%1' needs 'TEXCOORD_%2' attribute.";
    MESH_PRIMITIVE_UNEQUAL_ACCESSOR_COUNT Error link "All accessors of the same primitive must have the same count.";
    NODE_LOOP Error link "Node is a part of a node loop.";
    NODE_PARENT_OVERRIDE Error link "Value overrides parent of node %1.";
    NODE_SKINNED_MESH_WITHOUT_SKIN Warning link "Node uses skinned mesh, but has no skin defined.";
    NODE_SKIN_WITH_NON_SKINNED_MESH Error link "Node has skin defined, but mesh has no joints data.";
    NODE_WEIGHTS_INVALID Error link "The length of weights array (%1) does not match the number of morph targets (%2).";
    SCENE_NON_ROOT_NODE Error link "Node %1 is not a root node.";
    SKIN_IBM_ACCESSOR_WITH_BYTESTRIDE Error link "bufferView.byteStride must not be defined for buffer views used by inverse bind matrices accessors.";
    SKIN_IBM_INVALID_FORMAT Error link "Invalid IBM accessor format '%1'. Must be one of ('%a', '%b', '%c'). ";
    TEXTURE_INVALID_IMAGE_MIME_TYPE Error link "Invalid MIME type '%1' for the texture source. Valid MIME types are ('%a', '%b', '%c').";
    UNDECLARED_EXTENSION Error link "Extension is not declared in extensionsUsed.";
    UNEXPECTED_EXTENSION_OBJECT Error link "Unexpected location for this extension.";
    UNRESOLVED_REFERENCE Error link "Unresolved reference: %1.";
    UNSUPPORTED_EXTENSION Info link "Cannot validate an extension as it is not supported by the validator: '%1'.";
    UNUSED_MESH_TANGENT Info link "Tangents are not used because the material has no normal texture.";
    UNUSED_MESH_WEIGHTS Info link "The static morph target weights are always overridden.";
    UNUSED_OBJECT Info link "This object may be unused.";
    ACCESSOR_ANIMATION_INPUT_NEGATIVE Error data "Animation input accessor element at index %1 is negative: %2.";
    ACCESSOR_ANIMATION_INPUT_NON_INCREASING Error data "Animation input accessor element at index %1 is less than or equal to previous: %2 <= %3.";
    ACCESSOR_ANIMATION_SAMPLER_OUTPUT_NON_NORMALIZED_QUATERNION Error data "Animation sampler output accessor element at indices %1..%2 is not of unit length: %3.";
    ACCESSOR_ELEMENT_OUT_OF_MAX_BOUND Error data "Accessor contains %1 element(s) greater than declared maximum value %2.";
    ACCESSOR_ELEMENT_OUT_OF_MIN_BOUND Error data "Accessor contains %1 element(s) less than declared minimum value %2.";
    ACCESSOR_INDEX_OOB Error data "Indices accessor element at index %1 has value %2 that is greater than the maximum vertex index available (%3).";
    ACCESSOR_INDEX_PRIMITIVE_RESTART Error data "Indices accessor contains primitive restart value (%1) at index %2.";
    ACCESSOR_INDEX_TRIANGLE_DEGENERATE Info data "Indices accessor contains %1 degenerate triangles (out of %2).";
    ACCESSOR_INVALID_FLOAT Error data "Accessor element at index %1 is %2.";
    ACCESSOR_INVALID_IBM Error data "Matrix element at index %1 (component index %2) contains invalid value: %3.";
    ACCESSOR_INVALID_SIGN Error data "Vector3 with sign at accessor indices %1..%2 has invalid w component: %3. Must be 1.0 or -1.0.";
    ACCESSOR_JOINTS_INDEX_DUPLICATE Error data "Joints accessor element at index %1 (component index %2) has value %3 that is already in use for the vertex.";
    ACCESSOR_JOINTS_INDEX_OOB Error data "Joints accessor element at index %1 (component index %2) has value %3 that is greater than the maximum joint index (%4) set by skin %5.";
    ACCESSOR_JOINTS_USED_ZERO_WEIGHT Warning data "Joints accessor element at index %1 (component index %2) is used with zero weight but has non-zero value (%3).";
    ACCESSOR_MAX_MISMATCH Error data "Declared maximum value for this component (%1) does not match actual maximum (%2).";
    ACCESSOR_MIN_MISMATCH Error data "Declared minimum value for this component (%1) does not match actual minimum (%2).";
    ACCESSOR_NON_CLAMPED Error data "Accessor element at index %1 is not clamped to 0..1 range: %2.";
    ACCESSOR_SPARSE_INDEX_OOB Error data "Accessor sparse indices element at index %1 is greater than or equal to the number of accessor elements: %2 >= %3.";
    ACCESSOR_SPARSE_INDICES_NON_INCREASING Error data "Accessor sparse indices element at index %1 is less than or equal to previous: %2 <= %3.";
    ACCESSOR_VECTOR3_NON_UNIT Error data "Vector3 at accessor indices %1..%2 is not of unit length: %3.";
    ACCESSOR_WEIGHTS_NEGATIVE Error data "Weights accessor element at index %1 (component index %2) has negative value %3.";
    ACCESSOR_WEIGHTS_NON_NORMALIZED Error data "Weights accessor elements (at indices %1..%2) have non-normalized sum: %3.";
    BUFFER_BYTE_LENGTH_MISMATCH Error data "Actual data byte length (%1) is less than the declared buffer byte length (%2).";
    BUFFER_GLB_CHUNK_TOO_BIG Warning data "GLB-stored BIN chunk contains %1 extra padding byte(s).";
    DATA_URI_GLB Warning data "Data URI is used in GLB container.";
    IMAGE_DATA_INVALID Error data "Image data is invalid. %1";
    IMAGE_FEATURES_UNSUPPORTED Warning data "Image contains unsupported features like non-default colorspace information, non-square pixels, or animation.";
    IMAGE_MIME_TYPE_INVALID Error data "Recognized image format '%1' does not match declared image format '%2'.";
    IMAGE_NON_ENABLED_MIME_TYPE Error data "'%1' MIME type requires an extension.";
    IMAGE_NPOT_DIMENSIONS Info data "Image has non-power-of-two dimensions: %1x%2.";
    IMAGE_UNEXPECTED_EOS Error data "Unexpected end of image stream.";
    IMAGE_UNRECOGNIZED_FORMAT Warning data "Image format not recognized.";
    URI_GLB Info data "URI is used in GLB container.";
    GLB_CHUNK_LENGTH_UNALIGNED Error glb "Length of %1 chunk is not aligned to 4-byte boundaries.";
    GLB_CHUNK_TOO_BIG Error glb "Chunk (%1) length (%2) does not fit total GLB length.";
    GLB_DUPLICATE_CHUNK Error glb "Chunk of type %1 has already been used.";
    GLB_EMPTY_BIN_CHUNK Info glb "Empty BIN chunk should be omitted.";
    GLB_EMPTY_CHUNK Error glb "Chunk (%1) cannot have zero length.";
    GLB_EXTRA_DATA Warning glb "Extra data after the end of GLB stream.";
    GLB_INVALID_MAGIC Error glb "Invalid GLB magic value (%1).";
    GLB_INVALID_VERSION Error glb "Invalid GLB version value %1.";
    GLB_LENGTH_MISMATCH Error glb "Declared length (%1) does not match GLB length (%2).";
    GLB_LENGTH_TOO_SMALL Error glb "Declared GLB length (%1) is too small.";
    GLB_UNEXPECTED_BIN_CHUNK Error glb "BIN chunk must be the second chunk.";
    GLB_UNEXPECTED_END_OF_CHUNK_DATA Error glb "Unexpected end of chunk data.";
    GLB_UNEXPECTED_END_OF_CHUNK_HEADER Error glb "Unexpected end of chunk header.";
    GLB_UNEXPECTED_END_OF_HEADER Error glb "Unexpected end of header.";
    GLB_UNEXPECTED_FIRST_CHUNK Error glb "First chunk must be of JSON type. Found %1 instead.";
    GLB_UNKNOWN_CHUNK_TYPE Warning glb "Unknown GLB chunk type: %1.";
}

/// Codes the Khronos validator's builds after the release gltfmat's Khronos profile follows
/// (2.0.0-dev.3.10) replaced, each with its replacement's reason. The default profile follows
/// the newer builds and does not report them.
pub static RETIRED: &[(Code, &str)] = &[(
    NODE_SKINNED_MESH_NON_ROOT,
    "Replaced by NODE_SKINNED_MESH_PARENT_TRANSFORMS where a parent has a transform, as the Khronos build after 2.0.0-dev.3.10 does: under untransformed parents nothing is lost.",
)];

/// Codes of those newer builds that the released validator does not have: the Khronos
/// profile does not report them.
pub static UNRELEASED: &[(Code, &str)] = &[(
    NODE_SKINNED_MESH_PARENT_TRANSFORMS,
    "Reported by the default profile only: the released Khronos validator (2.0.0-dev.3.10) does not have it.",
)];
