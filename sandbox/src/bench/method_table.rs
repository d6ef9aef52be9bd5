//! The method table: the marching methods at 8, 16, 32 and 64 samples and MaxMip over its
//! pyramid, each with its hit error against the exact intersection (the CPU reference on the
//! bench's height map, 70° from the normal), its height fetches per pixel (the `samples` view
//! of the timed scene, view ray only) and its time. The seed port's row comes from
//! `--only seed-port` in the same run.

use std::fmt::Write as _;

use anyhow::Result;
use pom::material::Choice;
use pom::parallax::MAX_SAMPLES_LIMIT;
use pom::reference::errors_in_texels;
use pom::{Channel, HeightField, ParallaxMethod, ParallaxOcclusionMaterial, ShadowMode};
use serde::Serialize;

use super::Runner;
use super::sample_count::SampleCounter;
use super::scene::BenchScene;

const SAMPLES: [u32; 4] = [8, 16, 32, 64];
const MARCHING: [ParallaxMethod; 3] = [
    ParallaxMethod::Steep,
    ParallaxMethod::Occlusion,
    ParallaxMethod::Relief,
];
/// The angle of the error columns (a grazing view, where the methods differ most), and the entry points per side of the grid.
const ERROR_ANGLE_DEGREES: f32 = 70.0;
const ERROR_GRID: u32 = 24;

/// One method at one sample count (none for MaxMip) at one size.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct MethodRow {
    /// The method's name (`steep`, `pom`, `relief`, `maxmip`).
    pub method: &'static str,
    /// Samples per view ray (min = max), or `None` for MaxMip (its pyramid decides).
    pub samples: Option<u32>,
    /// Image width.
    pub width: u32,
    /// Image height.
    pub height: u32,
    /// The path the timed frames ran.
    pub path: &'static str,
    /// Median milliseconds of the material's phases, with the bench material's other settings
    /// (its shadow mode among them).
    pub ms: f64,
    /// View-ray height fetches per surface pixel.
    pub fetches_per_pixel: f64,
    /// Max-mip's surface pixels whose fetches reached the count's ceiling (256): counted at the
    /// ceiling, so `fetches_per_pixel` is a lower bound where this is not 0. Always 0 for the
    /// other methods, which cannot take more than their `max_samples`.
    pub saturated_pixels: u64,
    /// Mean distance in texels from the exact intersection (CPU reference).
    pub mean_error_texels: f32,
    /// 99th percentile of that distance.
    pub p99_error_texels: f32,
}

/// The table's rows: each marching method at each sample count, then MaxMip (no count).
fn table_rows() -> impl Iterator<Item = (ParallaxMethod, Option<u32>)> {
    MARCHING
        .iter()
        .flat_map(|&method| SAMPLES.map(|samples| (method, Some(samples))))
        .chain([(ParallaxMethod::MaxMip, None)])
}

/// The (mean, p99) error in texels of `method` at `samples` on `field`, against the exact
/// intersection, over a grid of entry points seen along +u at [`ERROR_ANGLE_DEGREES`].
fn errors(
    field: &HeightField,
    method: ParallaxMethod,
    samples: u32,
    height_scale: f32,
) -> (f32, f32) {
    let mut distances = errors_in_texels(
        field,
        method,
        ERROR_ANGLE_DEGREES,
        height_scale,
        samples,
        ERROR_GRID,
    );
    let mean = distances.iter().sum::<f32>() / distances.len() as f32;
    distances.sort_by(f32::total_cmp);
    let p99 = distances[(distances.len() * 99 / 100).min(distances.len() - 1)];
    (mean, p99)
}

impl Runner<'_> {
    /// Every row of the table at `size`.
    pub(super) fn method_table(&mut self, scene: &mut BenchScene, size: (u32, u32)) -> Result<()> {
        // The errors depend on neither the size nor the path: computed in the first table.
        if self.method_errors.is_empty() {
            let convention = self.base.height_convention;
            let field = HeightField::from_image(&self.textures.height, Channel::Red, convention);
            self.method_errors = table_rows()
                .map(|(method, samples)| {
                    errors(&field, method, samples.unwrap_or(0), self.base.height_scale)
                })
                .collect();
        }
        let mut counter = SampleCounter::new(size, self.textures, &self.view, self.path)?;
        for (row, (method, samples)) in table_rows().enumerate() {
            let material = ParallaxOcclusionMaterial {
                method,
                min_samples: samples.unwrap_or(self.base.min_samples),
                max_samples: samples.unwrap_or(self.base.max_samples),
                ..self.base.clone()
            };
            let variant = samples.map_or("pyramid".to_owned(), |n| format!("{n} samples"));
            let place = (size, self.view.tiling);
            let timed =
                self.case_variant(scene, "method_table", place, material.clone(), variant)?;
            // The heat view scales by max_samples: MaxMip's fetches get the whole range.
            let counted = ParallaxOcclusionMaterial {
                shadows: ShadowMode::Off,
                max_samples: samples.unwrap_or(MAX_SAMPLES_LIMIT),
                ..material
            };
            let count = counter.count(&counted)?;
            let (mean, p99) = self.method_errors[row];
            self.method_rows.push(MethodRow {
                method: method.name(),
                samples,
                width: size.0,
                height: size.1,
                path: timed.path,
                ms: timed.ms,
                fetches_per_pixel: count.total as f64 / count.surface_pixels.max(1) as f64,
                saturated_pixels: if samples.is_none() {
                    count.saturated_pixels
                } else {
                    0
                },
                mean_error_texels: mean,
                p99_error_texels: p99,
            });
        }
        Ok(())
    }
}

/// The rows as a Markdown table.
pub fn table(rows: &[MethodRow]) -> String {
    if rows.is_empty() {
        return String::new();
    }
    let mut out = format!(
        "\nmethods against the exact intersection ({ERROR_ANGLE_DEGREES}°, {ERROR_GRID}² entry \
         points; fetches: at the ceiling in `saturated` pixels):\n| method | samples | size | \
         path | mean error (texel) | p99 error (texel) | fetches / pixel | saturated | ms |\n\
         | --- | --- | --- | --- | --- | --- | --- | --- | --- |\n"
    );
    for row in rows {
        let samples = row.samples.map_or("pyramid".to_owned(), |n| n.to_string());
        let _ = writeln!(
            out,
            "| {} | {samples} | {}x{} | {} | {:.3} | {:.3} | {:.1} | {} | {:.3} |",
            row.method,
            row.width,
            row.height,
            row.path,
            row.mean_error_texels,
            row.p99_error_texels,
            row.fetches_per_pixel,
            row.saturated_pixels,
            row.ms
        );
    }
    out
}
