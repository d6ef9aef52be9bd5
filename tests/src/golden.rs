//! Reference-image comparison with NVIDIA FLIP.

use std::path::{Path, PathBuf};

use image::RgbaImage;

pub use pom::FlipTolerance;

/// How many pixels of `a` and `b` (of one size) differ at all.
pub fn differing_pixels(a: &RgbaImage, b: &RgbaImage) -> usize {
    a.pixels().zip(b.pixels()).filter(|(a, b)| a != b).count()
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

/// The FLIP comparison of two same-sized images.
fn flip_error(reference: &RgbaImage, actual: &RgbaImage, percentile: f32) -> pom::FlipComparison {
    // Callers check the sizes first.
    pom::flip_compare(reference, actual, percentile).expect("same sizes")
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
    let comparison = flip_error(expected, actual, tolerance.percentile);
    if comparison.within(&tolerance) {
        Ok(())
    } else {
        Err(ImagesDiffer {
            what: what.to_owned(),
            mean: comparison.mean,
            percentile: tolerance.percentile * 100.0,
            at_percentile: comparison.at_percentile,
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
    let comparison = flip_error(&reference, actual, tolerance.percentile);
    if comparison.within(&tolerance) {
        return Ok(());
    }
    if blessing() {
        return save(actual, &path);
    }
    let actual_path = sibling(&path, "actual");
    let difference_path = sibling(&path, "difference");
    save(actual, &actual_path)?;
    save(&comparison.error_map, &difference_path)?;
    Err(GoldenError::TooDifferent {
        path,
        mean: comparison.mean,
        mean_max: tolerance.mean,
        percentile: tolerance.percentile * 100.0,
        at_percentile: comparison.at_percentile,
        percentile_max: tolerance.percentile_max,
        actual: actual_path.display().to_string(),
        difference: difference_path.display().to_string(),
    })
}
