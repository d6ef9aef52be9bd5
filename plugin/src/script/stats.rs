//! Statistics over rectangles of captures. A debug view's statistic counts only the pixels of
//! parallax surfaces (the [`SurfaceMask`] of its capture): the background and other materials
//! carry no debug data, and counting them would measure the framing, not the material.

use image::RgbaImage;

use super::format::{Rect, Statistic};
use crate::srgb_to_linear;

/// Which pixels of a capture show the surface of a parallax material, row by row.
#[derive(Clone, Debug, PartialEq)]
pub struct SurfaceMask {
    width: u32,
    covered: Vec<bool>,
}

impl SurfaceMask {
    /// The mask of a `width` × `height` capture where `covers(x, y)` says whether a pixel
    /// shows a parallax surface.
    pub fn new(width: u32, height: u32, covers: impl Fn(u32, u32) -> bool) -> Self {
        let covered = (0..height)
            .flat_map(|y| (0..width).map(move |x| (x, y)))
            .map(|(x, y)| covers(x, y))
            .collect();
        Self { width, covered }
    }

    /// Whether pixel (`x`, `y`) shows a parallax surface (outside the capture: no).
    fn contains(&self, x: u32, y: u32) -> bool {
        x < self.width
            && self
                .covered
                .get(y as usize * self.width as usize + x as usize)
                .is_some_and(|covered| *covered)
    }
}

/// A capture as a statistic reads it: its pixels and, for a debug view, its parallax surface.
#[derive(Clone, Copy, Debug)]
pub struct Measured<'a> {
    /// The captured frame.
    pub image: &'a RgbaImage,
    /// The pixels that show a parallax surface (`None`: taken without a debug view).
    pub surface: Option<&'a SurfaceMask>,
}

impl Measured<'_> {
    /// Whether pixel (`x`, `y`) shows a parallax surface.
    fn on_surface(&self, x: u32, y: u32) -> bool {
        self.surface.is_some_and(|mask| mask.contains(x, y))
    }
}

/// How a statistic is named in reports and errors.
pub fn stat_name(stat: &Statistic) -> String {
    match stat {
        Statistic::MeanLuminance => "mean luminance".into(),
        Statistic::LodBandFraction => "LOD band fraction".into(),
        Statistic::NormalMappingFraction => "normal-mapping fraction".into(),
        Statistic::ShadowedFraction => "shadowed fraction".into(),
        Statistic::UvShift { baseline } => format!("UV shift from {baseline:?}"),
    }
}

/// The pixels of `rect` (clamped to the image), or every pixel.
fn region(image: &RgbaImage, rect: Option<Rect>) -> impl Iterator<Item = (u32, u32)> {
    let (width, height) = image.dimensions();
    let (x0, y0, w, h) = rect.unwrap_or((0, 0, width, height));
    let (x1, y1) = (
        (x0.saturating_add(w)).min(width),
        (y0.saturating_add(h)).min(height),
    );
    (y0.min(height)..y1).flat_map(move |y| (x0.min(width)..x1).map(move |x| (x, y)))
}

fn linear(image: &RgbaImage, x: u32, y: u32, channel: usize) -> f32 {
    srgb_to_linear(f32::from(image.get_pixel(x, y).0[channel]) / 255.0)
}

/// The mean of `value` over `pixels`; `None` when there is none.
fn mean(pixels: impl Iterator<Item = (u32, u32)>, value: impl Fn(u32, u32) -> f32) -> Option<f32> {
    let (total, count) = pixels.fold((0.0, 0_u32), |(total, count), (x, y)| {
        (total + value(x, y), count + 1)
    });
    (count > 0).then(|| total / count as f32)
}

/// The fraction of the parallax-surface pixels of `rect` that pass `test`.
fn fraction(
    capture: Measured<'_>,
    rect: Option<Rect>,
    test: impl Fn(u32, u32) -> bool,
) -> Option<f32> {
    let surface = region(capture.image, rect).filter(|&(x, y)| capture.on_surface(x, y));
    mean(surface, |x, y| f32::from(u8::from(test(x, y))))
}

/// The value of `stat` over `rect` of `capture`; `baseline` is the capture a `UvShift`
/// measures from. `None` when `rect` holds no pixel the statistic counts: mean luminance counts
/// every pixel, the debug-view statistics only those of parallax surfaces (for `UvShift`, in
/// both captures). Debug-view statistics read the raw values back through the sRGB curve the
/// target applied.
pub fn measure(
    stat: &Statistic,
    capture: Measured<'_>,
    rect: Option<Rect>,
    baseline: Option<Measured<'_>>,
) -> Option<f32> {
    let image = capture.image;
    match stat {
        Statistic::MeanLuminance => mean(region(image, rect), |x, y| {
            0.2126 * linear(image, x, y, 0)
                + 0.7152 * linear(image, x, y, 1)
                + 0.0722 * linear(image, x, y, 2)
        }),
        // The uv view's blue channel: 1 full march, 0.5 band, 0 normal mapping only.
        Statistic::LodBandFraction => fraction(capture, rect, |x, y| {
            (0.25..0.75).contains(&linear(image, x, y, 2))
        }),
        Statistic::NormalMappingFraction => {
            fraction(capture, rect, |x, y| linear(image, x, y, 2) < 0.25)
        }
        // The shadow view's visibility: 1 lit, 0 fully in the height field's shadow.
        Statistic::ShadowedFraction => fraction(capture, rect, |x, y| linear(image, x, y, 0) < 0.5),
        Statistic::UvShift { .. } => {
            let baseline = baseline?;
            let both = region(image, rect)
                .filter(|&(x, y)| capture.on_surface(x, y) && baseline.on_surface(x, y));
            mean(both, |x, y| {
                let wrapped = |channel| {
                    let d = linear(image, x, y, channel) - linear(baseline.image, x, y, channel);
                    d - d.round()
                };
                (wrapped(0).powi(2) + wrapped(1).powi(2)).sqrt()
            })
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

    const WHITE: image::Rgba<u8> = image::Rgba([255, 255, 255, 255]);
    const BLACK: image::Rgba<u8> = image::Rgba([0, 0, 0, 255]);

    /// A 4×4 white capture with a black top-left pixel, its surface the left half.
    fn left_half_surface() -> (RgbaImage, SurfaceMask) {
        let mut image = RgbaImage::from_pixel(4, 4, WHITE);
        image.put_pixel(0, 0, BLACK);
        // The background (right half) is dark too, as a clear colour is.
        for y in 0..4 {
            image.put_pixel(3, y, BLACK);
        }
        (image, SurfaceMask::new(4, 4, |x, _| x < 2))
    }

    #[test]
    fn fractions_count_the_parallax_surface_of_the_rectangle_only() {
        let (image, mask) = left_half_surface();
        let capture = Measured {
            image: &image,
            surface: Some(&mask),
        };
        let shadowed = |rect| measure(&Statistic::ShadowedFraction, capture, rect, None);
        // One of the eight surface pixels is dark; the dark background column is not counted.
        assert_eq!(shadowed(None), Some(1.0 / 8.0));
        assert_eq!(shadowed(Some((0, 0, 2, 2))), Some(0.25));
        assert_eq!(shadowed(Some((2, 0, 2, 4))), None, "no surface to count");
        let luminance = measure(&Statistic::MeanLuminance, capture, Some((1, 1, 2, 3)), None);
        assert!((luminance.unwrap() - 1.0).abs() < 1e-6);
    }

    #[test]
    fn uv_shift_counts_pixels_on_the_surface_in_both_captures() {
        let (image, mask) = left_half_surface();
        let moved = RgbaImage::from_pixel(4, 4, image::Rgba([128, 0, 0, 255]));
        let right_column = SurfaceMask::new(4, 4, |x, _| x >= 1);
        let shift = |baseline_mask: &SurfaceMask| {
            measure(
                &Statistic::UvShift {
                    baseline: "flat".into(),
                },
                Measured {
                    image: &moved,
                    surface: Some(&mask),
                },
                None,
                Some(Measured {
                    image: &image,
                    surface: Some(baseline_mask),
                }),
            )
        };
        // Column 1 only: from white to mid-red, R moves by 0.216 − 1 (wrapped: 0.216) and G by
        // −1 (wrapped: 0).
        let expected = srgb_to_linear(128.0 / 255.0);
        assert!((shift(&right_column).unwrap() - expected).abs() < 1e-5);
        assert_eq!(shift(&SurfaceMask::new(4, 4, |x, _| x >= 2)), None);
    }
}
