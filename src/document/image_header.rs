//! Image headers (PNG, JPEG, WebP, KTX2) read without decoding pixels: format, size,
//! channels, bit depth and colour tagging — what the channel and colour-space rules need.

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ImageFormat {
    Png,
    Jpeg,
    Webp,
    Ktx2,
}

impl ImageFormat {
    pub fn mime_type(self) -> &'static str {
        match self {
            ImageFormat::Png => "image/png",
            ImageFormat::Jpeg => "image/jpeg",
            ImageFormat::Webp => "image/webp",
            ImageFormat::Ktx2 => "image/ktx2",
        }
    }
}

/// Channel layout, named as in the Khronos report (`info.resources[].image.format`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Channels {
    Luminance,
    LuminanceAlpha,
    Rgb,
    Rgba,
    Unknown,
}

impl Channels {
    pub fn name(self) -> &'static str {
        match self {
            Channels::Luminance => "luminance",
            Channels::LuminanceAlpha => "luminanceAlpha",
            Channels::Rgb => "rgb",
            Channels::Rgba => "rgba",
            Channels::Unknown => "unknown",
        }
    }

    pub fn has_alpha(self) -> bool {
        matches!(self, Channels::LuminanceAlpha | Channels::Rgba)
    }

    pub fn is_grey(self) -> bool {
        matches!(self, Channels::Luminance | Channels::LuminanceAlpha)
    }
}

/// Transfer function the file declares, when it declares one.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Transfer {
    Srgb,
    Linear,
    /// A gAMA value that is neither sRGB-like nor linear, or an ICC profile.
    Custom,
}

/// What an image header says, without decoding pixels.
#[derive(Debug, Clone, PartialEq)]
pub struct ImageInfo {
    /// The container format.
    pub format: ImageFormat,
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Which channels the pixels hold.
    pub channels: Channels,
    /// Bits per channel.
    pub bits: u8,
    /// The transfer function the file declares, if any.
    pub transfer: Option<Transfer>,
    /// An animated WebP (the Khronos validator does not read APNG's animation chunk).
    pub animated: bool,
    /// Colour primaries other than sRGB's (PNG cHRM or iCCP, WebP ICC profile).
    pub custom_primaries: bool,
    /// PNG pHYs with different horizontal and vertical densities.
    pub non_square_pixels: bool,
    /// A KTX2's container fields that KHR_texture_basisu constrains.
    pub ktx2: Option<Ktx2Layout>,
}

/// What a KTX2 header and data format descriptor say of its layout.
#[derive(Debug, Clone, PartialEq)]
pub struct Ktx2Layout {
    /// vkFormat: 0 (undefined) for Basis Universal.
    pub vk_format: u32,
    /// supercompressionScheme: 1 BasisLZ, 2 Zstandard, 0 none.
    pub supercompression: u32,
    /// pixelDepth, layerCount, faceCount.
    pub depth: u32,
    pub layers: u32,
    pub faces: u32,
    /// levelCount (0: "the loader generates them").
    pub levels: u32,
    /// The first level's uncompressedByteLength (what a Zstandard level inflates to).
    pub first_level_uncompressed: u64,
    /// The descriptor's colour model and each sample's channel id, when it could be read.
    pub model: Option<u8>,
    pub channel_ids: Vec<u8>,
}

impl Ktx2Layout {
    /// A 2D texture: no depth, array layers or cube faces (KHR_texture_basisu: "MUST be of 2D
    /// type").
    pub fn is_2d(&self) -> bool {
        self.depth <= 1 && self.layers <= 1 && self.faces == 1
    }
}

impl ImageInfo {
    /// An image with no colour tagging, animation or pixel-aspect information.
    fn plain(format: ImageFormat, width: u32, height: u32, channels: Channels, bits: u8) -> Self {
        ImageInfo {
            format,
            width,
            height,
            channels,
            bits,
            transfer: None,
            animated: false,
            custom_primaries: false,
            non_square_pixels: false,
            ktx2: None,
        }
    }

    /// The mip levels from this size down to 1×1.
    pub fn full_mip_levels(&self) -> u32 {
        32 - self.width.max(self.height).max(1).leading_zeros()
    }

    /// What the Khronos validator calls unsupported features: custom colour information,
    /// non-square pixels or animation (glTF ignores them all, so the image may not look as
    /// its author saw it).
    pub fn has_unsupported_features(&self) -> bool {
        self.custom_primaries
            || self.transfer == Some(Transfer::Custom)
            || self.non_square_pixels
            || self.animated
    }
}

/// sRGB primaries as PNG cHRM stores them (x, y × 100000): white, red, green, blue.
const SRGB_CHROMATICITIES: [u32; 8] = [31270, 32900, 64000, 33000, 30000, 60000, 15000, 6000];

#[derive(Debug, Clone, PartialEq)]
pub(crate) enum HeaderError {
    Unrecognized,
    UnexpectedEnd,
    Invalid(String),
}

/// The signature a PNG file starts with.
const PNG_MAGIC: &[u8] = b"\x89PNG\r\n\x1a\n";

/// The identifier a KTX 2.0 file starts with.
pub(crate) const KTX2_MAGIC: &[u8] = b"\xABKTX 20\xBB\r\n\x1A\n";

/// The format a file's first bytes name, as the Khronos validator detects a data URI's codec
/// (at least 14 bytes; JPEG by its first marker, WebP by its RIFF form and VP8 chunk); no
/// header is read.
pub(crate) fn codec_of(bytes: &[u8]) -> Option<ImageFormat> {
    let b = bytes.get(..14)?;
    if b.starts_with(&[0xFF, 0xD8, 0xFF]) {
        Some(ImageFormat::Jpeg)
    } else if b.starts_with(PNG_MAGIC) {
        Some(ImageFormat::Png)
    } else if &b[..4] == b"RIFF" && &b[8..14] == b"WEBPVP" {
        Some(ImageFormat::Webp)
    } else if b.starts_with(KTX2_MAGIC) {
        Some(ImageFormat::Ktx2)
    } else {
        None
    }
}

/// The header of an image in a format [`codec_of`] recognises.
pub(crate) fn read(bytes: &[u8]) -> Result<ImageInfo, HeaderError> {
    match codec_of(bytes) {
        Some(ImageFormat::Png) => png(bytes),
        Some(ImageFormat::Jpeg) => jpeg(bytes),
        Some(ImageFormat::Webp) => webp(bytes),
        Some(ImageFormat::Ktx2) => ktx2(bytes),
        None => Err(HeaderError::Unrecognized),
    }
}

fn be32(b: &[u8], at: usize) -> Result<u32, HeaderError> {
    b.get(at..at + 4)
        .map(|s| u32::from_be_bytes([s[0], s[1], s[2], s[3]]))
        .ok_or(HeaderError::UnexpectedEnd)
}

fn le32(b: &[u8], at: usize) -> Result<u32, HeaderError> {
    b.get(at..at + 4)
        .map(|s| u32::from_le_bytes([s[0], s[1], s[2], s[3]]))
        .ok_or(HeaderError::UnexpectedEnd)
}

/// A PNG's header chunks, read as the Khronos validator reads them: chunk after chunk up to
/// the first IDAT, in any order (the last IHDR wins), each colour chunk of a wrong length
/// invalid as soon as its type is read, an unknown colour type an unknown format.
fn png(b: &[u8]) -> Result<ImageInfo, HeaderError> {
    let mut pos = 8;
    let mut header: Option<&[u8]> = None;
    let mut has_trns = false;
    let mut transfer: Option<Transfer> = None;
    let mut custom_primaries: Option<bool> = None;
    let mut non_square_pixels = false;
    loop {
        let length = be32(b, pos)? as usize;
        let kind = b.get(pos + 4..pos + 8).ok_or(HeaderError::UnexpectedEnd)?;
        let required = match kind {
            b"IHDR" => Some(13),
            b"cHRM" => Some(32),
            b"sRGB" => Some(1),
            b"pHYs" => Some(9),
            b"gAMA" => Some(4),
            _ => None,
        };
        if required.is_some_and(|r| r != length) {
            return Err(HeaderError::Invalid("wrong PNG chunk length".into()));
        }
        match kind {
            b"IDAT" => break,
            b"tRNS" => has_trns = true,
            b"iCCP" => (transfer, custom_primaries) = (Some(Transfer::Custom), Some(true)),
            _ => {}
        }
        let data_start = pos + 8;
        let data = (b.get(data_start..data_start.saturating_add(length)))
            .ok_or(HeaderError::UnexpectedEnd)?;
        match kind {
            b"IHDR" => header = Some(data),
            b"sRGB" => (transfer, custom_primaries) = (Some(Transfer::Srgb), Some(false)),
            b"cHRM" if custom_primaries.is_none() => {
                let values: Vec<u32> = (0..8)
                    .map(|i| be32(data, i * 4))
                    .collect::<Result<_, _>>()?;
                custom_primaries = Some(values != SRGB_CHROMATICITIES);
            }
            b"gAMA" if transfer.is_none() => {
                transfer = Some(match be32(data, 0)? {
                    45455 => Transfer::Srgb,
                    100000 => Transfer::Linear,
                    _ => Transfer::Custom,
                });
            }
            b"pHYs" => non_square_pixels = be32(data, 0)? != be32(data, 4)?,
            _ => {}
        }
        pos = data_start + length + 4;
    }
    let header = header.ok_or_else(|| HeaderError::Invalid("PNG header not found".into()))?;
    let channels = match (header[9], has_trns) {
        (0, false) => Channels::Luminance,
        (0, true) | (4, _) => Channels::LuminanceAlpha,
        (2 | 3, false) => Channels::Rgb,
        (2 | 3, true) | (6, _) => Channels::Rgba,
        _ => Channels::Unknown,
    };
    let (width, height) = (be32(header, 0)?, be32(header, 4)?);
    let mut info = ImageInfo::plain(ImageFormat::Png, width, height, channels, header[8]);
    info.transfer = transfer;
    info.custom_primaries = custom_primaries.unwrap_or(false);
    info.non_square_pixels = non_square_pixels;
    Ok(info)
}

/// A JPEG's frame header, read as the Khronos validator reads it: after the first 0xFF (which
/// [`codec_of`] has seen), each byte where a marker may stand is one (fill bytes and markers without a segment are
/// passed over), each segment skipped by its length, until a start-of-frame segment
/// (C0–CF but C4, C8 and CC, or DE), whose component count must be 1 or 3.
fn jpeg(b: &[u8]) -> Result<ImageInfo, HeaderError> {
    let has_segment = |m: u8| !matches!(m, 0x01 | 0xD0..=0xD9 | 0xFF);
    let is_frame = |m: u8| (m & 0xF0 == 0xC0 && !matches!(m, 0xC4 | 0xC8 | 0xCC)) || m == 0xDE;
    let mut pos = 1;
    loop {
        let marker = *b.get(pos).ok_or(HeaderError::UnexpectedEnd)?;
        pos += 1;
        if !has_segment(marker) {
            continue;
        }
        let length = usize::from(u16::from_be_bytes([
            *b.get(pos).ok_or(HeaderError::UnexpectedEnd)?,
            *b.get(pos + 1).ok_or(HeaderError::UnexpectedEnd)?,
        ]));
        if length < 2 {
            return Err(HeaderError::Invalid(
                "invalid JPEG marker segment length".into(),
            ));
        }
        let segment = pos + 2..pos + length;
        if is_frame(marker) {
            let s = b.get(segment).ok_or(HeaderError::UnexpectedEnd)?;
            let channels = match s.get(5) {
                Some(3) => Channels::Rgb,
                Some(1) => Channels::Luminance,
                _ => {
                    return Err(HeaderError::Invalid(
                        "invalid number of JPEG colour channels".into(),
                    ))
                }
            };
            return Ok(ImageInfo::plain(
                ImageFormat::Jpeg,
                u32::from(u16::from_be_bytes([s[3], s[4]])),
                u32::from(u16::from_be_bytes([s[1], s[2]])),
                channels,
                s[0],
            ));
        }
        pos = segment.end;
    }
}

fn webp(b: &[u8]) -> Result<ImageInfo, HeaderError> {
    let kind = b.get(12..16).ok_or(HeaderError::UnexpectedEnd)?;
    let d = 20;
    let (width, height, alpha, animated, icc) = match kind {
        b"VP8 " => {
            let s = b.get(d + 6..d + 10).ok_or(HeaderError::UnexpectedEnd)?;
            let w = u16::from_le_bytes([s[0], s[1]]) & 0x3FFF;
            let h = u16::from_le_bytes([s[2], s[3]]) & 0x3FFF;
            (w as u32, h as u32, false, false, false)
        }
        b"VP8L" => {
            let bits = le32(b, d + 1)?;
            (
                (bits & 0x3FFF) + 1,
                ((bits >> 14) & 0x3FFF) + 1,
                (bits >> 28) & 1 == 1,
                false,
                false,
            )
        }
        b"VP8X" => {
            let flags = *b.get(d).ok_or(HeaderError::UnexpectedEnd)?;
            let s = b.get(d + 4..d + 10).ok_or(HeaderError::UnexpectedEnd)?;
            let w = u32::from_le_bytes([s[0], s[1], s[2], 0]) + 1;
            let h = u32::from_le_bytes([s[3], s[4], s[5], 0]) + 1;
            (
                w,
                h,
                flags & 0x10 != 0,
                flags & 0x02 != 0,
                flags & 0x20 != 0,
            )
        }
        // The validator reads 30 bytes (VP8 and VP8X need them; 25 where the chunk's fourth
        // letter is VP8L's) before it calls a chunk unknown.
        _ if b.len() < 25 || (b.len() < 30 && b[15] != b'L') => {
            return Err(HeaderError::UnexpectedEnd)
        }
        _ => return Err(HeaderError::Invalid("unknown WebP chunk".into())),
    };
    let channels = if alpha { Channels::Rgba } else { Channels::Rgb };
    let mut info = ImageInfo::plain(ImageFormat::Webp, width, height, channels, 8);
    info.animated = animated;
    if icc {
        info.custom_primaries = true;
        info.transfer = Some(Transfer::Custom);
    }
    Ok(info)
}

/// A KTX2 header: its size, and from its data format descriptor (when it can be read) the
/// channels a texel holds and the transfer function, which a viewer applies as it samples
/// (an sRGB KTX2 is decoded to linear by the GPU, whatever slot it is bound to).
fn ktx2(b: &[u8]) -> Result<ImageInfo, HeaderError> {
    let (width, height) = (le32(b, 20)?, le32(b, 24)?);
    let mut info = ImageInfo::plain(ImageFormat::Ktx2, width, height, Channels::Unknown, 8);
    let word = |at| le32(b, at).unwrap_or(0);
    let mut layout = Ktx2Layout {
        vk_format: word(12),
        supercompression: word(44),
        depth: word(28),
        layers: word(32),
        faces: word(36),
        levels: word(40),
        // The level index starts at byte 80: byteOffset, byteLength, uncompressedByteLength.
        first_level_uncompressed: u64::from(word(96)) | u64::from(word(100)) << 32,
        model: None,
        channel_ids: Vec::new(),
    };
    if let Some(descriptor) = ktx2_descriptor(b) {
        info.channels = ktx2_channels(descriptor.model, &descriptor.channel_ids);
        info.transfer = match descriptor.transfer {
            KHR_DF_TRANSFER_SRGB => Some(Transfer::Srgb),
            KHR_DF_TRANSFER_LINEAR => Some(Transfer::Linear),
            _ => None,
        };
        layout.model = Some(descriptor.model);
        layout.channel_ids = descriptor.channel_ids;
    }
    info.ktx2 = Some(layout);
    Ok(info)
}

const KHR_DF_TRANSFER_LINEAR: u8 = 1;
const KHR_DF_TRANSFER_SRGB: u8 = 2;
const KHR_DF_MODEL_RGBSDA: u8 = 1;
pub(crate) const KHR_DF_MODEL_ETC1S: u8 = 163;
pub(crate) const KHR_DF_MODEL_UASTC: u8 = 166;

/// What gltfmat reads of a KTX2's basic data format descriptor block.
struct Descriptor {
    model: u8,
    transfer: u8,
    /// Each sample's channel id (its channelType without the qualifier bits).
    channel_ids: Vec<u8>,
}

/// The first descriptor block (KTX 2.0 §3.10 and the Khronos Data Format specification's
/// basic block: model, primaries, transfer and flags at byte 8 of the block, then 16-byte
/// samples from byte 24, their channel type at byte 3), or None where the file does not hold
/// one within its bytes.
fn ktx2_descriptor(b: &[u8]) -> Option<Descriptor> {
    let offset = le32(b, 48).ok()? as usize;
    let block = b.get(offset.checked_add(4)?..)?;
    let size = usize::from(u16::from_le_bytes([*block.get(6)?, *block.get(7)?]));
    let block = block.get(..size)?;
    let samples = block.get(24..)?.chunks_exact(16);
    Some(Descriptor {
        model: *block.get(8)?,
        transfer: *block.get(10)?,
        channel_ids: samples.map(|sample| sample[3] & 0x0F).collect(),
    })
}

/// The channels of a KTX2 texel as decoded to RGBA, from the descriptor's channel ids per
/// colour model (KHR_texture_basisu's layouts; RGBSDA's R, G, B, A for plain formats).
fn ktx2_channels(model: u8, ids: &[u8]) -> Channels {
    match (model, ids) {
        // ETC1S: one slice of RGB (0) or RRR (3), and an optional second of AAA (15) or GGG (4),
        // which the transcoder puts in alpha.
        (KHR_DF_MODEL_ETC1S, [0]) => Channels::Rgb,
        (KHR_DF_MODEL_ETC1S, [0, 15]) => Channels::Rgba,
        (KHR_DF_MODEL_ETC1S, [3]) => Channels::Luminance,
        (KHR_DF_MODEL_ETC1S, [3, 4 | 15]) => Channels::LuminanceAlpha,
        // UASTC: one sample, RGB (0), RGBA (3), RRR (4), RRRG (5).
        (KHR_DF_MODEL_UASTC, [0]) => Channels::Rgb,
        (KHR_DF_MODEL_UASTC, [3]) => Channels::Rgba,
        (KHR_DF_MODEL_UASTC, [4]) => Channels::Luminance,
        (KHR_DF_MODEL_UASTC, [5]) => Channels::LuminanceAlpha,
        (KHR_DF_MODEL_RGBSDA, [0, 1, 2]) => Channels::Rgb,
        (KHR_DF_MODEL_RGBSDA, [0, 1, 2, 15]) => Channels::Rgba,
        _ => Channels::Unknown,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn png_bytes(colour_type: u8, extra: &[(&[u8; 4], &[u8])]) -> Vec<u8> {
        let mut out = PNG_MAGIC.to_vec();
        let mut chunk = |kind: &[u8; 4], data: &[u8]| {
            out.extend_from_slice(&(data.len() as u32).to_be_bytes());
            out.extend_from_slice(kind);
            out.extend_from_slice(data);
            out.extend_from_slice(&[0; 4]);
        };
        let mut ihdr = Vec::new();
        ihdr.extend_from_slice(&4u32.to_be_bytes());
        ihdr.extend_from_slice(&2u32.to_be_bytes());
        ihdr.extend_from_slice(&[8, colour_type, 0, 0, 0]);
        chunk(b"IHDR", &ihdr);
        for (k, d) in extra {
            chunk(k, d);
        }
        chunk(b"IDAT", &[]);
        chunk(b"IEND", &[]);
        out
    }

    #[test]
    fn png_channels_and_transfer_are_read() {
        let info = read(&png_bytes(2, &[(b"gAMA", &100000u32.to_be_bytes())])).unwrap();
        assert_eq!(
            (info.width, info.height, info.channels),
            (4, 2, Channels::Rgb)
        );
        assert_eq!(info.transfer, Some(Transfer::Linear));
        assert_eq!(
            read(&png_bytes(0, &[(b"tRNS", &[0, 0])])).unwrap().channels,
            Channels::LuminanceAlpha
        );
    }

    #[test]
    fn a_png_is_read_up_to_its_first_idat_as_the_validator_reads_it() {
        let bytes = png_bytes(2, &[]);
        let idat = bytes.windows(4).position(|w| w == b"IDAT").unwrap();
        assert!(
            read(&bytes[..idat + 4]).is_ok(),
            "nothing after IDAT's type is read"
        );
        assert_eq!(read(&bytes[..idat + 3]), Err(HeaderError::UnexpectedEnd));
        let invalid = |extra: &[(&[u8; 4], &[u8])]| {
            matches!(read(&png_bytes(2, extra)), Err(HeaderError::Invalid(_)))
        };
        assert!(
            invalid(&[(b"sRGB", &[0, 0])]),
            "a colour chunk of a wrong length"
        );
        assert!(invalid(&[(b"cHRM", &[0; 8])]));
        assert!(!invalid(&[(b"acTL", &[0; 8])]));
        assert!(!read(&png_bytes(2, &[(b"acTL", &[0; 8])])).unwrap().animated);
        assert_eq!(
            read(&png_bytes(7, &[])).unwrap().channels,
            Channels::Unknown
        );
    }

    #[test]
    fn a_jpeg_is_read_marker_after_segment_to_its_frame_header() {
        let frame = |marker: u8, components: u8| {
            let mut b = vec![0xFF, 0xD8, 0xFF, 0xE0, 0, 4, 1, 2];
            // The byte after a segment is taken as a marker, with or without 0xFF before it.
            b.extend([marker, 0, 8, 8, 0, 2, 0, 3, components]);
            b
        };
        let info = read(&frame(0xC0, 3)).unwrap();
        assert_eq!(
            (info.width, info.height, info.channels),
            (3, 2, Channels::Rgb)
        );
        assert!(read(&frame(0xDE, 1)).is_ok(), "DHP carries a frame header");
        assert!(matches!(
            read(&frame(0xC2, 2)),
            Err(HeaderError::Invalid(_))
        ));
        assert_eq!(read(&frame(0xC4, 3)), Err(HeaderError::UnexpectedEnd));
    }

    #[test]
    fn truncated_and_unknown_data_are_errors() {
        let bytes = png_bytes(6, &[]);
        assert_eq!(read(&bytes[..20]), Err(HeaderError::UnexpectedEnd));
        assert_eq!(read(b"GIF89a"), Err(HeaderError::Unrecognized));
    }

    #[test]
    fn a_ktx1_file_is_not_taken_for_ktx2() {
        let mut ktx1 = b"\xABKTX 11\xBB\r\n\x1A\n".to_vec();
        ktx1.extend([0; 64]);
        assert_eq!(read(&ktx1), Err(HeaderError::Unrecognized));
        let mut ktx2 = b"\xABKTX 20\xBB\r\n\x1A\n".to_vec();
        ktx2.extend([0; 8]);
        ktx2.extend(4u32.to_le_bytes());
        ktx2.extend(2u32.to_le_bytes());
        let info = read(&ktx2).unwrap();
        assert_eq!(
            (info.format.mime_type(), info.width, info.height),
            ("image/ktx2", 4, 2)
        );
    }
}
