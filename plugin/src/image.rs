//! Texture images held on the CPU, and their mip chains.

use image::RgbaImage;

use crate::color::{linear_to_srgb, srgb_to_linear};

/// How an image's 8-bit values map to numbers the shader sees.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ColorSpace {
    /// sRGB-encoded colour (albedo): decoded to linear light when sampled, filtered in linear
    /// light when mips are built.
    Srgb,
    /// Plain data (normal maps, height maps): values are used as they are.
    Linear,
}

/// What went wrong building or loading an [`Image`].
#[derive(Debug, thiserror::Error)]
pub enum ImageError {
    /// The file could not be read or decoded.
    #[error("cannot load image {path}: {reason}")]
    Load {
        /// The file.
        path: std::path::PathBuf,
        /// What the decoder or the file system said.
        reason: String,
    },
    /// Width or height is zero.
    #[error("image is {width}×{height}; both sides must be at least 1")]
    Empty {
        /// Width in pixels.
        width: u32,
        /// Height in pixels.
        height: u32,
    },
    /// The pixel buffer's length does not match the size.
    #[error("image of {width}×{height} needs {expected} bytes of RGBA8 but got {found}")]
    WrongLength {
        /// Width in pixels.
        width: u32,
        /// Height in pixels.
        height: u32,
        /// Bytes needed.
        expected: usize,
        /// Bytes given.
        found: usize,
    },
}

/// An RGBA8 texture with its colour space; the renderer uploads it with a full mip chain.
#[derive(Clone, Debug, PartialEq)]
pub struct Image {
    pixels: RgbaImage,
    color_space: ColorSpace,
}

impl Image {
    /// Wraps decoded pixels. Fails for an empty image.
    pub fn new(pixels: RgbaImage, color_space: ColorSpace) -> Result<Self, ImageError> {
        let (width, height) = pixels.dimensions();
        if width == 0 || height == 0 {
            return Err(ImageError::Empty { width, height });
        }
        Ok(Self {
            pixels,
            color_space,
        })
    }

    /// Builds an image from raw RGBA8 bytes, row by row.
    pub fn from_rgba8(
        width: u32,
        height: u32,
        bytes: Vec<u8>,
        color_space: ColorSpace,
    ) -> Result<Self, ImageError> {
        let expected = width as usize * height as usize * 4;
        let found = bytes.len();
        let pixels = RgbaImage::from_raw(width, height, bytes).ok_or(ImageError::WrongLength {
            width,
            height,
            expected,
            found,
        })?;
        Self::new(pixels, color_space)
    }

    /// Decodes a PNG or JPEG file (any bit depth; converted to 8-bit RGBA).
    pub fn load(
        path: impl AsRef<std::path::Path>,
        color_space: ColorSpace,
    ) -> Result<Self, ImageError> {
        let path = path.as_ref();
        let decoded = image::ImageReader::open(path)
            .and_then(|reader| reader.with_guessed_format())
            .map_err(|error| ImageError::Load {
                path: path.to_owned(),
                reason: error.to_string(),
            })?
            .decode()
            .map_err(|error| ImageError::Load {
                path: path.to_owned(),
                reason: error.to_string(),
            })?;
        Self::new(decoded.to_rgba8(), color_space)
    }

    /// A 1×1 image of one RGBA8 value.
    pub fn solid(rgba: [u8; 4], color_space: ColorSpace) -> Self {
        Self {
            pixels: RgbaImage::from_pixel(1, 1, image::Rgba(rgba)),
            color_space,
        }
    }

    /// Width and height in pixels.
    pub fn size(&self) -> (u32, u32) {
        self.pixels.dimensions()
    }

    /// The colour space.
    pub fn color_space(&self) -> ColorSpace {
        self.color_space
    }

    /// The full-resolution pixels.
    pub fn pixels(&self) -> &RgbaImage {
        &self.pixels
    }

    /// Every mip level from full size down to 1×1, each half the size of the previous (rounded
    /// down, at least 1). Each texel of a level is the average of the up to 2×2 texels it covers,
    /// taken in linear light for sRGB images; odd sizes fold their last row or column in.
    pub fn mip_chain(&self) -> Vec<RgbaImage> {
        let mut levels = vec![self.pixels.clone()];
        while let Some(previous) = levels.last() {
            let (width, height) = previous.dimensions();
            if width == 1 && height == 1 {
                break;
            }
            let next = downsample(previous, self.color_space);
            levels.push(next);
        }
        levels
    }
}

fn downsample(source: &RgbaImage, color_space: ColorSpace) -> RgbaImage {
    let (width, height) = source.dimensions();
    let (next_width, next_height) = ((width / 2).max(1), (height / 2).max(1));
    let decode = |value: u8| {
        let unit = f32::from(value) / 255.0;
        match color_space {
            ColorSpace::Srgb => srgb_to_linear(unit),
            ColorSpace::Linear => unit,
        }
    };
    let encode = |value: f32| {
        let unit = match color_space {
            ColorSpace::Srgb => linear_to_srgb(value),
            ColorSpace::Linear => value,
        };
        (unit * 255.0).round().clamp(0.0, 255.0) as u8
    };
    RgbaImage::from_fn(next_width, next_height, |x, y| {
        // The source footprint of this texel: 2×2, or 3 wide/high at the last column/row of an
        // odd-sized level so no source texel is dropped.
        let x_end = if x + 1 == next_width {
            width
        } else {
            2 * x + 2
        };
        let y_end = if y + 1 == next_height {
            height
        } else {
            2 * y + 2
        };
        let mut sum = [0.0_f32; 4];
        let mut count = 0.0;
        for sy in (2 * y).min(height - 1)..y_end {
            for sx in (2 * x).min(width - 1)..x_end {
                let texel = source.get_pixel(sx, sy).0;
                for channel in 0..3 {
                    sum[channel] += decode(texel[channel]);
                }
                sum[3] += f32::from(texel[3]) / 255.0;
                count += 1.0;
            }
        }
        let [r, g, b, a] = sum.map(|s| s / count);
        image::Rgba([
            encode(r),
            encode(g),
            encode(b),
            (a * 255.0).round().clamp(0.0, 255.0) as u8,
        ])
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mip_chain_reaches_one_by_one_for_any_size() {
        let image = Image::new(RgbaImage::new(37, 5), ColorSpace::Linear).unwrap();
        let sizes: Vec<_> = image.mip_chain().iter().map(|l| l.dimensions()).collect();
        assert_eq!(sizes, [(37, 5), (18, 2), (9, 1), (4, 1), (2, 1), (1, 1)]);
    }

    #[test]
    fn srgb_mips_average_in_linear_light() {
        // Black and white checker: the linear mean is 0.5, which is 188 in sRGB, not 128.
        let checker = RgbaImage::from_fn(2, 2, |x, y| {
            let v = if (x + y) % 2 == 0 { 255 } else { 0 };
            image::Rgba([v, v, v, 255])
        });
        let srgb = Image::new(checker.clone(), ColorSpace::Srgb)
            .unwrap()
            .mip_chain();
        assert_eq!(srgb[1].get_pixel(0, 0).0, [188, 188, 188, 255]);
        let linear = Image::new(checker, ColorSpace::Linear).unwrap().mip_chain();
        assert_eq!(linear[1].get_pixel(0, 0).0, [128, 128, 128, 255]);
    }

    #[test]
    fn bad_sizes_are_errors() {
        assert!(matches!(
            Image::from_rgba8(0, 4, Vec::new(), ColorSpace::Srgb),
            Err(ImageError::Empty {
                width: 0,
                height: 4
            })
        ));
        assert!(matches!(
            Image::from_rgba8(2, 2, vec![0; 15], ColorSpace::Srgb),
            Err(ImageError::WrongLength {
                expected: 16,
                found: 15,
                ..
            })
        ));
    }
}

#[cfg(test)]
mod load_tests {
    use super::*;

    #[test]
    fn loading_names_the_file_that_failed() {
        let missing = Image::load("/nonexistent/height.png", ColorSpace::Linear).unwrap_err();
        assert!(
            missing.to_string().contains("/nonexistent/height.png"),
            "{missing}"
        );
        let dir = std::env::temp_dir().join(format!("pom-image-load-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let truncated = dir.join("truncated.png");
        std::fs::write(&truncated, &b"\x89PNG\r\n\x1a\n\0\0\0\rIHDR"[..]).unwrap();
        let error = Image::load(&truncated, ColorSpace::Linear).unwrap_err();
        assert!(error.to_string().contains("truncated.png"), "{error}");
        let good = dir.join("good.png");
        RgbaImage::from_pixel(3, 2, image::Rgba([1, 2, 3, 4]))
            .save(&good)
            .unwrap();
        assert_eq!(Image::load(&good, ColorSpace::Srgb).unwrap().size(), (3, 2));
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
