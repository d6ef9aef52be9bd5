//! Counting POM's height samples: the material's `samples` debug view rendered into a float
//! target, each pixel's heat colour decoded back into the number of samples its march took.

use anyhow::{Result, bail};
use pom::preview::PreviewView;
use pom::{Color, DebugView, ParallaxOcclusionMaterial, TargetFormat};
use serde::Serialize;

use super::Runner;
use super::scene::{BenchScene, SceneOptions};
use crate::preview_textures::PreviewTextures;

/// The view-ray height samples of one frame.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct SampleCount {
    /// Height samples taken over the whole image.
    pub total: u64,
    /// Pixels the surface covers.
    pub surface_pixels: u64,
    /// Of those, pixels where a march ran (not past the LOD threshold).
    pub marching_pixels: u64,
    /// Of those, pixels whose count reached the heat map's maximum (`max_samples`): a method
    /// that can take more (max-mip) is counted at that maximum there.
    pub saturated_pixels: u64,
}

/// Height samples per second of the POM pass, against the texel-rate limits.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct SampleRate {
    /// Image width.
    pub width: u32,
    /// Image height.
    pub height: u32,
    /// The samples one frame takes.
    pub count: SampleCount,
    /// Median milliseconds of the POM main pass (shadows off) they were taken in.
    pub pom_ms: f64,
    /// The path POM's timed frames ran, `forward` or `deferred`.
    pub path: &'static str,
    /// Height samples per second, in billions.
    pub gsamples_per_s: f64,
    /// Bilinear samples per second the fragment stage reached in the texel-rate probe at this
    /// size, in billions: the limit of the path POM runs on.
    pub fragment_path_gtexels_per_s: f64,
    /// `gsamples_per_s` over `fragment_path_gtexels_per_s`.
    pub fraction_of_fragment_path: f64,
    /// Median milliseconds of the probe at one sample per pixel: what a full-screen pass costs
    /// before any texture work, the floor under every method's time.
    pub one_tap_pass_ms: f64,
    /// `gsamples_per_s` over the whole chip's bilinear texel-rate limit, when it is known.
    pub fraction_of_chip: Option<f64>,
}

/// What the fragment-stage probe measured at one size.
#[derive(Clone, Copy, Debug)]
pub struct ProbeResult {
    /// Samples per pixel.
    pub taps: u32,
    /// Median milliseconds of the probe pass.
    pub median_ms: f64,
    /// Median milliseconds of the probe at one sample per pixel.
    pub one_tap_ms: f64,
}

impl SampleRate {
    /// The rate of `count` samples in `pom_ms` (frames that ran on `path`), against the
    /// fragment path's `probe` and the chip's `chip_gtexels` (G texels/s) if known.
    pub fn new(
        size: (u32, u32),
        count: SampleCount,
        (pom_ms, path): (f64, &'static str),
        probe: ProbeResult,
        chip_gtexels: Option<f64>,
    ) -> Self {
        let per_second = |samples: f64, ms: f64| samples / (ms * 1e-3) * 1e-9;
        let gsamples_per_s = per_second(count.total as f64, pom_ms);
        let probe_samples = f64::from(probe.taps) * f64::from(size.0) * f64::from(size.1);
        let fragment_path_gtexels_per_s = per_second(probe_samples, probe.median_ms);
        Self {
            width: size.0,
            height: size.1,
            count,
            pom_ms,
            path,
            gsamples_per_s,
            fragment_path_gtexels_per_s,
            fraction_of_fragment_path: gsamples_per_s / fragment_path_gtexels_per_s,
            one_tap_pass_ms: probe.one_tap_ms,
            fraction_of_chip: chip_gtexels.map(|limit| gsamples_per_s / limit),
        }
    }
}

/// Renders `material` once with the `samples` debug view and counts the view ray's samples.
/// Shadow rays are not counted: measure with shadows off.
pub fn count_view_samples(
    size: (u32, u32),
    textures: &PreviewTextures,
    material: &ParallaxOcclusionMaterial,
    view: &PreviewView,
    path: pom::RenderPath,
) -> Result<SampleCount> {
    SampleCounter::new(size, textures, view, path)?.count(material)
}

/// A scene for counting samples: a float target cleared to alpha 0, reused for every material
/// counted at one size.
pub struct SampleCounter {
    scene: BenchScene,
}

impl SampleCounter {
    /// The preview plane with `textures` seen from `view`, at `size`, on `path`.
    pub fn new(
        size: (u32, u32),
        textures: &PreviewTextures,
        view: &PreviewView,
        path: pom::RenderPath,
    ) -> Result<Self> {
        let options = SceneOptions {
            timestamps: false,
            format: TargetFormat::Float32,
            ..SceneOptions::timed_plane(size, path)
        };
        let material = ParallaxOcclusionMaterial {
            debug_view: DebugView::Samples,
            ..ParallaxOcclusionMaterial::default()
        };
        let mut scene = BenchScene::new(options, textures, material, view)?;
        scene.set_clear_color(Color {
            a: 0.0,
            ..Color::BLACK
        });
        Ok(Self { scene })
    }

    /// Renders `material` (keeping the scene's textures) once with the `samples` debug view and
    /// counts the view ray's samples. Shadow rays are not counted: measure with shadows off.
    pub fn count(&mut self, material: &ParallaxOcclusionMaterial) -> Result<SampleCount> {
        let material = ParallaxOcclusionMaterial {
            debug_view: DebugView::Samples,
            ..material.clone()
        };
        // The shader scales the heat map by the clamped count, as the renderer uploads it.
        let max_samples = material.sanitized().max_samples;
        Runner::configure(&mut self.scene, &material);
        let image = self.scene.capture_f32()?;
        let mut count = SampleCount {
            total: 0,
            surface_pixels: 0,
            marching_pixels: 0,
            saturated_pixels: 0,
        };
        for pixel in image.pixels() {
            let Some(samples) = decode_heat(pixel.0, max_samples) else {
                continue;
            };
            count.surface_pixels += 1;
            count.total += u64::from(samples);
            count.marching_pixels += u64::from(samples > 0);
            count.saturated_pixels += u64::from(samples >= max_samples);
        }
        if count.surface_pixels == 0 {
            bail!("the samples view drew nothing: the surface is out of view");
        }
        Ok(count)
    }
}

/// The count behind one pixel of the `samples` view, or `None` where nothing was drawn
/// (alpha 0). The shader's heat map is clamp(3t − (0, 1, 2)) with t = samples / max, so
/// r + g + b = 3t exactly.
fn decode_heat(pixel: [f32; 4], max_samples: u32) -> Option<u32> {
    if pixel[3] <= 0.0 {
        return None;
    }
    let t = (pixel[0] + pixel[1] + pixel[2]) / 3.0;
    Some((t * max_samples.max(1) as f32).round() as u32)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `heat` of pom.wgsl.
    fn heat(t: f32) -> [f32; 3] {
        let x = t.clamp(0.0, 1.0) * 3.0;
        [x, x - 1.0, x - 2.0].map(|c| c.clamp(0.0, 1.0))
    }

    #[test]
    fn every_count_decodes_to_itself_and_background_to_nothing() {
        for max in [1, 8, 50, 256] {
            for samples in 0..=max {
                let [r, g, b] = heat(samples as f32 / max as f32);
                assert_eq!(decode_heat([r, g, b, 1.0], max), Some(samples));
            }
        }
        assert_eq!(decode_heat([0.0, 0.0, 0.0, 0.0], 50), None);
    }

    #[test]
    fn rates_are_samples_over_time_against_both_limits() {
        let count = SampleCount {
            total: 4_000_000,
            surface_pixels: 1_000_000,
            marching_pixels: 500_000,
            saturated_pixels: 0,
        };
        let probe = ProbeResult {
            taps: 64,
            median_ms: 8.0,
            one_tap_ms: 0.5,
        };
        // 4 M samples in 2 ms = 2 G/s; the probe: 64 × 1000 × 1000 in 8 ms = 8 G/s.
        let rate = SampleRate::new((1000, 1000), count, (2.0, "forward"), probe, Some(100.0));
        assert!((rate.gsamples_per_s - 2.0).abs() < 1e-12);
        assert!((rate.fragment_path_gtexels_per_s - 8.0).abs() < 1e-12);
        assert!((rate.fraction_of_fragment_path - 0.25).abs() < 1e-12);
        assert!((rate.fraction_of_chip.unwrap() - 0.02).abs() < 1e-12);
    }
}
