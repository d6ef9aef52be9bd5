//! Writing a captured frame to an image file, and saying where it went.

use std::path::Path;

use anyhow::{Context, Result};
use image::{DynamicImage, ImageBuffer, Rgb, Rgba32FImage};

/// A 16-bit RGB image: what the raw debug views are written as.
pub type Rgb16Image = ImageBuffer<Rgb<u16>, Vec<u16>>;

/// The red, green and blue of a float frame as 16-bit values (value × 65535, clamped to 0..=1,
/// NaN as 0), with no sRGB curve: 8 bits would round the UVs to 1/255 of a tile, and the curve
/// would bend the measurements.
pub fn raw_rgb16(frame: &Rgba32FImage) -> Rgb16Image {
    let to_u16 = |value: f32| {
        if value.is_nan() {
            0
        } else {
            (value.clamp(0.0, 1.0) * 65535.0).round() as u16
        }
    };
    ImageBuffer::from_fn(frame.width(), frame.height(), |x, y| {
        let [r, g, b, _alpha] = frame.get_pixel(x, y).0;
        Rgb([to_u16(r), to_u16(g), to_u16(b)])
    })
}

/// Saves `image` to `path` (the format follows the extension), creating its folder, and prints
/// one line naming the file, its size and the GPU that drew it.
pub fn write(app: &pom::App, image: DynamicImage, path: &Path) -> Result<()> {
    if let Some(parent) = path.parent().filter(|p| !p.as_os_str().is_empty()) {
        std::fs::create_dir_all(parent)
            .with_context(|| format!("creating {}", parent.display()))?;
    }
    pom::files::write_image(path, &image)?;
    let gpu = app
        .resources
        .get::<pom::GpuContext>()
        .map(|gpu| gpu.adapter_info().name)
        .unwrap_or_default();
    let (width, height) = (image.width(), image.height());
    println!("wrote {} ({width}×{height}, {gpu})", path.display());
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn raw_values_are_scaled_clamped_and_keep_no_alpha() {
        let frame = Rgba32FImage::from_fn(2, 1, |x, _| {
            if x == 0 {
                image::Rgba([0.0, 0.5, 1.0, 0.25])
            } else {
                image::Rgba([-1.0, 2.0, f32::NAN, 1.0])
            }
        });
        let raw = raw_rgb16(&frame);
        assert_eq!(raw.dimensions(), (2, 1));
        assert_eq!(raw.get_pixel(0, 0).0, [0, 32768, 65535]);
        assert_eq!(raw.get_pixel(1, 0).0, [0, 65535, 0]);
    }
}
