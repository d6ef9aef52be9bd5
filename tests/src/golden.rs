//! Reference-image comparison with NVIDIA FLIP.

use std::path::{Path, PathBuf};

use image::RgbaImage;

/// How different a capture may be from its reference, in FLIP units (0 = identical, 1 = maximal).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FlipTolerance {
    /// Largest allowed mean FLIP error over the image.
    pub mean: f32,
    /// Percentile checked (e.g. 0.99).
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

/// Why a capture did not match its reference.
#[derive(Debug, thiserror::Error)]
pub enum GoldenError {
    /// No reference exists and blessing was not asked for.
    #[error(
        "reference image {0} is missing: look at the capture, then run with UPDATE_GOLDENS=1 to bless it"
    )]
    Missing(PathBuf),
    /// The sizes differ.
    #[error("{path}: reference is {expected:?} but the capture is {actual:?}")]
    SizeMismatch {
        /// The reference.
        path: PathBuf,
        /// Reference size.
        expected: (u32, u32),
        /// Capture size.
        actual: (u32, u32),
    },
    /// The FLIP error is over the tolerance.
    #[error(
        "{path}: FLIP mean {mean:.4} (max {mean_max}), p{percentile} {at_percentile:.4} (max {percentile_max}); \
         see {actual} and {difference}"
    )]
    TooDifferent {
        /// The reference.
        path: PathBuf,
        /// Measured mean.
        mean: f32,
        /// Allowed mean.
        mean_max: f32,
        /// Percentile (0..=100).
        percentile: f32,
        /// Measured value at the percentile.
        at_percentile: f32,
        /// Allowed value at the percentile.
        percentile_max: f32,
        /// Where the capture was written.
        actual: String,
        /// Where the FLIP error map was written.
        difference: String,
    },
    /// Reading or writing an image failed.
    #[error("{path}: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// What failed.
        source: image::ImageError,
    },
}

/// Where reference images live: `tests/golden/`.
pub fn golden_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("golden")
}

fn blessing() -> bool {
    std::env::var_os("UPDATE_GOLDENS").is_some_and(|value| value != "0" && !value.is_empty())
}

fn sibling(path: &Path, suffix: &str) -> PathBuf {
    let stem = path
        .file_stem()
        .and_then(|s| s.to_str())
        .unwrap_or("capture");
    path.with_file_name(format!("{stem}-{suffix}.png"))
}

fn save(image: &RgbaImage, path: &Path) -> Result<(), GoldenError> {
    image.save(path).map_err(|source| GoldenError::Io {
        path: path.to_owned(),
        source,
    })
}

/// The FLIP error map of two same-sized images, its mean and its value at `percentile`.
fn flip_error(
    reference: &RgbaImage,
    actual: &RgbaImage,
    percentile: f32,
) -> (nv_flip::FlipImageFloat, f32, f32) {
    let (width, height) = actual.dimensions();
    let rgb = |image: &RgbaImage| -> Vec<u8> {
        image
            .pixels()
            .flat_map(|p| [p.0[0], p.0[1], p.0[2]])
            .collect()
    };
    let error_map = nv_flip::flip(
        nv_flip::FlipImageRgb8::with_data(width, height, &rgb(reference)),
        nv_flip::FlipImageRgb8::with_data(width, height, &rgb(actual)),
        nv_flip::DEFAULT_PIXELS_PER_DEGREE,
    );
    let mut pool = nv_flip::FlipPool::from_image(&error_map);
    let mean = pool.mean();
    let at_percentile = pool.get_percentile(percentile, true);
    (error_map, mean, at_percentile)
}

/// Why two renders differ more than allowed.
#[derive(Debug, thiserror::Error)]
#[error("{what}: FLIP mean {mean:.4}, p{percentile} {at_percentile:.4} (sizes {sizes:?})")]
pub struct ImagesDiffer {
    /// What was compared.
    pub what: String,
    /// Measured mean.
    pub mean: f32,
    /// Percentile (0..=100).
    pub percentile: f32,
    /// Measured value at the percentile.
    pub at_percentile: f32,
    /// Both sizes.
    pub sizes: ((u32, u32), (u32, u32)),
}

/// Compares two renders with FLIP (no reference file involved).
pub fn compare_images(
    what: &str,
    expected: &RgbaImage,
    actual: &RgbaImage,
    tolerance: FlipTolerance,
) -> Result<(), ImagesDiffer> {
    let sizes = (expected.dimensions(), actual.dimensions());
    if sizes.0 != sizes.1 {
        return Err(ImagesDiffer {
            what: what.to_owned(),
            mean: 1.0,
            percentile: tolerance.percentile * 100.0,
            at_percentile: 1.0,
            sizes,
        });
    }
    let (_, mean, at_percentile) = flip_error(expected, actual, tolerance.percentile);
    if mean <= tolerance.mean && at_percentile <= tolerance.percentile_max {
        Ok(())
    } else {
        Err(ImagesDiffer {
            what: what.to_owned(),
            mean,
            percentile: tolerance.percentile * 100.0,
            at_percentile,
            sizes,
        })
    }
}

/// Compares `actual` with `tests/golden/NAME.png` using FLIP.
///
/// A missing reference fails unless `UPDATE_GOLDENS=1`, which writes it (and rewrites references
/// that differ). On a failure, `NAME-actual.png` and `NAME-difference.png` are written next to the
/// reference.
pub fn check_golden(
    name: &str,
    actual: &RgbaImage,
    tolerance: FlipTolerance,
) -> Result<(), GoldenError> {
    let path = golden_dir().join(format!("{name}.png"));
    if !path.exists() {
        if blessing() {
            return save(actual, &path);
        }
        save(actual, &sibling(&path, "actual"))?;
        return Err(GoldenError::Missing(path));
    }
    let reference = image::open(&path)
        .map_err(|source| GoldenError::Io {
            path: path.clone(),
            source,
        })?
        .to_rgba8();
    if reference.dimensions() != actual.dimensions() {
        if blessing() {
            return save(actual, &path);
        }
        return Err(GoldenError::SizeMismatch {
            path,
            expected: reference.dimensions(),
            actual: actual.dimensions(),
        });
    }
    let (width, height) = actual.dimensions();
    let rgb = |image: &RgbaImage| -> Vec<u8> {
        image
            .pixels()
            .flat_map(|p| [p.0[0], p.0[1], p.0[2]])
            .collect()
    };
    let error_map = nv_flip::flip(
        nv_flip::FlipImageRgb8::with_data(width, height, &rgb(&reference)),
        nv_flip::FlipImageRgb8::with_data(width, height, &rgb(actual)),
        nv_flip::DEFAULT_PIXELS_PER_DEGREE,
    );
    let mut pool = nv_flip::FlipPool::from_image(&error_map);
    let mean = pool.mean();
    let at_percentile = pool.get_percentile(tolerance.percentile, true);
    if mean <= tolerance.mean && at_percentile <= tolerance.percentile_max {
        return Ok(());
    }
    if blessing() {
        return save(actual, &path);
    }
    let actual_path = sibling(&path, "actual");
    let difference_path = sibling(&path, "difference");
    save(actual, &actual_path)?;
    let colored = error_map.apply_color_lut(&nv_flip::magma_lut());
    let difference = image::RgbImage::from_raw(width, height, colored.to_vec())
        .map(|rgb| image::DynamicImage::ImageRgb8(rgb).to_rgba8())
        .unwrap_or_else(|| RgbaImage::new(width, height));
    save(&difference, &difference_path)?;
    Err(GoldenError::TooDifferent {
        path,
        mean,
        mean_max: tolerance.mean,
        percentile: tolerance.percentile * 100.0,
        at_percentile,
        percentile_max: tolerance.percentile_max,
        actual: actual_path.display().to_string(),
        difference: difference_path.display().to_string(),
    })
}
