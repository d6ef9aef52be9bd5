//! Texture images held on the CPU: colour, normal, height and data maps, their mip chains.

use std::path::Path;

use image::{DynamicImage, GrayImage, ImageBuffer, Luma, RgbaImage};

mod budget;
mod decode;
mod error;
mod mips;
mod pixels;
mod sampler;

pub use budget::IMAGE_MEMORY_BUDGET;
pub(crate) use budget::ImageBudget;
use decode::decode_file;
pub(crate) use decode::{ENVIRONMENT_FORMATS, TEXTURE_FORMATS, decode_bytes};
pub use decode::{MAX_IMAGE_PIXELS, MAX_IMAGE_SIDE};
pub use error::ImageError;
use mips::Reduce;
pub use pixels::Pixels;
pub use sampler::{FilterMode, ImageSampler, WrapMode};

/// What a texture holds: decides its GPU format and how its mip levels are filtered.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum TextureKind {
    /// sRGB colour (albedo): decoded to linear light when sampled; mips averaged in linear light.
    Color,
    /// Tangent-space normal map, xyz × 0.5 + 0.5 in RGB (alpha may carry a height): mips are
    /// averaged as vectors and renormalised, so distant normals stay unit length.
    Normal,
    /// A height (or depth) field, one channel of 8 or 16 bits: mips are plain averages, and a
    /// max-mip chain is available for exact intersection searches.
    Height,
    /// Any other linear data: plain averages.
    Data,
}

/// Which channel of a colour image holds a height.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Channel {
    /// Red (and the grey of a grey image).
    #[default]
    Red,
    /// Green.
    Green,
    /// Blue.
    Blue,
    /// Alpha.
    Alpha,
}

impl Channel {
    /// 0 for red … 3 for alpha.
    pub fn index(self) -> usize {
        self as usize
    }
}

/// A texture on the CPU, with its kind; the renderer uploads it with a full mip chain.
#[derive(Clone, Debug, PartialEq)]
pub struct Image {
    pixels: Pixels,
    kind: TextureKind,
    gpu_written: bool,
    sampler: ImageSampler,
}

impl Image {
    /// Wraps 8-bit RGBA pixels. Fails for an empty image.
    pub fn new(pixels: RgbaImage, kind: TextureKind) -> Result<Self, ImageError> {
        Self::from_pixels(Pixels::Rgba8(pixels), kind)
    }

    /// Wraps pixels of any storage. Fails for an empty image.
    pub fn from_pixels(pixels: Pixels, kind: TextureKind) -> Result<Self, ImageError> {
        let (width, height) = pixels.dimensions();
        if width == 0 || height == 0 {
            return Err(ImageError::Empty { width, height });
        }
        Ok(Self {
            pixels,
            kind,
            gpu_written: false,
            sampler: ImageSampler::default(),
        })
    }

    /// The same image sampled with `sampler` (a material samples all its textures with the
    /// sampler of its first one).
    pub fn with_sampler(self, sampler: ImageSampler) -> Self {
        Self { sampler, ..self }
    }

    /// How the image is sampled.
    pub fn sampler(&self) -> ImageSampler {
        self.sampler
    }

    /// Builds an image from raw RGBA8 bytes, row by row.
    pub fn from_rgba8(
        width: u32,
        height: u32,
        bytes: Vec<u8>,
        kind: TextureKind,
    ) -> Result<Self, ImageError> {
        // In 64 bits: a declared size near u32::MAX must not overflow before it is refused.
        let texels = u64::from(width) * u64::from(height);
        let expected = usize::try_from(texels.saturating_mul(4)).unwrap_or(usize::MAX);
        let found = bytes.len();
        let pixels = RgbaImage::from_raw(width, height, bytes).ok_or(ImageError::WrongLength {
            width,
            height,
            expected,
            found,
        })?;
        Self::new(pixels, kind)
    }

    /// A 1×1 image of one RGBA8 value.
    pub fn solid(rgba: [u8; 4], kind: TextureKind) -> Self {
        Self {
            pixels: Pixels::Rgba8(RgbaImage::from_pixel(1, 1, image::Rgba(rgba))),
            kind,
            gpu_written: false,
            sampler: ImageSampler::default(),
        }
    }

    /// Decodes a PNG or JPEG file (a regular file, within [`crate::files::MAX_IMAGE_FILE_BYTES`]
    /// and [`IMAGE_MEMORY_BUDGET`]). Height maps keep one channel (red; see
    /// [`Image::load_height`]) at their bit depth; everything else becomes 8-bit RGBA.
    pub fn load(path: impl AsRef<Path>, kind: TextureKind) -> Result<Self, ImageError> {
        Self::load_alone(path.as_ref(), kind, Channel::Red)
    }

    /// Decodes a height map from `channel` of a PNG or JPEG file, keeping 16 bits when the file
    /// has them.
    pub fn load_height(path: impl AsRef<Path>, channel: Channel) -> Result<Self, ImageError> {
        Self::load_alone(path.as_ref(), TextureKind::Height, channel)
    }

    fn load_alone(path: &Path, kind: TextureKind, channel: Channel) -> Result<Self, ImageError> {
        let mut budget = ImageBudget::new(IMAGE_MEMORY_BUDGET);
        let (decoded, file_bytes) = decode_file(path, &mut budget)?;
        let name = path.display().to_string();
        Self::from_decoded_within(decoded, kind, channel, &name, file_bytes, &mut budget)
    }

    /// Decodes an image held in memory (a glTF buffer view, say); `name` appears in errors.
    pub fn decode(
        bytes: &[u8],
        name: &str,
        kind: TextureKind,
        channel: Channel,
    ) -> Result<Self, ImageError> {
        let mut budget = ImageBudget::new(IMAGE_MEMORY_BUDGET);
        let decoded = decode_bytes(bytes, name, (None, decode::TEXTURE_FORMATS), &mut budget)?;
        Self::from_decoded_within(
            decoded,
            kind,
            channel,
            name,
            bytes.len() as u64,
            &mut budget,
        )
    }

    /// [`Image::from_decoded`] once `budget` allows the pixels it keeps (of a file of
    /// `file_bytes`).
    pub(crate) fn from_decoded_within(
        decoded: DynamicImage,
        kind: TextureKind,
        channel: Channel,
        name: &str,
        file_bytes: u64,
        budget: &mut ImageBudget,
    ) -> Result<Self, ImageError> {
        let size = (decoded.width(), decoded.height());
        let bytes_per_texel = match kind {
            TextureKind::Height => 2,
            _ => 4,
        };
        let kept = u64::from(size.0) * u64::from(size.1) * bytes_per_texel;
        budget.reserve_kept(name, file_bytes, size, kept)?;
        Self::from_decoded(decoded, kind, channel, name)
    }

    /// Converts a decoded image for `kind`: heights keep `channel` at 8 or 16 bits. Float values
    /// are clamped to 0..=1, NaN to 0.
    pub fn from_decoded(
        mut decoded: DynamicImage,
        kind: TextureKind,
        channel: Channel,
        name: &str,
    ) -> Result<Self, ImageError> {
        // The image crate's integer conversion turns NaN into the maximum, not 0.
        let floats: Option<&mut [f32]> = match &mut decoded {
            DynamicImage::ImageRgb32F(image) => Some(&mut **image),
            DynamicImage::ImageRgba32F(image) => Some(&mut **image),
            _ => None,
        };
        for value in floats.into_iter().flatten().filter(|v| v.is_nan()) {
            *value = 0.0;
        }
        if kind != TextureKind::Height {
            return Self::new(decoded.to_rgba8(), kind);
        }
        if channel == Channel::Alpha && !decoded.color().has_alpha() {
            return Err(ImageError::NoAlpha {
                name: name.to_owned(),
            });
        }
        let index = channel.index();
        let sixteen_bit = decoded.color().bytes_per_pixel() / decoded.color().channel_count() >= 2;
        let pixels = if sixteen_bit {
            let rgba = decoded.to_rgba16();
            Pixels::Gray16(ImageBuffer::from_fn(rgba.width(), rgba.height(), |x, y| {
                Luma([rgba.get_pixel(x, y).0[index]])
            }))
        } else {
            let rgba = decoded.to_rgba8();
            Pixels::Gray8(GrayImage::from_fn(rgba.width(), rgba.height(), |x, y| {
                Luma([rgba.get_pixel(x, y).0[index]])
            }))
        };
        Self::from_pixels(pixels, kind)
    }

    /// An RGBA8 image of `width` × `height` that a GPU pass writes (a dynamic height field's
    /// normal map, say): uploaded once with these pixels as its starting content and a single
    /// mip level, and bindable as a storage texture.
    pub fn gpu_written(
        width: u32,
        height: u32,
        kind: TextureKind,
        fill: [u8; 4],
    ) -> Result<Self, ImageError> {
        decode::check_size("a GPU-written image", width, height)?;
        let pixels = RgbaImage::from_pixel(width, height, image::Rgba(fill));
        Ok(Self {
            gpu_written: true,
            ..Self::new(pixels, kind)?
        })
    }

    /// Whether a GPU pass writes this image (see [`Image::gpu_written`]).
    pub fn is_gpu_written(&self) -> bool {
        self.gpu_written
    }

    /// Width and height in pixels.
    pub fn size(&self) -> (u32, u32) {
        self.pixels.dimensions()
    }

    /// What the image holds.
    pub fn kind(&self) -> TextureKind {
        self.kind
    }

    /// The full-resolution pixels.
    pub fn pixels(&self) -> &Pixels {
        &self.pixels
    }

    /// The pixels as 8-bit RGBA (grey images repeat their value in R, G and B).
    pub fn to_rgba8(&self) -> RgbaImage {
        match &self.pixels {
            Pixels::Rgba8(pixels) => pixels.clone(),
            Pixels::Gray8(pixels) => DynamicImage::ImageLuma8(pixels.clone()).to_rgba8(),
            Pixels::Gray16(pixels) => DynamicImage::ImageLuma16(pixels.clone()).to_rgba8(),
        }
    }

    /// Every mip level from full size down to 1×1, each half the size of the previous (rounded
    /// down, at least 1), filtered for the image's kind: each texel averages the up to 2×2 (3 at
    /// the last row or column of an odd size) texels it covers, in linear light for colour,
    /// renormalised for normals. Levels are computed from floats, so rounding does not pile up.
    pub fn mip_chain(&self) -> Vec<Pixels> {
        mips::chain(&self.pixels, self.kind, Reduce::Average)
    }

    /// For height maps: the chain whose texels hold the *maximum* of the texels they cover, so
    /// a ray that passes above a coarse texel passes above everything under it. `None` for other
    /// kinds.
    pub fn max_mip_chain(&self) -> Option<Vec<Pixels>> {
        (self.kind == TextureKind::Height)
            .then(|| mips::chain(&self.pixels, self.kind, Reduce::Max))
    }

    /// This image, or its first mip level whose sides fit `limit` texels.
    pub fn fitted_to(&self, limit: u32) -> Image {
        let (width, height) = self.size();
        if width <= limit && height <= limit {
            return self.clone();
        }
        let pixels = self
            .mip_chain()
            .into_iter()
            .find(|level| {
                let (w, h) = level.dimensions();
                w <= limit && h <= limit
            })
            // The chain ends at 1×1, which fits any limit ≥ 1.
            .unwrap_or_else(|| self.pixels.clone());
        Image {
            pixels,
            kind: self.kind,
            gpu_written: self.gpu_written,
            sampler: self.sampler,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rgba(image: &Pixels) -> &RgbaImage {
        match image {
            Pixels::Rgba8(pixels) => pixels,
            other => panic!("expected RGBA8, got {other:?}"),
        }
    }

    #[test]
    fn mip_chain_reaches_one_by_one_for_any_size() {
        let image = Image::new(RgbaImage::new(37, 5), TextureKind::Data).unwrap();
        let sizes: Vec<_> = image.mip_chain().iter().map(Pixels::dimensions).collect();
        assert_eq!(sizes, [(37, 5), (18, 2), (9, 1), (4, 1), (2, 1), (1, 1)]);
    }

    #[test]
    fn colour_mips_average_in_linear_light() {
        // Black and white checker: the linear mean is 0.5, which is 188 in sRGB, not 128.
        let checker = RgbaImage::from_fn(2, 2, |x, y| {
            let v = if (x + y) % 2 == 0 { 255 } else { 0 };
            image::Rgba([v, v, v, 255])
        });
        let color = Image::new(checker.clone(), TextureKind::Color)
            .unwrap()
            .mip_chain();
        assert_eq!(rgba(&color[1]).get_pixel(0, 0).0, [188, 188, 188, 255]);
        let data = Image::new(checker, TextureKind::Data).unwrap().mip_chain();
        assert_eq!(rgba(&data[1]).get_pixel(0, 0).0, [128, 128, 128, 255]);
    }

    #[test]
    fn normal_mips_stay_unit_length() {
        // Two normals tilted ±45° about v: their plain average is short; the mip is renormalised.
        let encode = |c: f32| ((c * 0.5 + 0.5) * 255.0).round() as u8;
        let s = std::f32::consts::FRAC_1_SQRT_2;
        let tilted = RgbaImage::from_fn(2, 1, |x, _| {
            let x_component = if x == 0 { s } else { -s };
            image::Rgba([encode(x_component), 128, encode(s), 200])
        });
        let chain = Image::new(tilted, TextureKind::Normal).unwrap().mip_chain();
        let top = rgba(&chain[1]).get_pixel(0, 0).0;
        assert_eq!(top[..3], [128, 128, 255], "straight up and unit length");
        assert_eq!(
            top[3], 200,
            "alpha (a packed height) is averaged, not renormalised"
        );
    }

    #[test]
    fn sixteen_bit_heights_keep_their_precision_through_the_chain() {
        let ramp = ImageBuffer::from_fn(4, 1, |x, _| Luma([1000 + x as u16]));
        let chain = Image::from_pixels(Pixels::Gray16(ramp), TextureKind::Height)
            .unwrap()
            .mip_chain();
        let Pixels::Gray16(level) = &chain[1] else {
            panic!("16-bit heights must stay 16-bit");
        };
        // (1000 + 1001) / 2 = 1000.5 rounds to 1001; 8 bits could not tell these apart.
        assert_eq!(level.as_raw(), &[1001, 1003]);
    }

    #[test]
    fn the_max_chain_keeps_peaks() {
        let spike =
            GrayImage::from_fn(4, 4, |x, y| Luma([if (x, y) == (3, 0) { 250 } else { 10 }]));
        let image = Image::from_pixels(Pixels::Gray8(spike), TextureKind::Height).unwrap();
        let maxima = image.max_mip_chain().unwrap();
        let Pixels::Gray8(top) = maxima.last().unwrap() else {
            panic!("8-bit");
        };
        assert_eq!(top.get_pixel(0, 0).0, [250]);
        let Pixels::Gray8(averaged) = image.mip_chain().pop().unwrap() else {
            panic!("8-bit");
        };
        assert!(averaged.get_pixel(0, 0).0[0] < 30);
        assert!(
            Image::solid([0; 4], TextureKind::Color)
                .max_mip_chain()
                .is_none()
        );
    }

    #[test]
    fn oversized_images_are_fitted_by_halving() {
        let wide = Image::new(RgbaImage::new(1000, 10), TextureKind::Data).unwrap();
        assert_eq!(wide.fitted_to(300).size(), (250, 2));
        assert_eq!(wide.fitted_to(4096).size(), (1000, 10));
    }

    #[test]
    fn bad_sizes_are_errors() {
        assert!(matches!(
            Image::from_rgba8(0, 4, Vec::new(), TextureKind::Color),
            Err(ImageError::Empty {
                width: 0,
                height: 4
            })
        ));
        assert!(matches!(
            Image::from_rgba8(2, 2, vec![0; 15], TextureKind::Color),
            Err(ImageError::WrongLength {
                expected: 16,
                found: 15,
                ..
            })
        ));
    }

    #[test]
    fn loading_names_the_file_that_failed() {
        let missing = Image::load("/nonexistent/height.png", TextureKind::Height).unwrap_err();
        assert!(
            missing.to_string().contains("/nonexistent/height.png"),
            "{missing}"
        );
        let dir = std::env::temp_dir().join(format!("pom-image-load-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let truncated = dir.join("truncated.png");
        std::fs::write(&truncated, &b"\x89PNG\r\n\x1a\n\0\0\0\rIHDR"[..]).unwrap();
        let error = Image::load(&truncated, TextureKind::Height).unwrap_err();
        assert!(error.to_string().contains("truncated.png"), "{error}");
        let empty = dir.join("empty.jpg");
        std::fs::write(&empty, b"").unwrap();
        assert!(
            Image::load(&empty, TextureKind::Color)
                .unwrap_err()
                .to_string()
                .contains("empty.jpg")
        );
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn jpeg_files_load_as_colour() {
        let dir = std::env::temp_dir().join(format!("pom-jpeg-load-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("albedo.jpg");
        image::RgbImage::from_pixel(9, 7, image::Rgb([200, 100, 50]))
            .save(&path)
            .unwrap();
        let albedo = Image::load(&path, TextureKind::Color).unwrap();
        assert_eq!(albedo.size(), (9, 7));
        let texel = albedo.to_rgba8().get_pixel(4, 3).0;
        // JPEG is lossy: close, not exact.
        assert!(
            texel[0].abs_diff(200) < 6 && texel[1].abs_diff(100) < 6 && texel[3] == 255,
            "{texel:?}"
        );
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn heights_load_from_the_chosen_channel_at_their_bit_depth() {
        let dir = std::env::temp_dir().join(format!("pom-height-load-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let colour = dir.join("colour.png");
        RgbaImage::from_pixel(3, 2, image::Rgba([1, 2, 3, 4]))
            .save(&colour)
            .unwrap();
        let green = Image::load_height(&colour, Channel::Green).unwrap();
        assert_eq!(
            green.pixels(),
            &Pixels::Gray8(GrayImage::from_pixel(3, 2, Luma([2])))
        );
        let sixteen = dir.join("sixteen.png");
        ImageBuffer::<Luma<u16>, _>::from_pixel(5, 3, Luma([40_000]))
            .save(&sixteen)
            .unwrap();
        let deep = Image::load(&sixteen, TextureKind::Height).unwrap();
        assert!(matches!(deep.pixels(), Pixels::Gray16(p) if p.get_pixel(4, 2).0 == [40_000]));
        let no_alpha = dir.join("grey.png");
        GrayImage::new(2, 2).save(&no_alpha).unwrap();
        let error = Image::load_height(&no_alpha, Channel::Alpha).unwrap_err();
        assert!(matches!(error, ImageError::NoAlpha { .. }), "{error}");
        assert!(error.to_string().contains("grey.png"));
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
