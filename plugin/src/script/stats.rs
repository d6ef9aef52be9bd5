//! Statistics over rectangles of captures.

use image::RgbaImage;

use super::format::{Rect, Statistic};
use crate::srgb_to_linear;

/// The pixels of `rect` (clamped to the image), or every pixel.
fn region(image: &RgbaImage, rect: Option<Rect>) -> Vec<(u32, u32)> {
    let (width, height) = image.dimensions();
    let (x0, y0, w, h) = rect.unwrap_or((0, 0, width, height));
    let (x1, y1) = (
        (x0.saturating_add(w)).min(width),
        (y0.saturating_add(h)).min(height),
    );
    (y0.min(height)..y1)
        .flat_map(|y| (x0.min(width)..x1).map(move |x| (x, y)))
        .collect()
}

fn linear(image: &RgbaImage, x: u32, y: u32, channel: usize) -> f32 {
    srgb_to_linear(f32::from(image.get_pixel(x, y).0[channel]) / 255.0)
}

fn fraction(image: &RgbaImage, rect: Option<Rect>, test: impl Fn(u32, u32) -> bool) -> f32 {
    let pixels = region(image, rect);
    if pixels.is_empty() {
        return 0.0;
    }
    pixels.iter().filter(|(x, y)| test(*x, *y)).count() as f32 / pixels.len() as f32
}

/// The value of `stat` over `rect` of `image`; `baseline` is the capture a `UvShift` measures
/// from. Debug-view statistics read the raw values back through the sRGB curve the target
/// applied.
pub fn measure(
    stat: &Statistic,
    image: &RgbaImage,
    rect: Option<Rect>,
    baseline: Option<&RgbaImage>,
) -> f32 {
    match stat {
        Statistic::MeanLuminance => {
            let pixels = region(image, rect);
            let total: f32 = pixels
                .iter()
                .map(|&(x, y)| {
                    0.2126 * linear(image, x, y, 0)
                        + 0.7152 * linear(image, x, y, 1)
                        + 0.0722 * linear(image, x, y, 2)
                })
                .sum();
            total / pixels.len().max(1) as f32
        }
        // The uv view's blue channel: 1 full march, 0.5 band, 0 normal mapping only.
        Statistic::LodBandFraction => fraction(image, rect, |x, y| {
            (0.25..0.75).contains(&linear(image, x, y, 2))
        }),
        Statistic::NormalMappingFraction => {
            fraction(image, rect, |x, y| linear(image, x, y, 2) < 0.25)
        }
        Statistic::ShadowedFraction => fraction(image, rect, |x, y| linear(image, x, y, 0) < 0.5),
        Statistic::UvShift { .. } => {
            let Some(baseline) = baseline else {
                return 0.0;
            };
            let pixels = region(image, rect);
            let total: f32 = pixels
                .iter()
                .map(|&(x, y)| {
                    let wrapped = |channel| {
                        let d = linear(image, x, y, channel) - linear(baseline, x, y, channel);
                        d - d.round()
                    };
                    (wrapped(0).powi(2) + wrapped(1).powi(2)).sqrt()
                })
                .sum();
            total / pixels.len().max(1) as f32
        }
    }
}

/// The debug view a statistic needs its capture to be taken with, if any.
pub fn required_view(stat: &Statistic) -> Option<crate::DebugView> {
    match stat {
        Statistic::MeanLuminance => None,
        Statistic::LodBandFraction
        | Statistic::NormalMappingFraction
        | Statistic::UvShift { .. } => Some(crate::DebugView::Uv),
        Statistic::ShadowedFraction => Some(crate::DebugView::Shadow),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fractions_count_the_rectangle_only() {
        let mut image = RgbaImage::from_pixel(4, 4, image::Rgba([255, 255, 255, 255]));
        image.put_pixel(0, 0, image::Rgba([0, 0, 0, 255]));
        assert_eq!(
            measure(&Statistic::ShadowedFraction, &image, None, None),
            1.0 / 16.0
        );
        assert_eq!(
            measure(
                &Statistic::ShadowedFraction,
                &image,
                Some((0, 0, 2, 2)),
                None
            ),
            0.25
        );
        assert_eq!(
            measure(
                &Statistic::ShadowedFraction,
                &image,
                Some((9, 9, 2, 2)),
                None
            ),
            0.0
        );
        assert!(
            (measure(&Statistic::MeanLuminance, &image, Some((1, 1, 3, 3)), None) - 1.0).abs()
                < 1e-6
        );
    }
}
