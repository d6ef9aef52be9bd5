//! Comparing renders with NVIDIA's FLIP perceptual metric.

use image::RgbaImage;

/// How different a capture may be from its reference, in FLIP units (0 = identical, 1 = maximal).
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FlipTolerance {
    /// Largest allowed mean FLIP error over the image.
    pub mean: f32,
    /// Percentile checked, as a fraction (0.99 = the 99th percentile).
    pub percentile: f32,
    /// Largest allowed FLIP error at that percentile.
    pub percentile_max: f32,
}

impl Default for FlipTolerance {
    /// Tight enough to catch a moved light or a broken normal map, loose enough for the small
    /// rounding differences between software drivers.
    fn default() -> Self {
        Self {
            mean: 0.01,
            percentile: 0.99,
            percentile_max: 0.1,
        }
    }
}

impl FlipTolerance {
    /// The first field that cannot mean anything, and why: a `mean` or `percentile_max` that is
    /// not a finite number ≥ 0 (NaN would pass or fail everything), a `percentile` outside
    /// 0..=1 (it is a fraction: 0.95, not 95).
    ///
    /// # Example
    /// ```
    /// let tolerance = pom::FlipTolerance { percentile: 95.0, ..Default::default() };
    /// assert_eq!(tolerance.problem().unwrap().0, "percentile");
    /// assert!(pom::FlipTolerance::default().problem().is_none());
    /// ```
    pub fn problem(&self) -> Option<(&'static str, String)> {
        let not_a_bound = |value: f32| !(value.is_finite() && value >= 0.0);
        if not_a_bound(self.mean) {
            Some((
                "mean",
                format!("mean {} is not a finite number ≥ 0", self.mean),
            ))
        } else if !(0.0..=1.0).contains(&self.percentile) {
            Some((
                "percentile",
                format!(
                    "percentile {} is outside 0..=1 (a fraction: 0.99 is the 99th percentile)",
                    self.percentile
                ),
            ))
        } else if not_a_bound(self.percentile_max) {
            Some((
                "percentile_max",
                format!(
                    "percentile_max {} is not a finite number ≥ 0",
                    self.percentile_max
                ),
            ))
        } else {
            None
        }
    }
}

/// The outcome of one comparison.
#[derive(Clone, Debug)]
pub struct FlipComparison {
    /// Mean FLIP error.
    pub mean: f32,
    /// FLIP error at the tolerance's percentile.
    pub at_percentile: f32,
    /// The per-pixel error drawn with the magma colour map (black = identical).
    pub error_map: RgbaImage,
}

impl FlipComparison {
    /// Whether the comparison is within `tolerance`.
    pub fn within(&self, tolerance: &FlipTolerance) -> bool {
        self.mean <= tolerance.mean && self.at_percentile <= tolerance.percentile_max
    }
}

/// Compares two images of the same size with FLIP; `None` when the sizes differ.
pub fn flip_compare(
    reference: &RgbaImage,
    actual: &RgbaImage,
    percentile: f32,
) -> Option<FlipComparison> {
    if reference.dimensions() != actual.dimensions() {
        return None;
    }
    let (width, height) = actual.dimensions();
    let rgb = |image: &RgbaImage| -> Vec<u8> {
        image
            .pixels()
            .flat_map(|p| [p.0[0], p.0[1], p.0[2]])
            .collect()
    };
    let error = nv_flip::flip(
        nv_flip::FlipImageRgb8::with_data(width, height, &rgb(reference)),
        nv_flip::FlipImageRgb8::with_data(width, height, &rgb(actual)),
        nv_flip::DEFAULT_PIXELS_PER_DEGREE,
    );
    let mut pool = nv_flip::FlipPool::from_image(&error);
    let mean = pool.mean();
    let at_percentile = pool.get_percentile(percentile.clamp(0.0, 1.0), true);
    let colored = error.apply_color_lut(&nv_flip::magma_lut());
    let error_map = image::RgbImage::from_raw(width, height, colored.to_vec())
        .map(|rgb| image::DynamicImage::ImageRgb8(rgb).to_rgba8())
        .unwrap_or_else(|| RgbaImage::new(width, height));
    Some(FlipComparison {
        mean,
        at_percentile,
        error_map,
    })
}
