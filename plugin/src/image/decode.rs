//! Decoding image files and bytes under size limits: a file never claims more memory than the
//! limits allow, and a broken file is an error, never a panic.

use std::path::Path;

use image::DynamicImage;

use super::ImageError;
use super::budget::ImageBudget;
use crate::files::FileError;

/// Longest side, in pixels, of an image file the loader decodes: twice the largest texture
/// limit of today's GPUs, so any texture a device can hold loads (and larger ones are halved
/// to fit on upload), while a file declaring an absurd size is refused before it is allocated.
pub const MAX_IMAGE_SIDE: u32 = 32_768;

/// Most pixels of an image file the loader decodes (a 16384 × 8192 image): the mip chain is
/// built in floats, so this bounds the memory one file can claim.
pub const MAX_IMAGE_PIXELS: u64 = 1 << 27;

/// Refuses a size over [`MAX_IMAGE_SIDE`] or [`MAX_IMAGE_PIXELS`] before anything is allocated
/// for it; the error names the image `name`.
pub(crate) fn check_size(name: &str, width: u32, height: u32) -> Result<(), ImageError> {
    if width > MAX_IMAGE_SIDE
        || height > MAX_IMAGE_SIDE
        || u64::from(width) * u64::from(height) > MAX_IMAGE_PIXELS
    {
        return Err(ImageError::TooLarge {
            name: name.to_owned(),
            width,
            height,
            max_side: MAX_IMAGE_SIDE,
            max_pixels: MAX_IMAGE_PIXELS,
        });
    }
    Ok(())
}

pub(super) fn load_error(name: &str, error: impl std::fmt::Display) -> ImageError {
    ImageError::Load {
        path: name.into(),
        reason: error.to_string(),
    }
}

/// Reads (a regular file, within [`crate::files::MAX_IMAGE_FILE_BYTES`]) and decodes `path`;
/// returns the image and the file's size.
pub(super) fn decode_file(
    path: &Path,
    budget: &mut ImageBudget,
) -> Result<(DynamicImage, u64), ImageError> {
    let name = path.display().to_string();
    let bytes =
        crate::files::read_bounded(path, crate::files::MAX_IMAGE_FILE_BYTES).map_err(|error| {
            match error {
                FileError::Io { reason, .. } => load_error(&name, reason),
                other => load_error(&name, other),
            }
        })?;
    // As `ImageReader::open` does: the extension names the format when the content cannot.
    let decoded = decode_bytes(
        &bytes,
        &name,
        (image::ImageFormat::from_path(path).ok(), TEXTURE_FORMATS),
        budget,
    )?;
    Ok((decoded, bytes.len() as u64))
}

/// Most bytes a decoder may allocate beyond the decoded pixels (its row buffers, a PNG's
/// compressed metadata such as an ICC profile), and all it may allocate to read a header.
const DECODER_SLACK_BYTES: u64 = 16 << 20;

/// The formats textures are decoded from: 8- and 16-bit images. Float images (Radiance `.hdr`,
/// OpenEXR) are environments' ([`crate::EnvironmentLight::from_file`]), not textures.
pub(crate) const TEXTURE_FORMATS: &[image::ImageFormat] =
    &[image::ImageFormat::Png, image::ImageFormat::Jpeg];

/// The formats an environment is decoded from.
pub(crate) const ENVIRONMENT_FORMATS: &[image::ImageFormat] =
    &[image::ImageFormat::Hdr, image::ImageFormat::OpenExr];

/// Reads the header first and refuses a format outside `formats`, sizes over [`MAX_IMAGE_SIDE`] / [`MAX_IMAGE_PIXELS`] and
/// what would pass `budget`, then decodes with allocations capped at the decoded size (so a
/// header that lies, or metadata that inflates, is caught by the decoder too).
pub(crate) fn decode_bytes(
    bytes: &[u8],
    name: &str,
    (format_hint, formats): (Option<image::ImageFormat>, &[image::ImageFormat]),
    budget: &mut ImageBudget,
) -> Result<DynamicImage, ImageError> {
    check_png_palette(bytes).map_err(|reason| load_error(name, reason))?;
    let reader = |limits: image::Limits| {
        let mut reader = image::ImageReader::new(std::io::Cursor::new(bytes));
        if let Some(format) = format_hint {
            reader.set_format(format);
        }
        let mut reader = reader
            .with_guessed_format()
            .map_err(|error| load_error(name, error))?;
        if let Some(format) = reader.format().filter(|format| !formats.contains(format)) {
            return Err(load_error(
                name,
                format!("the format {format:?} is not supported here (only {formats:?})"),
            ));
        }
        reader.limits(limits);
        Ok(reader)
    };
    let mut limits = image::Limits::default();
    let header = {
        use image::ImageDecoder;
        // No size limits yet: the header's size is checked below, with its own message.
        limits.max_alloc = Some(DECODER_SLACK_BYTES);
        let reader = reader(limits.clone())?;
        without_panics(name, || {
            let decoder = reader.into_decoder()?;
            Ok((decoder.dimensions(), decoder.color_type().bytes_per_pixel()))
        })?
    };
    let ((width, height), bytes_per_texel) = header;
    check_size(name, width, height)?;
    let decoded_bytes = budget.reserve_decode(
        name,
        bytes.len() as u64,
        (width, height),
        u64::from(bytes_per_texel),
    )?;
    limits.max_image_width = Some(MAX_IMAGE_SIDE);
    limits.max_image_height = Some(MAX_IMAGE_SIDE);
    limits.max_alloc = Some(decoded_bytes + DECODER_SLACK_BYTES);
    let reader = reader(limits)?;
    without_panics(name, || reader.decode())
}

/// Runs `step` of the image crate's decoders with a panic turned into an error naming `name`:
/// zune-jpeg 0.5 overflows on some malformed JPEGs (found by fuzzing; a panic in debug
/// builds), and the header readers of formats not fuzzed here may too. A broken file is an
/// error, not a crash.
fn without_panics<T>(
    name: &str,
    step: impl FnOnce() -> image::ImageResult<T>,
) -> Result<T, ImageError> {
    std::panic::catch_unwind(std::panic::AssertUnwindSafe(step))
        .unwrap_or_else(|_| {
            Err(image::ImageError::Decoding(
                image::error::DecodingError::from_format_hint(
                    image::error::ImageFormatHint::Unknown,
                ),
            ))
        })
        .map_err(|error| load_error(name, error))
}

/// A PNG palette (PLTE) must hold whole RGB entries: png 0.18 panics on a partial one (found
/// by fuzzing).
fn check_png_palette(bytes: &[u8]) -> Result<(), String> {
    let Some(mut chunks) = bytes.strip_prefix(b"\x89PNG\r\n\x1a\n") else {
        return Ok(());
    };
    // Each chunk: 4-byte big-endian length, 4-byte type, data, 4-byte CRC.
    while let [l0, l1, l2, l3, t0, t1, t2, t3, rest @ ..] = chunks {
        let length = u32::from_be_bytes([*l0, *l1, *l2, *l3]) as usize;
        if [*t0, *t1, *t2, *t3] == *b"PLTE" && !length.is_multiple_of(3) {
            return Err(format!(
                "the PNG palette (PLTE) has {length} bytes, not a whole number of RGB entries"
            ));
        }
        let Some(next) = rest.get(length.saturating_add(4)..) else {
            break;
        };
        chunks = next;
    }
    Ok(())
}
