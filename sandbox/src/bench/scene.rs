//! One benchmark scene: the plugin's preview plane with a parallax material, rendered offscreen
//! with blocking GPU timing. The plugin does all the rendering; this only drives it.

use anyhow::{Context, Result, bail};
use pom::preview::{PreviewView, spawn_preview};
use pom::{
    App, Assets, GpuContext, GpuTimings, Image, ParallaxOcclusionMaterial, PomPlugin, RenderPlugin,
    TimingMode,
};

use crate::preview_textures::PreviewTextures;

/// The pass every case times: the main render pass, where the material's shader runs.
pub const TIMED_PASS: &str = "main pass";

/// A headless app showing one material on the preview plane.
pub struct BenchScene {
    app: App,
}

impl BenchScene {
    /// Sets up the plane at `size` with `material` wearing `textures`, seen from `view`.
    /// `timestamps: false` leaves GPU timing off, as on an adapter without it.
    pub fn new(
        size: (u32, u32),
        textures: &PreviewTextures,
        material: ParallaxOcclusionMaterial,
        view: &PreviewView,
        timestamps: bool,
    ) -> Result<Self> {
        let mut app = App::new();
        let timing = timestamps.then_some(TimingMode::Blocking);
        app.add_plugin(RenderPlugin::headless(size.0, size.1).with_gpu_timing(timing));
        app.add_plugin(PomPlugin);
        app.finish().context("starting the GPU")?;
        let images = app
            .resources
            .get_mut::<Assets<Image>>()
            .context("the render plugin provides no image store")?;
        let material = textures.clone().attach(images, material);
        spawn_preview(&mut app, material, view).context("setting up the plane")?;
        Ok(Self { app })
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

    /// Renders `warmup` untimed frames, then `frames` timed ones; returns the main pass's
    /// milliseconds per timed frame.
    pub fn time(&mut self, warmup: usize, frames: usize) -> Result<Vec<f64>> {
        for _ in 0..warmup {
            self.app.update().context("rendering a warm-up frame")?;
        }
        let mut times = Vec::with_capacity(frames);
        for frame in 0..frames {
            self.app.update().context("rendering a timed frame")?;
            let ms = self
                .app
                .resources
                .get::<GpuTimings>()
                .and_then(|timings| timings.pass_ms(TIMED_PASS));
            match ms {
                Some(ms) => times.push(ms),
                None => bail!("timed frame {frame}: the GPU gave no valid timestamps"),
            }
        }
        if let Some(gpu) = self.app.resources.get::<GpuContext>()
            && let Some(error) = gpu.take_uncaptured_errors().first()
        {
            bail!("GPU error while timing: {error}");
        }
        Ok(times)
    }
}
