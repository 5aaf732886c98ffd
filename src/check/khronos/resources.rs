//! Buffers, buffer views and images: where their bytes come from, whether the declared
//! lengths hold, and what the image headers say.

use crate::check::context::{member, unsigned, Context, ResourceInfo};
use crate::check::pass_codes;
use crate::diagnostic::khronos;
use crate::document::file::Kept;
use crate::document::image_header::{self, HeaderError, ImageFormat, ImageInfo};
use crate::document::uri::{classify, LoadError, ResourceLoader, UriKind};
use crate::document::Node;
use crate::document::{BufferData, Bytes};
use crate::gltf::gl::ELEMENT_ARRAY_BUFFER;
use std::borrow::Cow;
use std::collections::HashMap;
use std::sync::Arc;

/// How [`load_uri`] treats a URI naming a file.
#[derive(Clone, Copy, PartialEq)]
enum Files {
    /// Read it whole.
    Read,
    /// Read it, a large one left in the file to be read by ranges.
    KeepLarge,
    /// Not fetched (what the URI says is still checked, as the validator parses it).
    Unfetched,
}

/// Bytes behind a `uri`, with diagnostics for everything that stops us reading them.
/// Returns the bytes (a file as `files` says) and, for data URIs, the declared media type.
fn load_uri(
    ctx: &mut Context,
    uri: &str,
    pointer: &str,
    files: Files,
) -> (Option<Kept>, Option<String>, &'static str) {
    let glb = crate::check::is_glb(ctx.document);
    if glb {
        ctx.emit(khronos::URI_GLB, pointer, "URI is used in GLB container.");
    }
    match classify(uri) {
        Err(reason) => {
            invalid_uri(ctx, pointer, uri, &reason);
            (None, None, "data-uri")
        }
        Ok(UriKind::Data {
            media_type,
            bytes,
            stray_bits,
        }) => {
            if glb {
                ctx.emit(
                    khronos::DATA_URI_GLB,
                    pointer,
                    "Data URI is used in GLB container.",
                );
            }
            // The Khronos profile never gets here: the validator stops reading the file
            // at such a URI (see `khronos::stops_at_data_uri`).
            if stray_bits {
                ctx.emit(
                    khronos::INVALID_URI,
                    pointer,
                    format!("Invalid URI '{}'. Parser output: its base64 ends in bits past the data (its last character is not the one that encodes them). Browsers drop those bits and read the data, as this check does; the Khronos validator stops reading the whole file here.", shorten(uri)),
                );
            }
            (
                Some(Kept::Read(Arc::new(bytes.into()))),
                Some(media_type),
                "data-uri",
            )
        }
        Ok(UriKind::Relative(path)) if files != Files::Unfetched => {
            let kept = load_relative(ctx, pointer, uri, &path, files == Files::KeepLarge);
            (kept, None, "external")
        }
        Ok(kind) => {
            unread_external(ctx, pointer, uri, kind, files);
            (None, None, "external")
        }
    }
}

fn invalid_uri(ctx: &mut Context, pointer: &str, uri: &str, reason: &str) {
    let message = format!("Invalid URI '{}'. Parser output: {reason}", shorten(uri));
    ctx.emit(khronos::INVALID_URI, pointer, message);
}

/// What the Khronos validator says of the buffers and images it parses before it stops at
/// the data URI of `/collection/index` (see `khronos::stops_at_data_uri`): each URI it
/// cannot parse and each image's members, those of the image it stops at included.
pub(crate) fn check_parsed_before_stop(ctx: &mut Context, (collection, index): (&str, usize)) {
    let unparsed = |ctx: &mut Context, pointer: &str, object: Node| {
        let uri = object.get("uri").and_then(Node::as_str);
        if let Some((uri, Err(reason))) = uri.map(|uri| (uri, classify(uri))) {
            invalid_uri(ctx, &member(pointer, "uri"), uri, &reason);
        }
    };
    let buffers_read = |i: usize| collection != "buffers" || i < index;
    for (_, pointer, buffer) in ctx
        .objects("buffers")
        .take_while(|(i, ..)| buffers_read(*i))
    {
        unparsed(ctx, &pointer, buffer);
    }
    if collection != "images" {
        return;
    }
    let enabled = EnabledFormats {
        webp: ctx.uses_extension("EXT_texture_webp"),
        ktx2: false,
    };
    for (_, pointer, image) in ctx.objects("images").take_while(|(i, ..)| *i <= index) {
        check_image_members(ctx, &pointer, image, enabled);
        unparsed(ctx, &pointer, image);
    }
}

/// What a URI naming no file that is read is told: another scheme, an absolute path, a query
/// or fragment, an undecodable path, or any file when `files` is [`Files::Unfetched`].
fn unread_external(ctx: &mut Context, pointer: &str, uri: &str, kind: UriKind, files: Files) {
    let fetched = files != Files::Unfetched;
    match kind {
        // Another scheme is not fetched, and nothing more is said (as the validator's own
        // harness, which fetches only files, reports it).
        UriKind::NonRelative => ctx.emit(
            khronos::NON_RELATIVE_URI,
            pointer,
            format!(
                "Non-relative URI found: '{}'. It is not fetched.",
                shorten(uri)
            ),
        ),
        // An absolute path is non-relative to the validator, which then fails to read it;
        // gltfmat refuses to, as it leaves the asset's folder.
        UriKind::AbsolutePath => {
            non_relative(ctx, pointer, uri);
            if fetched {
                refuse_outside(ctx, pointer, uri);
            }
        }
        UriKind::QueryOrFragment => {
            non_relative(ctx, pointer, uri);
            if fetched {
                ctx.emit(
                    khronos::IO_ERROR,
                    pointer,
                    "Could not read resource: a URI with a query or fragment names no file.",
                );
            }
        }
        UriKind::Undecodable(why) if fetched => ctx.emit(
            khronos::IO_ERROR,
            pointer,
            format!("Could not read resource '{}': {why}.", shorten(uri)),
        ),
        UriKind::Undecodable(_) | UriKind::Relative(_) | UriKind::Data { .. } => {}
    }
}

/// A file named by a relative `uri` (at `path` in the asset's folder), with a diagnostic for
/// whatever stops it being read.
fn load_relative(
    ctx: &mut Context,
    pointer: &str,
    uri: &str,
    path: &str,
    keep_large: bool,
) -> Option<Kept> {
    let error = match read_relative(ctx.loader, path, keep_large) {
        Ok(kept) => return Some(kept),
        Err(error) => error,
    };
    match error {
        LoadError::OutsideFolder(_) => refuse_outside(ctx, pointer, uri),
        LoadError::NoFolder => ctx.emit(
            pass_codes::EXTERNAL_RESOURCE_NOT_READ,
            pointer,
            format!("'{uri}' was not read (no folder to resolve it in): what depends on it was not checked."),
        ),
        LoadError::NotFound(p) => ctx.emit(
            khronos::IO_ERROR,
            pointer,
            format!("Resource not found ({p})."),
        ),
        unreadable => ctx.emit(
            khronos::IO_ERROR,
            pointer,
            format!("Could not read resource: {unreadable}."),
        ),
    }
    None
}

fn read_relative(
    loader: &dyn ResourceLoader,
    path: &str,
    keep_large: bool,
) -> Result<Kept, LoadError> {
    if keep_large {
        loader.load_buffer(path)
    } else {
        loader.load(path).map(Kept::Read)
    }
}

/// Absolute paths and `..` escapes are never read.
/// NON_RELATIVE_URI for a URI gltfmat does not read.
fn non_relative(ctx: &mut Context, pointer: &str, uri: &str) {
    ctx.emit(
        khronos::NON_RELATIVE_URI,
        pointer,
        format!(
            "Non-relative URI found: '{}'. It is not read.",
            shorten(uri)
        ),
    );
}

fn refuse_outside(ctx: &mut Context, pointer: &str, uri: &str) {
    ctx.emit(
        pass_codes::URI_OUTSIDE_ASSET_FOLDER,
        pointer,
        format!(
            "Refused to read '{}': it resolves outside the asset's folder.",
            shorten(uri)
        ),
    );
}

fn shorten(uri: &str) -> String {
    if uri.chars().count() > 80 {
        format!("{}…", uri.chars().take(77).collect::<String>())
    } else {
        uri.to_string()
    }
}

fn align4(n: u64) -> u64 {
    n.div_ceil(4) * 4
}

/// Whether a buffer's data URI declares a binary media type; reported where it does not.
fn buffer_media_type_valid(ctx: &mut Context, media: &str, pointer: &str) -> bool {
    let lower = media.to_ascii_lowercase();
    if lower == "application/octet-stream" || lower == "application/gltf-buffer" {
        return true;
    }
    ctx.emit(
        khronos::BUFFER_DATA_URI_MIME_TYPE_INVALID,
        pointer,
        format!("Data URI media type must be 'application/octet-stream' or 'application/gltf-buffer'. Found '{media}' instead."),
    );
    false
}

pub(crate) fn check_buffers(ctx: &mut Context) {
    let buffers = ctx.items("buffers");
    ctx.buffers = buffers.iter().map(|_| None).collect();
    for (i, pointer, buffer) in ctx.objects("buffers") {
        // A GLB whose bytes end inside a chunk: what its JSON says of a URI is checked, and
        // nothing is loaded, as the validator's reader gives up its document there.
        if ctx.document.cut_short {
            if let Some(uri) = buffer.get("uri").and_then(Node::as_str) {
                let uri_pointer = member(&pointer, "uri");
                let (_, media_type, _) = load_uri(ctx, uri, &uri_pointer, Files::Unfetched);
                if let Some(media) = media_type {
                    buffer_media_type_valid(ctx, &media, &uri_pointer);
                }
            }
            continue;
        }
        let declared = unsigned(buffer, "byteLength");
        let Some((data, storage, uri)) = buffer_data(ctx, i, buffer, &pointer, declared) else {
            continue;
        };
        let short = match (&data, declared) {
            (Some(bytes), Some(length)) if (bytes.len() as u64) < length => {
                ctx.emit(
                    khronos::BUFFER_BYTE_LENGTH_MISMATCH,
                    pointer.clone(),
                    format!("Actual data byte length ({}) is less than the declared buffer byte length ({length}).", bytes.len()),
                );
                true
            }
            _ => false,
        };
        ctx.resources.push(ResourceInfo {
            pointer: pointer.clone(),
            storage,
            mime_type: Some("application/gltf-buffer".into()),
            byte_length: data.as_ref().map(|d| d.len()),
            uri,
            image: None,
        });
        // Shorter than it says, a file or a GLB chunk holds no data to read, as for the
        // Khronos validator (which still reads a data URI's).
        ctx.buffers[i] = data.filter(|_| !short || storage == "data-uri");
    }
}

/// Buffer `i`'s bytes as the validator resolves them, its storage and its external URI;
/// `None` where it names a GLB chunk the file does not have (reported).
fn buffer_data<'a>(
    ctx: &mut Context<'a>,
    i: usize,
    buffer: Node,
    pointer: &str,
    declared: Option<u64>,
) -> Option<(Option<BufferData<'a>>, &'static str, Option<String>)> {
    Some(match buffer.get("uri").and_then(Node::as_str) {
        // Without a declared length an external file is not read and the GLB chunk not
        // attached (a data URI is still decoded and used), as the Khronos validator reads it;
        // the URI is still parsed.
        Some(uri) if declared.is_none() && !uri.starts_with("data:") => {
            load_uri(ctx, uri, &member(pointer, "uri"), Files::Unfetched);
            (None, "external", Some(uri.to_string()))
        }
        Some(uri) => {
            let uri_pointer = member(pointer, "uri");
            let (data, media_type, storage) = load_uri(ctx, uri, &uri_pointer, Files::KeepLarge);
            // Data under another media type is not read.
            let data = data.filter(|_| match &media_type {
                Some(media) => buffer_media_type_valid(ctx, media, &uri_pointer),
                None => true,
            });
            let uri = (storage == "external").then(|| uri.to_string());
            (data.map(BufferData::Loaded), storage, uri)
        }
        // A buffer whose byteLength is not a valid length is not resolved at all (the
        // validator ignores it), so it cannot miss its chunk.
        None if i == 0
            && crate::check::is_glb(ctx.document)
            && declared.is_some_and(|n| n >= 1) =>
        {
            (Some(glb_chunk(ctx, pointer, declared)?), "glb", None)
        }
        None => (None, "buffer", None),
    })
}

/// The GLB's BIN chunk for the first buffer, its padding beyond `declared` reported; `None`
/// where the file has none (reported).
fn glb_chunk<'a>(
    ctx: &mut Context<'a>,
    pointer: &str,
    declared: Option<u64>,
) -> Option<BufferData<'a>> {
    let Some(bin) = ctx.document.bin_data() else {
        ctx.emit(
            khronos::BUFFER_MISSING_GLB_DATA,
            pointer,
            "Buffer refers to an unresolved GLB binary chunk.",
        );
        return None;
    };
    // An empty BIN chunk (GLB_EMPTY_BIN_CHUNK) holds 0 bytes: fewer than the buffer
    // declares. (One that ends the file cuts it short: see above.)
    let padded = align4(declared?);
    if bin.len() as u64 > padded {
        ctx.emit(
            khronos::BUFFER_GLB_CHUNK_TOO_BIG,
            pointer,
            format!(
                "GLB-stored BIN chunk contains {} extra padding byte(s).",
                bin.len() as u64 - padded
            ),
        );
    }
    Some(bin)
}

pub(crate) fn check_buffer_views(ctx: &mut Context) {
    for (_, pointer, view) in ctx.objects("bufferViews") {
        let buffer = ctx.reference(view, "buffer", &pointer, "buffers");
        let offset = unsigned(view, "byteOffset").unwrap_or(0);
        let length = unsigned(view, "byteLength");
        if let Some(b) = buffer {
            if let Some(buffer_length) = unsigned(ctx.items("buffers").at(b), "byteLength") {
                // A length that is no valid one (below 1, or unreadable) is the validator's
                // -1: the view is then too long only where it starts past the buffer's end.
                let end = match length.filter(|&l| l >= 1) {
                    Some(length) => offset.saturating_add(length),
                    None => offset.saturating_add(1),
                };
                if end > buffer_length {
                    let key = if offset >= buffer_length {
                        "byteOffset"
                    } else {
                        "byteLength"
                    };
                    ctx.emit(
                        khronos::BUFFER_VIEW_TOO_LONG,
                        member(&pointer, key),
                        format!(
                            "BufferView does not fit buffer ({b}) byteLength ({buffer_length})."
                        ),
                    );
                }
            }
        }
        if let Some(stride) = unsigned(view, "byteStride") {
            if length.is_some_and(|l| stride > l) {
                ctx.emit(
                    khronos::BUFFER_VIEW_TOO_BIG_BYTE_STRIDE,
                    member(&pointer, "byteStride"),
                    format!("Buffer view's byteStride ({stride}) is greater than byteLength."),
                );
            }
            if unsigned(view, "target") == Some(ELEMENT_ARRAY_BUFFER) {
                ctx.emit(
                    khronos::BUFFER_VIEW_INVALID_BYTE_STRIDE,
                    member(&pointer, "byteStride"),
                    "Only buffer views with raw vertex data can have byteStride.",
                );
            }
        }
    }
}

/// A buffer view's bytes, when its buffer was read and the range fits: read (from a large
/// GLB's file) only when asked, so a pass holds a view's bytes only while it walks them.
pub(crate) struct ViewData<'c> {
    buffer: &'c BufferData<'c>,
    range: std::ops::Range<usize>,
}

impl<'c> ViewData<'c> {
    pub(crate) fn len(&self) -> usize {
        self.range.len()
    }

    /// The bytes at `part` of the view (what one accessor needs of it).
    pub(crate) fn part(&self, part: std::ops::Range<usize>) -> Option<ViewData<'c>> {
        (part.start <= part.end && part.end <= self.len()).then(|| ViewData {
            buffer: self.buffer,
            range: self.range.start + part.start..self.range.start + part.end,
        })
    }

    /// Whether reading makes a copy (the bytes are in a file, not in memory).
    pub(crate) fn is_in_file(&self) -> bool {
        self.buffer.in_memory().is_none()
    }

    /// The bytes, borrowed when in memory; `None` when a file no longer holds them.
    pub(crate) fn read(&self) -> Option<Cow<'c, [u8]>> {
        self.buffer.get(self.range.clone())
    }
}

/// A buffer view's bytes, unread (see [`ViewData`]), when the view fits its buffer.
pub(crate) fn view_data<'c>(ctx: &'c Context, view_index: usize) -> Option<ViewData<'c>> {
    let data = view_data_in_buffer(ctx, view_index)?;
    let view = ctx.items("bufferViews").get(view_index)?;
    let declared = usize::try_from(unsigned(view, "byteLength")?).ok()?;
    (data.len() == declared).then_some(data)
}

/// A buffer view's bytes as far as its buffer holds them: the Khronos validator reads an
/// accessor's elements wherever they lie in the buffer, even through a view whose byteLength
/// runs past it (BUFFER_VIEW_TOO_LONG).
pub(crate) fn view_data_in_buffer<'c>(ctx: &'c Context, view_index: usize) -> Option<ViewData<'c>> {
    let view = ctx.items("bufferViews").get(view_index)?;
    let buffer = ctx
        .buffers
        .get(unsigned(view, "buffer")? as usize)?
        .as_ref()?;
    let start = usize::try_from(crate::gltf::byte_offset(view)?).ok()?;
    // A length past 2^64 (a valid integer to the schema) runs past any buffer.
    let length = unsigned(view, "byteLength").or_else(|| {
        let length = view.get("byteLength")?.as_f64()?;
        (length >= u64::MAX as f64).then_some(u64::MAX)
    })?;
    let end = start.saturating_add(usize::try_from(length).unwrap_or(usize::MAX));
    (start <= buffer.len()).then_some(ViewData {
        buffer,
        range: start..end.min(buffer.len()),
    })
}

/// The bytes of a buffer view, read now (see [`view_data`]).
pub(crate) fn view_bytes<'c>(ctx: &'c Context, view_index: usize) -> Option<Cow<'c, [u8]>> {
    view_data(ctx, view_index)?.read()
}

/// `length` bytes at `offset` in bufferView `view`, read as components of `size` bytes (an
/// accessor, or a part of a sparse one at `pointer`): the offset and the total offset
/// aligned to the component, and the bytes inside the view (ACCESSOR_TOO_LONG; a length
/// past 2^64 is `None`).
pub(super) fn fits_in_view(
    ctx: &mut Context,
    pointer: &str,
    view: usize,
    offset: u64,
    size: u64,
    length: Option<u64>,
) {
    let view_object = ctx.items("bufferViews").at(view);
    // A view without a readable byteLength holds nothing, as the Khronos validator reads it
    // (length -1): every accessor on it is too long, placed at its byteOffset.
    let view_length = unsigned(view_object, "byteLength");
    if !offset.is_multiple_of(size) {
        ctx.emit(
            khronos::ACCESSOR_OFFSET_ALIGNMENT,
            member(pointer, "byteOffset"),
            format!("Offset {offset} is not a multiple of componentType length {size}."),
        );
    }
    // A view's byteOffset that is there but no unsigned integer is read as -1, and the
    // validator then checks neither the total offset nor the length.
    let view_offset = match (
        view_object.get("byteOffset"),
        unsigned(view_object, "byteOffset"),
    ) {
        (None, _) => 0,
        (Some(_), Some(view_offset)) => view_offset,
        (Some(_), None) => return,
    };
    let total = view_offset.saturating_add(offset);
    if !total.is_multiple_of(size) {
        ctx.emit(
            khronos::ACCESSOR_TOTAL_OFFSET_ALIGNMENT,
            pointer,
            format!("Accessor's total byteOffset {total} isn't a multiple of componentType length {size}."),
        );
    }
    let fits = (length.and_then(|n| n.checked_add(offset)))
        .zip(view_length)
        .is_some_and(|(end, view_length)| end <= view_length);
    if !fits {
        let length = length.map_or_else(|| "more than 2^64".to_string(), |n| n.to_string());
        let at = if view_length.is_none_or(|l| offset > l) {
            member(pointer, "byteOffset")
        } else {
            pointer.to_string()
        };
        let view_length = view_length.map_or_else(|| "-1".to_string(), |l| l.to_string());
        ctx.emit(
            khronos::ACCESSOR_TOO_LONG,
            at,
            format!("Accessor (offset: {offset}, length: {length}) does not fit referenced bufferView [{view}] length {view_length}."),
        );
    }
}

/// The MIME type an image declares in its `mimeType`. (A data URI's media type is not
/// one: the validator reads one it does not accept as INVALID_URI, and an accepted one is
/// checked against the content instead.)
pub(crate) fn declared_mime(image: Node) -> Option<String> {
    image
        .get("mimeType")
        .and_then(Node::as_str)
        .map(str::to_string)
}

pub(crate) fn check_images(ctx: &mut Context) {
    ctx.images = vec![None; ctx.items("images").len()];
    ctx.image_bytes = ctx.items("images").iter().map(|_| None).collect();
    let enabled = EnabledFormats {
        webp: ctx.uses_extension("EXT_texture_webp"),
        // KHR_texture_basisu's schema adds image/ktx2 to image.mimeType; the released
        // validator does not know it.
        ktx2: ctx.options.profile.recognises_ktx2() && ctx.uses_extension("KHR_texture_basisu"),
    };
    let mut read_views = HashMap::new();
    for (i, pointer, image) in ctx.objects("images") {
        let mime_type = check_image_members(ctx, &pointer, image, enabled);
        let read = !ctx.images_left_to_extensions.contains(&i) && !ctx.document.cut_short;
        let Some(source) = image_source(ctx, &pointer, image, read, &mut read_views) else {
            continue;
        };
        let mut resource = ResourceInfo {
            pointer: pointer.clone(),
            storage: source.storage,
            mime_type: mime_type.map(str::to_string),
            byte_length: source.bytes.as_ref().map(|b| b.len()),
            uri: source.uri.clone(),
            image: None,
        };
        if let Some(bytes) = &source.bytes {
            if let Some(info) =
                check_image_header(ctx, &pointer, bytes, mime_type, &source, enabled)
            {
                resource.mime_type = Some(info.format.mime_type().to_string());
                resource.image = Some(info.clone());
                ctx.images[i] = Some(info);
                // Kept for gltfmat's rules: the pixel rules, and the colour-space rule, which
                // decodes an image two slots read differently.
                if ctx.options.profile.runs_rules() {
                    ctx.image_bytes[i] = Some(Arc::clone(bytes));
                }
            }
        }
        ctx.resources.push(resource);
    }
}

/// The image formats other than PNG and JPEG that an asset's extensions enable.
#[derive(Clone, Copy)]
struct EnabledFormats {
    webp: bool,
    ktx2: bool,
}

/// Checks that an image defines exactly one of `uri` and `bufferView` and names a known
/// `mimeType`; returns the `mimeType`.
fn check_image_members<'t>(
    ctx: &mut Context,
    pointer: &str,
    image: Node<'t>,
    enabled: EnabledFormats,
) -> Option<&'t str> {
    // Counted on the members as read: one of the wrong type is absent, so `{"uri": 5}`
    // defines neither and `{"uri": 5, "bufferView": 0}` one (the schema's `oneOf` would
    // count what is written).
    let defined = ["uri", "bufferView"]
        .iter()
        .filter(|m| image.get(**m).is_some());
    if defined.count() != 1 {
        ctx.emit(
            khronos::ONE_OF_MISMATCH,
            pointer.to_string(),
            "Exactly one of ('uri', 'bufferView') properties must be defined.",
        );
    }
    let mime_type = image.get("mimeType").and_then(Node::as_str);
    if image.get("bufferView").is_some() && mime_type.is_none() {
        ctx.emit(
            khronos::UNSATISFIED_DEPENDENCY,
            member(pointer, "bufferView"),
            "Dependency failed. 'mimeType' must be defined.",
        );
    }
    if let Some(m) = mime_type {
        let allowed = matches!(m, "image/png" | "image/jpeg")
            || (m == "image/webp" && enabled.webp)
            || (m == "image/ktx2" && enabled.ktx2);
        if !allowed {
            ctx.emit(
                khronos::VALUE_NOT_IN_LIST,
                member(pointer, "mimeType"),
                format!("Invalid value '{m}'. Valid values are ('image/jpeg', 'image/png')."),
            );
        }
    }
    mime_type
}

/// Where an image's bytes come from, and the bytes when they could be read.
struct ImageSource {
    bytes: Option<Arc<Bytes>>,
    storage: &'static str,
    /// An external file's URI.
    uri: Option<String>,
    /// Where a format that does not match is reported: the URI, or the buffer view.
    mime_pointer: String,
}

/// Reads an image from its URI or its buffer view (a view shared by several images is read
/// once); `None` when it has neither. Without `read`, what the image names is checked as
/// the validator parses it, and nothing is fetched: the source has no bytes.
fn image_source(
    ctx: &mut Context,
    pointer: &str,
    image: Node,
    read: bool,
    read_views: &mut HashMap<usize, Arc<Bytes>>,
) -> Option<ImageSource> {
    // The validator resolves a bufferView beside a uri too (ONE_OF_MISMATCH says the pair
    // is wrong), and reads the uri.
    let view = match image.get("bufferView") {
        Some(_) => ctx.reference(image, "bufferView", pointer, "bufferViews"),
        None => None,
    };
    if let Some(view) = view {
        if (ctx.items("bufferViews").at(view).get("byteStride")).is_some() {
            ctx.emit(
                khronos::IMAGE_BUFFER_VIEW_WITH_BYTESTRIDE,
                member(pointer, "bufferView"),
                "Buffer view used by an image must not have byteStride.",
            );
        }
    }
    if let Some(uri) = image.get("uri").and_then(Node::as_str) {
        let uri_pointer = member(pointer, "uri");
        let files = if read { Files::Read } else { Files::Unfetched };
        let (kept, media_type, storage) = load_uri(ctx, uri, &uri_pointer, files);
        let bytes = kept.and_then(|kept| match kept {
            Kept::Read(bytes) => Some(bytes),
            Kept::File(_) | Kept::Pieces(_) => None,
        });
        let bytes = bytes.filter(|bytes| match &media_type {
            Some(media) => data_matches_media_type(ctx, &uri_pointer, bytes, media),
            None => true,
        });
        let bytes = bytes.filter(|_| read);
        let uri = (storage == "external").then(|| uri.to_string());
        return Some(ImageSource {
            bytes,
            storage,
            uri,
            mime_pointer: uri_pointer,
        });
    }
    let view = view?;
    // Read once however many images share the view.
    let bytes = match read_views.get(&view) {
        _ if !read => None,
        Some(bytes) => Some(Arc::clone(bytes)),
        None => view_bytes(ctx, view).map(|bytes| Arc::new(bytes.into_owned().into())),
    };
    if let Some(bytes) = &bytes {
        read_views.insert(view, Arc::clone(bytes));
    }
    Some(ImageSource {
        bytes,
        storage: "buffer-view",
        uri: None,
        mime_pointer: member(pointer, "bufferView"),
    })
}

/// Whether a data URI's content is of the media type it declares, by the codec its first
/// bytes name, as the validator checks it when it parses the URI (case aside); where not,
/// the URI is invalid and its data is not read as an image.
fn data_matches_media_type(ctx: &mut Context, pointer: &str, data: &[u8], media: &str) -> bool {
    let found = image_header::codec_of(data).map(ImageFormat::mime_type);
    if found == Some(media.to_ascii_lowercase().as_str()) {
        return true;
    }
    let found = found.unwrap_or("no image format");
    ctx.emit(
        khronos::INVALID_URI,
        pointer,
        format!("Invalid URI. Parser output: the declared media type '{media}' does not match the embedded content ({found})."),
    );
    false
}

/// Reads an image's header and checks its format against what the asset declares and
/// enables; the header when the format is one the profile recognises.
fn check_image_header(
    ctx: &mut Context,
    pointer: &str,
    bytes: &[u8],
    mime_type: Option<&str>,
    source: &ImageSource,
    enabled: EnabledFormats,
) -> Option<ImageInfo> {
    let known = |format| format != ImageFormat::Ktx2 || ctx.options.profile.recognises_ktx2();
    let header = match image_header::codec_of(bytes).is_some_and(known) {
        true => image_header::read(bytes),
        false => Err(HeaderError::Unrecognized),
    };
    let info = match header {
        Ok(info) => info,
        Err(HeaderError::Unrecognized) => {
            let message = "Image format not recognized.";
            ctx.emit(
                khronos::IMAGE_UNRECOGNIZED_FORMAT,
                pointer.to_string(),
                message,
            );
            return None;
        }
        Err(HeaderError::UnexpectedEnd) => {
            let message = "Unexpected end of image stream.";
            ctx.emit(khronos::IMAGE_UNEXPECTED_EOS, pointer.to_string(), message);
            return None;
        }
        Err(HeaderError::Invalid(why)) => {
            let message = format!("Image data is invalid: {why}.");
            ctx.emit(khronos::IMAGE_DATA_INVALID, pointer.to_string(), message);
            return None;
        }
    };
    let found = info.format.mime_type();
    if let Some(declared) = mime_type.filter(|m| *m != found) {
        ctx.emit(
            khronos::IMAGE_MIME_TYPE_INVALID,
            source.mime_pointer.clone(),
            format!("Recognized image format '{found}' does not match declared image format '{declared}'."),
        );
    }
    if info.format == ImageFormat::Webp && !enabled.webp {
        ctx.emit(
            khronos::IMAGE_NON_ENABLED_MIME_TYPE,
            pointer.to_string(),
            "Image format 'image/webp' not enabled (declare EXT_texture_webp).",
        );
    }
    if info.has_unsupported_features() {
        ctx.emit(
            khronos::IMAGE_FEATURES_UNSUPPORTED,
            pointer.to_string(),
            "Image contains unsupported features like non-default colorspace information, non-square pixels, or animation.",
        );
    }
    if info.format != ImageFormat::Ktx2
        && (!info.width.is_power_of_two() || !info.height.is_power_of_two())
    {
        ctx.emit(
            khronos::IMAGE_NPOT_DIMENSIONS,
            pointer.to_string(),
            format!(
                "Image has non-power-of-two dimensions: {}x{}.",
                info.width, info.height
            ),
        );
    }
    Some(info)
}

/// The images whose `extensions` object, as written, has a member the Khronos validator
/// keeps (mistyped, undeclared and unknown ones too; not a declared extension it knows,
/// which it reports as unexpected on an image and drops): it leaves those images to their
/// extensions and neither fetches nor parses their data.
pub(crate) fn images_with_extensions(
    root: Node,
    declared: &hashbrown::HashSet<&str>,
) -> std::collections::HashSet<usize> {
    let kept = |name: &str| !(declared.contains(&name) && super::extensions::khronos_knows(name));
    let images = root.get("images").and_then(Node::as_array);
    (images.into_iter().flatten().enumerate())
        .filter(|(_, image)| {
            let extensions = image.get("extensions").and_then(Node::as_object);
            extensions.is_some_and(|e| e.keys().any(kept))
        })
        .map(|(i, _)| i)
        .collect()
}
