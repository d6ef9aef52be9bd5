//! The expectation steps: a capture against its reference image (FLIP), a statistic within
//! bounds, a statistic in order along captures.

use std::path::{Path, PathBuf};

use image::RgbaImage;

use super::Runner;
use crate::files::FileAccess;
use crate::script::Outcome;
use crate::script::format::{Rect, Statistic};
use crate::script::stats::{Measured, measure, stat_name};
use crate::{FlipComparison, FlipTolerance, Image, TextureKind, flip_compare};

/// Writes `image` as a PNG at `path`, making its folder first. Where the script named the
/// path (`scene_named`), something there that is not a regular file is refused: a FIFO would
/// block the run, a device swallow the image. A path the user chose (`--out`, or a trusted
/// script's) may be a device.
fn save(image: &RgbaImage, path: &Path, scene_named: bool) -> Result<(), String> {
    if scene_named
        && let Ok(existing) = std::fs::metadata(path)
        && !existing.is_file()
    {
        return Err(format!(
            "{} is not a regular file: the image is not written there",
            path.display()
        ));
    }
    if let Some(parent) = path.parent() {
        std::fs::create_dir_all(parent).map_err(|e| format!("{}: {e}", parent.display()))?;
    }
    crate::files::write_png(path, image).map_err(|error| error.to_string())
}

/// One `ExpectMatch` step's capture and files: the reference it reads (and writes when
/// blessing), and where the images of a failure go.
struct ReferenceMatch<'a> {
    actual: &'a RgbaImage,
    reference: PathBuf,
    actual_path: PathBuf,
    difference_path: PathBuf,
    bless: bool,
    /// Whether the script named the reference's path (not the user: a trusted script's).
    reference_scene_named: bool,
    /// Whether the script named the failure images' paths (not the user's `--out`).
    failures_scene_named: bool,
}

impl ReferenceMatch<'_> {
    /// Blessing: writes the capture as the reference, and removes the failure images an earlier
    /// run left, which showed a difference the new reference no longer has.
    fn write_reference(&self, detail: String) -> Result<Outcome, String> {
        save(self.actual, &self.reference, self.reference_scene_named)?;
        for stale in [&self.actual_path, &self.difference_path] {
            match std::fs::remove_file(stale) {
                Err(error) if error.kind() != std::io::ErrorKind::NotFound => {
                    return Err(format!("{}: {error}", stale.display()));
                }
                _ => {}
            }
        }
        Ok(Outcome::Blessed(detail))
    }

    /// The reference could not be read: written when blessing, else a failure.
    fn missing(&self, error: &crate::ImageError) -> Result<Outcome, String> {
        if self.bless {
            return self.write_reference(format!("wrote {}", self.reference.display()));
        }
        save(self.actual, &self.actual_path, self.failures_scene_named)?;
        Ok(Outcome::Failed(format!(
            "reference {} is missing ({error}); look at {} and run with --bless",
            self.reference.display(),
            self.actual_path.display()
        )))
    }

    /// The capture and the reference differ in size: rewritten when blessing, else a failure.
    fn size_differs(&self, expected: &RgbaImage) -> Result<Outcome, String> {
        if self.bless {
            return self.write_reference(format!(
                "rewrote {} at the new size",
                self.reference.display()
            ));
        }
        save(self.actual, &self.actual_path, self.failures_scene_named)?;
        Ok(Outcome::Failed(format!(
            "size {:?} differs from the reference's {:?}",
            self.actual.dimensions(),
            expected.dimensions()
        )))
    }

    /// A pass within `tolerance`; outside it, rewritten when blessing, else a failure with the
    /// capture and the error map written.
    fn judge(
        &self,
        comparison: &FlipComparison,
        tolerance: &FlipTolerance,
    ) -> Result<Outcome, String> {
        let detail = format!(
            "FLIP mean {:.4} (max {}), p{} {:.4} (max {})",
            comparison.mean,
            tolerance.mean,
            tolerance.percentile * 100.0,
            comparison.at_percentile,
            tolerance.percentile_max
        );
        if comparison.within(tolerance) {
            return Ok(Outcome::Passed(detail));
        }
        if self.bless {
            return self.write_reference(format!("{detail}; rewrote {}", self.reference.display()));
        }
        save(self.actual, &self.actual_path, self.failures_scene_named)?;
        save(
            &comparison.error_map,
            &self.difference_path,
            self.failures_scene_named,
        )?;
        Ok(Outcome::Failed(format!(
            "{detail}; see {} and {}",
            self.actual_path.display(),
            self.difference_path.display()
        )))
    }
}

impl Runner<'_> {
    /// `ExpectMatch`: compares capture `capture` with the reference image at `reference`.
    pub(super) fn expect_match(
        &self,
        capture: &str,
        reference: &str,
        tolerance: &FlipTolerance,
    ) -> Result<Outcome, String> {
        let check = self.reference_match(capture, reference)?;
        let expected = match Image::load(&check.reference, TextureKind::Color) {
            Ok(expected) => expected.to_rgba8(),
            Err(error) => return check.missing(&error),
        };
        match flip_compare(&expected, check.actual, tolerance.percentile) {
            Some(comparison) => check.judge(&comparison, tolerance),
            None => check.size_differs(&expected),
        }
    }

    /// The files of comparing `capture` with `reference` (a PNG file, as checked): failure
    /// images are named after the reference and go to the options' folder, or next to the
    /// reference, where they stay inside the folder the script may write in as it does.
    fn reference_match(
        &self,
        capture: &str,
        reference: &str,
    ) -> Result<ReferenceMatch<'_>, String> {
        // Blessing writes it: it must stay where the script may write.
        let reference_path = self.resolve(reference)?;
        let stem = Path::new(reference)
            .file_stem()
            .ok_or_else(|| format!("reference {reference:?} names no file"))?
            .to_string_lossy();
        let failure_image = |suffix: &str| -> Result<PathBuf, String> {
            let name = format!("{stem}-{suffix}.png");
            match &self.options.out_dir {
                Some(out_dir) => Ok(out_dir.join(name)),
                None => self.resolve(&Path::new(reference).with_file_name(name).to_string_lossy()),
            }
        };
        Ok(ReferenceMatch {
            actual: &self.captures[capture].image,
            actual_path: failure_image("actual")?,
            difference_path: failure_image("difference")?,
            reference: reference_path,
            bless: self.options.bless,
            reference_scene_named: self.options.file_access == FileAccess::InsideFolder,
            failures_scene_named: self.options.file_access == FileAccess::InsideFolder
                && self.options.out_dir.is_none(),
        })
    }

    /// `ExpectStat`: the statistic of a capture (over `rect`) within `min..=max` (each open
    /// when absent).
    pub(super) fn expect_stat(
        &self,
        capture: &str,
        stat: &Statistic,
        rect: Option<Rect>,
        min: Option<f32>,
        max: Option<f32>,
    ) -> Result<Outcome, String> {
        let value = self.statistic(capture, stat, rect)?;
        let low = min.unwrap_or(f32::NEG_INFINITY);
        let high = max.unwrap_or(f32::INFINITY);
        let detail = format!("{} = {value:.4}, bounds {low}..={high}", stat_name(stat));
        Ok(if (low..=high).contains(&value) {
            Outcome::Passed(detail)
        } else {
            Outcome::Failed(detail)
        })
    }

    /// `ExpectMonotonic`: the statistic (over `rect`) grows (or shrinks) strictly along
    /// `captures`.
    pub(super) fn expect_monotonic(
        &self,
        captures: &[String],
        stat: &Statistic,
        rect: Option<Rect>,
        increasing: bool,
    ) -> Result<Outcome, String> {
        let values = captures
            .iter()
            .map(|capture| self.statistic(capture, stat, rect))
            .collect::<Result<Vec<f32>, String>>()?;
        let ordered = values.windows(2).all(|pair| {
            if increasing {
                pair[1] > pair[0]
            } else {
                pair[1] < pair[0]
            }
        });
        let list: Vec<String> = values.iter().map(|v| format!("{v:.4}")).collect();
        let detail = format!(
            "{} = [{}], {}",
            stat_name(stat),
            list.join(", "),
            if increasing {
                "must grow"
            } else {
                "must shrink"
            }
        );
        Ok(if ordered {
            Outcome::Passed(detail)
        } else {
            Outcome::Failed(detail)
        })
    }

    /// `stat` of capture `capture` over `rect`; fails when the rectangle holds nothing the
    /// statistic counts (the loader checked the capture's debug view).
    fn statistic(
        &self,
        capture: &str,
        stat: &Statistic,
        rect: Option<Rect>,
    ) -> Result<f32, String> {
        let measured = |name: &str| {
            let taken = &self.captures[name];
            Measured {
                image: &taken.image,
                surface: taken.surface.as_ref(),
            }
        };
        let baseline = match stat {
            Statistic::UvShift { baseline } => Some(measured(baseline)),
            _ => None,
        };
        measure(stat, measured(capture), rect, baseline).ok_or_else(|| {
            let region = rect.map_or("the whole image".to_owned(), |rect| {
                format!("rect {rect:?}")
            });
            format!(
                "{} of capture {capture:?} over {region}: no pixel of a parallax surface to count",
                stat_name(stat)
            )
        })
    }
}
