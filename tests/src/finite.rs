//! Frames checked for NaN and ±∞ where they arise: in the HDR scene the materials draw, before
//! tonemapping, which turns NaN into 0 and so hides it from the display target.

use image::Rgba32FImage;
use pom::App;

use crate::{HarnessError, in_error_scopes};

/// How many non-finite pixels [`NonFinitePixels`] lists by position.
const LISTED: usize = 4;

/// The pixels of one target that hold a NaN or ±∞ in any channel.
#[derive(Debug, Clone, PartialEq)]
pub struct NonFinitePixels {
    /// Which target: `"scene"` (HDR, before tonemapping) or `"display"`.
    pub target: &'static str,
    /// How many pixels hold one.
    pub count: usize,
    /// The first few, in row order: their position and RGBA value.
    pub first: Vec<(u32, u32, [f32; 4])>,
}

impl std::fmt::Display for NonFinitePixels {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{} pixels of the {} target are not finite, first",
            self.count, self.target
        )?;
        for (x, y, value) in &self.first {
            write!(f, " ({x}, {y}) = {value:?}")?;
        }
        Ok(())
    }
}

/// The non-finite pixels of `image`, `None` when there are none. Every channel counts: display
/// data in the scene (the clear colour, a debug view) has a negative but finite alpha.
pub fn non_finite_pixels(image: &Rgba32FImage, target: &'static str) -> Option<NonFinitePixels> {
    let mut bad = image
        .enumerate_pixels()
        .filter(|(_, _, pixel)| pixel.0.iter().any(|c| !c.is_finite()));
    let first: Vec<_> = bad
        .by_ref()
        .take(LISTED)
        .map(|(x, y, pixel)| (x, y, pixel.0))
        .collect();
    let count = first.len() + bad.count();
    (count > 0).then_some(NonFinitePixels {
        target,
        count,
        first,
    })
}

/// Runs one update of a [`pom::TargetFormat::Float32`] app and reads its display target back,
/// all inside error scopes, and fails with [`HarnessError::NonFinite`] if the HDR scene under
/// it or the display itself holds a NaN or ±∞ anywhere.
pub fn render_and_capture_finite(app: &mut App) -> Result<Rgba32FImage, HarnessError> {
    in_error_scopes(app, "render and capture", |app| {
        app.update()?;
        let scene = pom::capture_scene(app)?;
        let display = pom::capture_f32(app)?;
        match non_finite_pixels(&scene, "scene").or_else(|| non_finite_pixels(&display, "display"))
        {
            Some(bad) => Err(HarnessError::NonFinite(bad)),
            None => Ok(display),
        }
    })
}

#[cfg(test)]
mod tests {
    use image::Rgba;

    use super::*;

    #[test]
    fn counts_every_non_finite_channel_and_lists_the_first() {
        let mut image = Rgba32FImage::from_pixel(8, 4, Rgba([0.5, 0.5, 0.5, -2.0]));
        image.put_pixel(3, 0, Rgba([f32::NAN, 0.0, 0.0, 1.0]));
        image.put_pixel(1, 1, Rgba([0.0, f32::INFINITY, 0.0, 1.0]));
        image.put_pixel(0, 2, Rgba([0.0, 0.0, f32::NEG_INFINITY, 1.0]));
        image.put_pixel(5, 2, Rgba([0.0, 0.0, 0.0, f32::NAN]));
        image.put_pixel(7, 3, Rgba([f32::NAN; 4]));
        let bad = non_finite_pixels(&image, "scene").unwrap();
        assert_eq!(bad.count, 5);
        let positions: Vec<_> = bad.first.iter().map(|(x, y, _)| (*x, *y)).collect();
        assert_eq!(positions, [(3, 0), (1, 1), (0, 2), (5, 2)]);
        assert!(
            bad.to_string()
                .starts_with("5 pixels of the scene target are not finite, first (3, 0) = [NaN"),
            "{bad}"
        );
    }

    #[test]
    fn display_data_and_huge_values_are_finite() {
        let mut image = Rgba32FImage::from_pixel(4, 4, Rgba([0.0, 0.0, 1.0, -1.0]));
        image.put_pixel(2, 2, Rgba([f32::MAX, 1e30, 0.0, -2.0]));
        assert_eq!(non_finite_pixels(&image, "scene"), None);
    }
}
