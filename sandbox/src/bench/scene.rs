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

/// What every case times: the material's phases (depth prepass + opaque), where its shaders
/// run. Post-processing is the same for every material and is reported on its own (`phases`).
pub const TIMED_PASS: &str = "prepass+opaque";
/// The phases [`TIMED_PASS`] adds up.
const MATERIAL_PHASES: [&str; 2] = ["prepass", "opaque"];

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
    /// Whether frames run the depth prepass.
    pub depth_prepass: bool,
}

impl SceneOptions {
    /// The flat plane into an sRGB target of `size`, timed.
    pub fn timed_plane(size: (u32, u32)) -> Self {
        Self {
            size,
            timestamps: true,
            format: TargetFormat::Srgb8,
            surface: None,
            depth_prepass: true,
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
                .with_gpu_timing(timing)
                .with_depth_prepass(options.depth_prepass),
        );
        app.add_plugin(PomPlugin)
            .add_plugin(pom::seed_port::seed_port_plugin());
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

    /// A scene around an app already set up (with blocking GPU timing).
    pub fn from_app(app: App) -> Self {
        Self { app }
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

    /// Replaces the plane with `count` copies stacked along its normal `spacing` apart, spawned
    /// deepest first. With `own_meshes` each copy gets its own mesh, made deepest first: separate
    /// batches in mesh order, drawn back to front (the worst order); else they share one, and
    /// the renderer draws the instances nearest first.
    pub fn stack_planes(&mut self, count: usize, spacing: f32, own_meshes: bool) -> Result<()> {
        let (entity, mesh, material, transform) = self
            .app
            .world
            .query_mut::<(
                pom::hecs::Entity,
                &pom::Handle<Mesh>,
                &ParallaxOcclusionMaterial,
                &pom::Transform,
            )>()
            .into_iter()
            .map(|(entity, mesh, material, transform)| {
                (entity, mesh.clone(), material.clone(), *transform)
            })
            .next()
            .context("the scene has no parallax plane")?;
        self.app.world.despawn(entity)?;
        let normal = transform.rotation * glam::Vec3::Y;
        let meshes = self.app.resources.require_mut::<Assets<Mesh>>()?;
        let plane = meshes
            .get(mesh.id())
            .cloned()
            .context("the plane's mesh is not loaded")?;
        for index in (0..count).rev() {
            let mesh = if own_meshes {
                self.app
                    .resources
                    .require_mut::<Assets<Mesh>>()?
                    .add(plane.clone())
            } else {
                mesh.clone()
            };
            let mut behind = transform;
            behind.translation -= normal * spacing * index as f32;
            // With the global transform: adding it later would move entities between
            // archetypes and reorder them, and the order is the draw order.
            self.app.world.spawn((
                mesh.clone(),
                material.clone(),
                behind,
                pom::GlobalTransform(behind.to_affine()),
            ));
        }
        Ok(())
    }

    /// Draws the plane with the seed's shader ([`pom::seed_port::SeedPortMaterial`], with the
    /// parallax material's textures and shared settings) instead of ours.
    pub fn use_seed_port(&mut self) -> Result<()> {
        let replaced = pom::seed_port::replace_parallax_materials(&mut self.app.world);
        anyhow::ensure!(replaced > 0, "the scene has no parallax plane");
        Ok(())
    }

    /// Changes the material's parameters, keeping its textures.
    pub fn configure(&mut self, change: impl Fn(&mut ParallaxOcclusionMaterial)) {
        for material in self.app.world.query_mut::<&mut ParallaxOcclusionMaterial>() {
            change(material);
        }
    }

    /// Renders `warmup.frames` untimed frames (and more until `warmup.least` has passed), then
    /// `frames` timed ones; returns the material phases' milliseconds per timed frame.
    pub fn time(&mut self, warmup: Warmup, frames: usize) -> Result<Vec<f64>> {
        let phases = self.time_phases(warmup, frames, &MATERIAL_PHASES)?;
        Ok((0..frames)
            .map(|frame| phases.iter().map(|times| times[frame]).sum())
            .collect())
    }

    /// Like [`BenchScene::time`], the milliseconds of each of `phases` per timed frame.
    pub fn time_phases(
        &mut self,
        warmup: Warmup,
        frames: usize,
        phases: &[&str],
    ) -> Result<Vec<Vec<f64>>> {
        self.time_frames(warmup, frames, phases, |app| Ok(app.update()?))
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
        let mut times = self.time_frames(warmup, frames, &[PROBE_PASS], |app| {
            probe.render(&mut app.resources)?;
            resolve_gpu_timings(&mut app.world, &mut app.resources)?;
            Ok(())
        })?;
        Ok(times.pop().unwrap_or_default())
    }

    /// Per pass of `passes`, its milliseconds in each timed frame.
    fn time_frames(
        &mut self,
        warmup: Warmup,
        frames: usize,
        passes: &[&str],
        mut render: impl FnMut(&mut App) -> Result<()>,
    ) -> Result<Vec<Vec<f64>>> {
        let started = Instant::now();
        let mut warmed = 0;
        while warmed < warmup.frames || started.elapsed() < warmup.least {
            render(&mut self.app).context("rendering a warm-up frame")?;
            warmed += 1;
        }
        let mut times = vec![Vec::with_capacity(frames); passes.len()];
        for frame in 0..frames {
            render(&mut self.app).context("rendering a timed frame")?;
            for (pass, times) in passes.iter().zip(&mut times) {
                let ms = self
                    .app
                    .resources
                    .get::<GpuTimings>()
                    .and_then(|timings| timings.pass_ms(pass));
                match ms {
                    Some(ms) => times.push(ms),
                    None => {
                        bail!("timed frame {frame}: the GPU gave no valid timestamps for {pass}")
                    }
                }
            }
        }
        self.check_errors().context("while timing")?;
        Ok(times)
    }
}
