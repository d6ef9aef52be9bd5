//! The environment light's cost: the street corner under the sky (its light on every material
//! and the background) against the same frame without it; the cobblestones under a uniform
//! environment with the relief's occlusion against without; and the prefiltering of a
//! 2048 × 1024 `.hdr` on the GPU, against the reading and decoding of the file on the CPU.

use std::sync::Arc;
use std::time::Instant;

use anyhow::{Context, Result};
use pom::render::environment::{ENVIRONMENT_BACKGROUND_NODE, ENVIRONMENT_PREFILTER_NODE};
use pom::{EnvironmentLight, EnvironmentSource, EquirectImage, RenderPath};

use super::Runner;
use super::scene::{PhaseTimes, Warmup};
use super::scene_shadows::{ShadowCase, ShadowLight, street_corner};
use pom::ParallaxOcclusionMaterial;

/// The street corner's frame phases (the resolve is added on the deferred path).
const FRAME_PHASES: [&str; 3] = ["prepass", "opaque", "post"];

/// The street corner lit by its sun without scene shadows, under the sky or not: per phase
/// (with the background's node under the sky), its milliseconds in each timed frame, and the
/// path the frames ran.
pub fn time_street_corner(
    size: (u32, u32),
    sky: bool,
    path: RenderPath,
    (warmup, frames): (Warmup, usize),
) -> Result<(&'static str, PhaseTimes)> {
    let case = ShadowCase {
        light: ShadowLight::Sun,
        shadows: false,
    };
    let mut scene = street_corner(size, case, path)?;
    let mut phases = FRAME_PHASES.to_vec();
    if sky {
        scene.insert_resource(EnvironmentLight::sky());
        phases.push(ENVIRONMENT_BACKGROUND_NODE);
    }
    let times = scene.time_phases(warmup, frames, &phases)?;
    Ok((scene.path_ran(), times))
}

/// A 2048 × 1024 equirectangular `.hdr` of a bright sky over a dim ground with a small sun,
/// written into a folder of its own made in the system's temporary folder (made new, so that
/// nothing planted at a predictable name is written through); returns the folder and the file.
fn write_test_hdr() -> Result<(std::path::PathBuf, std::path::PathBuf)> {
    let (width, height) = (2048, 1024);
    let image = image::Rgb32FImage::from_fn(width, height, |x, y| {
        let elevation = 0.5 - y as f32 / height as f32;
        let sun = ((x as f32 - 600.0).powi(2) + (y as f32 - 300.0).powi(2)).sqrt() < 6.0;
        let radiance = if sun {
            [50_000.0; 3]
        } else if elevation > 0.0 {
            [3_000.0 + 2_000.0 * elevation, 5_000.0, 8_000.0]
        } else {
            [600.0, 500.0, 400.0]
        };
        image::Rgb(radiance)
    });
    let nanos = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map_or(0, |since| since.subsec_nanos());
    let folder = std::env::temp_dir().join(format!("pom-bench-sky-{}-{nanos}", std::process::id()));
    std::fs::create_dir(&folder).with_context(|| format!("creating {}", folder.display()))?;
    let path = folder.join("sky.hdr");
    if let Err(error) = pom::files::write_image(&path, &image::DynamicImage::ImageRgb32F(image)) {
        std::fs::remove_dir_all(&folder).ok();
        return Err(error.into());
    }
    Ok((folder, path))
}

/// The prefiltering of a 2048 × 1024 `.hdr` into the default 256-texel cube: its GPU
/// milliseconds per frame (two copies of the image alternate, so every frame prefilters one
/// anew), and the milliseconds reading and decoding the file took on the CPU.
pub fn time_prefilter(
    size: (u32, u32),
    path: RenderPath,
    (warmup, frames): (Warmup, usize),
) -> Result<(&'static str, PhaseTimes, f64)> {
    let (folder, file) = write_test_hdr()?;
    let started = Instant::now();
    let decoded = EquirectImage::read(&file);
    let read_ms = started.elapsed().as_secs_f64() * 1000.0;
    std::fs::remove_dir_all(&folder).ok();
    let image = decoded?;
    let copies = [Arc::new(image.clone()), Arc::new(image)];
    let case = ShadowCase {
        light: ShadowLight::Sun,
        shadows: false,
    };
    let mut scene = street_corner(size, case, path)?;
    let mut frame = 0_usize;
    let times = scene.time_nodes(warmup, frames, &[ENVIRONMENT_PREFILTER_NODE], |app| {
        frame += 1;
        app.insert_resource(EnvironmentLight {
            source: EnvironmentSource::Equirect(copies[frame % 2].clone()),
            ..EnvironmentLight::default()
        });
    })?;
    Ok((scene.path_ran(), times, read_ms))
}

impl Runner<'_> {
    /// The environment light's cost: the street corner's frame under the sky against without
    /// it, the relief's occlusion on the cobblestones against none, a 2K `.hdr`'s prefiltering.
    pub(super) fn environment(&mut self, size: (u32, u32)) -> Result<()> {
        let place = (size, 1.0);
        let material = self.base.clone();
        let frames = (self.warmup, self.frames);
        let mut frame_ms = [None, None];
        for (index, sky) in [false, true].into_iter().enumerate() {
            let variant = if sky {
                "street corner, sky"
            } else {
                "street corner, no environment"
            };
            let (path, times) = time_street_corner(size, sky, self.path, frames)?;
            let frame =
                self.record_phases_and_frame("environment", size, (path, variant), &times)?;
            frame_ms[index] = Some(frame);
        }
        if let [Some(without), Some(with)] = frame_ms {
            self.ratio(
                "street corner frame: sky / no environment".into(),
                size,
                with,
                without,
            );
        }
        let mut scene = self.scene(size, &self.view.clone())?;
        scene.insert_resource(pom::EnvironmentLight::uniform([5_000.0; 3]));
        let mut occlusion_ms = [None, None];
        for (index, strength) in [0.0, 1.0].into_iter().enumerate() {
            let with = ParallaxOcclusionMaterial {
                relief_occlusion: strength,
                ..material.clone()
            };
            let variant = format!("uniform environment, relief occlusion {strength}");
            occlusion_ms[index] =
                Some(self.case_variant(&mut scene, "environment", place, with, variant)?);
        }
        if let [Some(off), Some(on)] = occlusion_ms {
            self.ratio("relief occlusion: on / off".into(), size, on, off);
        }
        drop(scene);
        let (path, times, read_ms) = time_prefilter(size, self.path, frames)?;
        let variant = "2048x1024 .hdr into a 256-texel cube".to_owned();
        for (node, times) in &times {
            self.record(
                "environment",
                place,
                &material,
                (path, *node, variant.clone()),
                times,
            )?;
        }
        // One reading, not a case of timed frames: printed beside the table.
        eprintln!("environment: reading and decoding the 2048x1024 .hdr took {read_ms:.1} ms");
        Ok(())
    }
}
