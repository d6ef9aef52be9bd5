//! Decoding image files and bytes under size limits: a file never claims more memory than the
//! limits allow, and a broken file is an error, never a panic.

use std::path::Path;

use image::DynamicImage;

use super::ImageError;

/// Longest side, in pixels, of an image file the loader decodes: twice the largest texture
/// limit of today's GPUs, so any texture a device can hold loads (and larger ones are halved
/// to fit on upload), while a file declaring an absurd size is refused before it is allocated.
pub const MAX_IMAGE_SIDE: u32 = 32_768;

/// Most pixels of an image file the loader decodes (a 16384 × 8192 image): the mip chain is
/// built in floats, so this bounds the memory one file can claim.
pub const MAX_IMAGE_PIXELS: u64 = 1 << 27;

pub(super) fn load_error(name: &str, error: impl std::fmt::Display) -> ImageError {
    ImageError::Load {
        path: name.into(),
        reason: error.to_string(),
    }
}

pub(super) fn decode_file(path: &Path) -> Result<DynamicImage, ImageError> {
    let name = path.display().to_string();
    let bytes = std::fs::read(path).map_err(|error| load_error(&name, error))?;
    // As `ImageReader::open` does: the extension names the format when the content cannot.
    decode_bytes(&bytes, &name, image::ImageFormat::from_path(path).ok())
}

/// Reads the header first and refuses sizes over [`MAX_IMAGE_SIDE`] / [`MAX_IMAGE_PIXELS`],
/// then decodes under the same limits (so a header that lies is caught by the decoder too).
pub(super) fn decode_bytes(
    bytes: &[u8],
    name: &str,
    format_hint: Option<image::ImageFormat>,
) -> Result<DynamicImage, ImageError> {
    check_png_palette(bytes).map_err(|reason| load_error(name, reason))?;
    let guessed = || {
        let mut reader = image::ImageReader::new(std::io::Cursor::new(bytes));
        if let Some(format) = format_hint {
            reader.set_format(format);
        }
        reader
            .with_guessed_format()
            .map_err(|error| load_error(name, error))
    };
    let (width, height) = guessed()?
        .into_dimensions()
        .map_err(|error| load_error(name, error))?;
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
    let mut limits = image::Limits::default();
    limits.max_image_width = Some(MAX_IMAGE_SIDE);
    limits.max_image_height = Some(MAX_IMAGE_SIDE);
    // Four 32-bit float channels per pixel: the largest decoded form of an allowed image.
    limits.max_alloc = Some(MAX_IMAGE_PIXELS * 16);
    let mut reader = guessed()?;
    reader.limits(limits);
    // zune-jpeg 0.5 overflows on some malformed JPEGs (found by fuzzing; a panic in debug
    // builds): a broken file is an error, not a crash.
    std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| reader.decode()))
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
