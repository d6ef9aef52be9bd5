//! One benchmark scene: the plugin's preview plane with a parallax material, rendered offscreen
//! with blocking GPU timing. The plugin does all the rendering; this only drives it.

use std::time::{Duration, Instant};

use anyhow::{Context, Result, bail};
use image::{Rgba32FImage, RgbaImage};
use pom::preview::{PreviewView, spawn_preview, spawn_preview_mesh};
use pom::render::{PROBE_PASS, RenderTarget, TexelRateProbe, resolve_gpu_timings};
use pom::{
    App, Assets, Camera, GpuContext, GpuTimings, Image, Mesh, ParallaxOcclusionMaterial, PomPlugin,
    RenderPlugin, TargetFormat, TimingMode,
};

use crate::preview_textures::PreviewTextures;

/// Untimed frames before a measurement.
#[derive(Clone, Copy, Debug)]
pub struct Warmup {
    /// At least this many frames.
    pub frames: usize,
    /// And at least this long: a GPU left idle (while the CPU compares images or builds a mesh)
    /// lowers its clocks, and a few short frames do not bring them back.
    pub least: Duration,
}

/// The pass every case times: the main render pass, where the material's shader runs.
pub const TIMED_PASS: &str = "main pass";

/// How a [`BenchScene`] is set up.
pub struct SceneOptions {
    /// Image size in pixels.
    pub size: (u32, u32),
    /// `false` leaves GPU timing off, as on an adapter without it.
    pub timestamps: bool,
    /// What the target stores: sRGB pixels, or raw floats for measuring a debug view.
    pub format: TargetFormat,
    /// A mesh to draw in place of the flat preview plane (a displaced grid).
    pub surface: Option<Mesh>,
}

impl SceneOptions {
    /// The flat plane into an sRGB target of `size`, timed.
    pub fn timed_plane(size: (u32, u32)) -> Self {
        Self {
            size,
            timestamps: true,
            format: TargetFormat::Srgb8,
            surface: None,
        }
    }
}

/// A headless app showing one material on the preview plane (or a mesh in its place).
pub struct BenchScene {
    app: App,
}

impl BenchScene {
    /// Sets up the scene with `material` wearing `textures`, seen from `view`.
    pub fn new(
        options: SceneOptions,
        textures: &PreviewTextures,
        material: ParallaxOcclusionMaterial,
        view: &PreviewView,
    ) -> Result<Self> {
        let (width, height) = options.size;
        let mut app = App::new();
        let timing = options.timestamps.then_some(TimingMode::Blocking);
        app.add_plugin(
            RenderPlugin::headless(width, height)
                .with_format(options.format)
                .with_gpu_timing(timing),
        );
        app.add_plugin(PomPlugin);
        app.finish().context("starting the GPU")?;
        let images = app
            .resources
            .get_mut::<Assets<Image>>()
            .context("the render plugin provides no image store")?;
        let material = textures.clone().attach(images, material);
        match options.surface {
            Some(mesh) => spawn_preview_mesh(&mut app, mesh, material, view),
            None => spawn_preview(&mut app, material, view),
        }
        .context("setting up the scene")?;
        Ok(Self { app })
    }

    /// Sets the colour the image is cleared to (alpha 0 marks pixels nothing was drawn on).
    pub fn set_clear_color(&mut self, color: pom::Color) {
        for camera in self.app.world.query_mut::<&mut Camera>() {
            camera.clear_color = color;
        }
    }

    /// Renders one frame and reads it back as sRGB pixels.
    pub fn capture(&mut self) -> Result<RgbaImage> {
        self.app.update().context("rendering a frame")?;
        self.check_errors()?;
        Ok(pom::render::capture(&self.app)?)
    }

    /// Renders one frame into a [`TargetFormat::Float32`] scene and reads back the raw floats.
    pub fn capture_f32(&mut self) -> Result<Rgba32FImage> {
        self.app.update().context("rendering a frame")?;
        self.check_errors()?;
        Ok(pom::render::capture_f32(&self.app)?)
    }

    fn check_errors(&self) -> Result<()> {
        if let Some(gpu) = self.app.resources.get::<GpuContext>()
            && let Some(error) = gpu.take_uncaptured_errors().first()
        {
            bail!("GPU error: {error}");
        }
        Ok(())
    }

    /// The adapter the scene renders on.
    pub fn adapter(&self) -> Option<pom::wgpu::AdapterInfo> {
        self.app
            .resources
            .get::<GpuContext>()
            .map(GpuContext::adapter_info)
    }

    /// Whether the adapter gives timings.
    pub fn timing_supported(&self) -> bool {
        !matches!(
            self.app.resources.get::<GpuTimings>(),
            None | Some(GpuTimings::Unsupported)
        )
    }

    /// Changes the material's parameters, keeping its textures.
    pub fn configure(&mut self, change: impl Fn(&mut ParallaxOcclusionMaterial)) {
        for material in self.app.world.query_mut::<&mut ParallaxOcclusionMaterial>() {
            change(material);
        }
    }

    /// Renders `warmup.frames` untimed frames (and more until `warmup.least` has passed), then
    /// `frames` timed ones; returns the main pass's milliseconds per timed frame.
    pub fn time(&mut self, warmup: Warmup, frames: usize) -> Result<Vec<f64>> {
        self.time_frames(warmup, frames, TIMED_PASS, |app| Ok(app.update()?))
    }

    /// Times the plugin's [`TexelRateProbe`] taking `taps` samples per pixel over the whole
    /// target, like [`BenchScene::time`].
    pub fn time_texel_rate_probe(
        &mut self,
        taps: u32,
        warmup: Warmup,
        frames: usize,
    ) -> Result<Vec<f64>> {
        let gpu = self.app.resources.require::<GpuContext>()?;
        let target = self.app.resources.require::<RenderTarget>()?;
        let probe = TexelRateProbe::new(gpu, target.color.format(), taps);
        self.time_frames(warmup, frames, PROBE_PASS, |app| {
            probe.render(&mut app.resources)?;
            resolve_gpu_timings(&mut app.world, &mut app.resources)?;
            Ok(())
        })
    }

    fn time_frames(
        &mut self,
        warmup: Warmup,
        frames: usize,
        pass: &str,
        mut render: impl FnMut(&mut App) -> Result<()>,
    ) -> Result<Vec<f64>> {
        let started = Instant::now();
        let mut warmed = 0;
        while warmed < warmup.frames || started.elapsed() < warmup.least {
            render(&mut self.app).context("rendering a warm-up frame")?;
            warmed += 1;
        }
        let mut times = Vec::with_capacity(frames);
        for frame in 0..frames {
            render(&mut self.app).context("rendering a timed frame")?;
            let ms = self
                .app
                .resources
                .get::<GpuTimings>()
                .and_then(|timings| timings.pass_ms(pass));
            match ms {
                Some(ms) => times.push(ms),
                None => bail!("timed frame {frame}: the GPU gave no valid timestamps for {pass}"),
            }
        }
        self.check_errors().context("while timing")?;
        Ok(times)
    }
}
