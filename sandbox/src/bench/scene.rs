//! One benchmark scene: the plugin's preview plane with a parallax material, rendered offscreen
//! with blocking GPU timing. The plugin does all the rendering; this only drives it.

use std::collections::HashSet;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::{Duration, Instant};

use anyhow::{Context, Result, bail};
use image::{Rgba32FImage, RgbaImage};
use pom::gpu::{DERIVED_TEXTURES_PASS, resolve_gpu_timings};
use pom::preview::{PreviewView, spawn_preview, spawn_preview_mesh};
use pom::render::{RenderTarget, Renderer};
use pom::texel_rate_probe::{PROBE_PASS, TexelRateProbe};
use pom::{
    App, Assets, Camera, GpuContext, GpuTimings, Handle, HeightSource, Image, Mesh,
    ParallaxOcclusionMaterial, PomPlugin, RenderPath, RenderPhase, RenderPlugin, TargetFormat,
    TimingMode,
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
/// [`TIMED_PASS`] on a frame that ran deferred: the prepass is the visibility pass, and the
/// material shades in the resolve.
pub const TIMED_PASS_DEFERRED: &str = "prepass+opaque+resolve";
/// The phases [`TIMED_PASS`] adds up (and the resolve, on the deferred path).
const MATERIAL_PHASES: [&str; 2] = ["prepass", "opaque"];

/// Per phase (or pass) timed, its milliseconds in each timed frame.
pub type PhaseTimes = Vec<(&'static str, Vec<f64>)>;

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
    /// Forward, deferred or auto (`--path`).
    pub path: RenderPath,
    /// Whether the seed port's material is registered, for [`BenchScene::use_seed_port`]. It
    /// has no deferred shader, and a registered material without one sends every frame forward.
    pub seed_port: bool,
    /// Whether pipelines compile on worker threads (as in a window), else in the frame that
    /// first needs them.
    pub background_pipelines: bool,
}

impl SceneOptions {
    /// The flat plane into an sRGB target of `size`, timed, rendered on `path`.
    pub fn timed_plane(size: (u32, u32), path: RenderPath) -> Self {
        Self {
            size,
            timestamps: true,
            format: TargetFormat::Srgb8,
            surface: None,
            depth_prepass: true,
            path,
            seed_port: false,
            background_pipelines: false,
        }
    }
}

/// A headless app showing one material on the preview plane (or a mesh in its place).
pub struct BenchScene {
    app: App,
    /// Whether the seed port's material is registered ([`SceneOptions::seed_port`]).
    seed_port: bool,
    /// Whether the frames of the last timing ran deferred, as the renderer said after their
    /// warm-up; `None` before any timing.
    timed_deferred: Option<bool>,
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
        let seed_port = options.seed_port;
        let mut app = App::new();
        if options.background_pipelines {
            app.insert_resource(pom::gpu::PipelineCompilation::background());
        }
        let timing = options.timestamps.then_some(TimingMode::Blocking);
        app.add_plugin(
            RenderPlugin::new(width, height)
                .with_format(options.format)
                .with_gpu_timing(timing)
                .with_depth_prepass(options.depth_prepass)
                .with_path(options.path),
        );
        app.add_plugin(PomPlugin);
        if options.seed_port {
            app.add_plugin(pom::seed_port::SeedPortPlugin);
        }
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
        Ok(Self {
            app,
            seed_port,
            timed_deferred: None,
        })
    }

    /// A scene around an app already set up (with blocking GPU timing).
    pub fn from_app(app: App) -> Self {
        Self {
            app,
            seed_port: false,
            timed_deferred: None,
        }
    }

    /// A resource of the scene's app.
    pub fn resource<T: 'static>(&self) -> Option<&T> {
        self.app.resources.get::<T>()
    }

    /// Puts `anti_aliasing` (TAA with its default parameters) on the camera.
    pub fn set_anti_aliasing(
        &mut self,
        anti_aliasing: pom::AntiAliasing,
        temporal: pom::TemporalAntiAliasing,
    ) {
        pom::set_camera_anti_aliasing(&mut self.app.world, anti_aliasing, temporal);
    }

    /// Sets the colour the image is cleared to (alpha 0 marks pixels nothing was drawn on).
    pub fn set_clear_color(&mut self, color: pom::Color) {
        for camera in self.app.world.query_mut::<&mut Camera>() {
            camera.clear_color = color;
        }
    }

    /// The bytes the GPU holds for what the scene draws with the parallax material: each mesh's
    /// vertex and index buffers (interleaved [`pom::gpu::Vertex`], `u32` indices, as uploaded)
    /// and each texture the material binds, every mip level, as the renderer uploaded it.
    pub fn drawn_gpu_bytes(&self) -> u64 {
        let (Some(renderer), Some(meshes)) = (
            self.app.resources.get::<Renderer>(),
            self.app.resources.get::<Assets<Mesh>>(),
        ) else {
            return 0;
        };
        let (mut seen_meshes, mut seen_images) = (HashSet::new(), HashSet::new());
        let mut bytes = 0;
        let mut query = self
            .app
            .world
            .query::<(&Handle<Mesh>, &ParallaxOcclusionMaterial)>();
        for (mesh, material) in query.iter() {
            if seen_meshes.insert(mesh.id())
                && let Some(mesh) = meshes.get(mesh)
            {
                let vertex = std::mem::size_of::<pom::gpu::Vertex>();
                bytes += (mesh.positions.len() * vertex + mesh.indices.len() * 4) as u64;
            }
            for image in pom::Material::textures(material).into_iter().flatten() {
                if seen_images.insert(image)
                    && let Some(texture) = renderer.gpu_texture(image)
                {
                    bytes += texture_bytes(texture);
                }
            }
        }
        bytes
    }

    /// Renders one frame and reads it back as sRGB pixels.
    pub fn capture(&mut self) -> Result<RgbaImage> {
        self.app.update().context("rendering a frame")?;
        self.check_errors()?;
        Ok(pom::capture(&self.app)?)
    }

    /// Renders one frame into a [`TargetFormat::Float32`] scene and reads back the raw floats.
    pub fn capture_f32(&mut self) -> Result<Rgba32FImage> {
        self.app.update().context("rendering a frame")?;
        self.check_errors()?;
        Ok(pom::capture_f32(&self.app)?)
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

    /// Despawns the scene's parallax surface and returns its mesh, material and transform.
    fn take_parallax_surface(
        &mut self,
    ) -> Result<(pom::Handle<Mesh>, ParallaxOcclusionMaterial, pom::Transform)> {
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
            .context("the scene has no parallax surface")?;
        self.app.world.despawn(entity)?;
        Ok((mesh, material, transform))
    }

    /// Replaces the plane with `count` copies stacked along its normal `spacing` apart, spawned
    /// deepest first. With `own_meshes` each copy gets its own mesh, made deepest first: separate
    /// batches in mesh order, drawn back to front (the worst order); else they share one, and
    /// the renderer draws the instances nearest first.
    pub fn stack_planes(&mut self, count: usize, spacing: f32, own_meshes: bool) -> Result<()> {
        let (mesh, material, transform) = self.take_parallax_surface()?;
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

    /// Replaces the surface with `tiles` × `tiles` copies of it `spacing` apart, side by side in
    /// the preview plane from its −u, −v corner as its UVs run: a mesh made for one texture
    /// repeat (UVs 0..1, side `spacing`) lies where each repeat lies (the textures wrap). With a
    /// fractional number of repeats the last copies reach past the plane's edge.
    pub fn tile_surface(&mut self, tiles: u32, spacing: f32) -> Result<()> {
        let (mesh, material, transform) = self.take_parallax_surface()?;
        let first = 0.5 * (spacing - pom::preview::PLANE_SIZE);
        for row in 0..tiles.max(1) {
            for column in 0..tiles.max(1) {
                let mut tile = transform;
                tile.translation += transform.rotation
                    * glam::Vec3::new(
                        first + spacing * column as f32,
                        0.0,
                        first + spacing * row as f32,
                    );
                self.app.world.spawn((mesh.clone(), material.clone(), tile));
            }
        }
        Ok(())
    }

    /// Draws the plane with the seed's shader ([`pom::seed_port::SeedPortMaterial`], with the
    /// parallax material's textures and shared settings) instead of ours; the scene must have
    /// been made with [`SceneOptions::seed_port`].
    pub fn use_seed_port(&mut self) -> Result<()> {
        anyhow::ensure!(
            self.seed_port,
            "the scene was made without the seed port's material"
        );
        let images = self.app.resources.require_mut::<Assets<Image>>()?;
        let replaced = pom::seed_port::replace_parallax_materials(&mut self.app.world, images)?;
        anyhow::ensure!(replaced > 0, "the scene has no parallax plane");
        Ok(())
    }

    /// Inserts (or replaces) a resource of the scene's app.
    pub fn insert_resource<T: 'static>(&mut self, value: T) {
        self.app.insert_resource(value);
    }

    /// Times the frame nodes named `nodes` (their names in the GPU timings), with `before`
    /// changing the app before each frame, warm-up frames included.
    pub fn time_nodes(
        &mut self,
        warmup: Warmup,
        frames: usize,
        nodes: &[&'static str],
        mut before: impl FnMut(&mut App),
    ) -> Result<PhaseTimes> {
        let nodes = nodes.to_vec();
        self.time_frames(
            warmup,
            frames,
            |_| nodes,
            |app| {
                before(app);
                Ok(app.update()?)
            },
        )
    }

    /// The scene's images, to add the textures a material needs.
    pub fn images(&mut self) -> Result<&mut Assets<Image>> {
        Ok(self.app.resources.require_mut::<Assets<Image>>()?)
    }

    /// Changes the material's parameters, keeping its textures.
    pub fn configure(&mut self, change: impl Fn(&mut ParallaxOcclusionMaterial)) {
        for material in self.app.world.query_mut::<&mut ParallaxOcclusionMaterial>() {
            change(material);
        }
    }

    /// Renders `warmup.frames` untimed frames (and more until `warmup.least` has passed), then
    /// `frames` timed ones; returns what was timed ([`TIMED_PASS`], or [`TIMED_PASS_DEFERRED`]
    /// where the frames ran deferred) and the material phases' milliseconds per timed frame.
    pub fn time(&mut self, warmup: Warmup, frames: usize) -> Result<(&'static str, Vec<f64>)> {
        let (pass, times, _) = self.time_material_phases(warmup, frames)?;
        Ok((pass, times))
    }

    /// Like [`BenchScene::time`], with each material phase's own milliseconds per timed frame
    /// besides their sum (on the deferred path, the resolve among them).
    pub fn time_material_phases(
        &mut self,
        warmup: Warmup,
        frames: usize,
    ) -> Result<(&'static str, Vec<f64>, PhaseTimes)> {
        let phases = self.time_phases(warmup, frames, &MATERIAL_PHASES)?;
        let pass = if self.timed_deferred == Some(true) {
            TIMED_PASS_DEFERRED
        } else {
            TIMED_PASS
        };
        let times = (0..frames)
            .map(|frame| phases.iter().map(|(_, times)| times[frame]).sum())
            .collect();
        Ok((pass, times, phases))
    }

    /// Like [`BenchScene::time`], each phase of `phases` with its milliseconds per timed frame;
    /// where the frames run deferred, the resolve is added after the opaque phase, and the
    /// opaque phase is left out when the renderer ran no opaque pass (only the resolve shades:
    /// the background is then written from compute). Every other phase must be timed.
    pub fn time_phases(
        &mut self,
        warmup: Warmup,
        frames: usize,
        phases: &[&'static str],
    ) -> Result<PhaseTimes> {
        self.time_frames(
            warmup,
            frames,
            |scene| {
                let opaque_pass = scene
                    .app
                    .resources
                    .get::<Renderer>()
                    .is_none_or(Renderer::ran_opaque_pass);
                on_path(phases, scene.runs_deferred())
                    .into_iter()
                    .filter(|phase| *phase != RenderPhase::Opaque.name() || opaque_pass)
                    .collect()
            },
            |app| Ok(app.update()?),
        )
    }

    /// Like [`BenchScene::time`], with every parallax material's height image marked changed
    /// before each frame, as a dynamic height field's are: re-uploaded, and what is derived
    /// from it rebuilt. Returns the milliseconds of that rebuild ([`DERIVED_TEXTURES_PASS`])
    /// per timed frame.
    pub fn time_rewritten_heights(&mut self, warmup: Warmup, frames: usize) -> Result<Vec<f64>> {
        let heights: Vec<Handle<Image>> = self
            .app
            .world
            .query::<&ParallaxOcclusionMaterial>()
            .iter()
            .filter_map(|material| match &material.height_map {
                Some(HeightSource::Texture(height)) => Some(height.clone()),
                _ => None,
            })
            .collect();
        if heights.is_empty() {
            bail!("no parallax material with a height texture to rewrite");
        }
        let mut times = self.time_frames(
            warmup,
            frames,
            |_| vec![DERIVED_TEXTURES_PASS],
            |app| {
                let images = app.resources.require_mut::<Assets<Image>>()?;
                for height in &heights {
                    // Borrowing it mutably is what marks it changed.
                    images.get_mut(height);
                }
                Ok(app.update()?)
            },
        )?;
        Ok(times.pop().map(|(_, times)| times).unwrap_or_default())
    }

    /// Renders one frame and waits until the GPU has finished it; returns its wall-clock
    /// milliseconds, pipeline compiles and uploads included (what a frame that stalls costs).
    pub fn wall_frame_ms(&mut self) -> Result<f64> {
        let started = Instant::now();
        self.app.update().context("rendering a frame")?;
        if let Some(gpu) = self.app.resources.get::<pom::GpuContext>() {
            gpu.device
                .poll(pom::wgpu::PollType::wait_indefinitely())
                .context("waiting for the GPU")?;
        }
        let ms = started.elapsed().as_secs_f64() * 1000.0;
        self.timed_deferred = Some(self.runs_deferred());
        self.check_errors().context("while timing")?;
        Ok(ms)
    }

    /// How many pipeline compiles run on worker threads now.
    pub fn compiles_in_flight(&self) -> usize {
        self.app
            .resources
            .get::<pom::gpu::PipelineCompilation>()
            .map_or(0, pom::gpu::PipelineCompilation::in_flight)
    }

    /// Whether the last frame ran the deferred path (the renderer decides per frame: a material
    /// without a deferred shader, such as the seed port, sends a deferred frame forward).
    fn runs_deferred(&self) -> bool {
        last_frame_deferred(&self.app)
    }

    /// The path the frames of the last timing ran, `forward` or `deferred` (as the renderer
    /// said after their warm-up, whatever `--path` asked for); before any timing, the path of
    /// the last frame.
    pub fn path_ran(&self) -> &'static str {
        path_name(self.timed_deferred.unwrap_or_else(|| self.runs_deferred()))
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
        let mut times = self.time_frames(
            warmup,
            frames,
            |_| vec![PROBE_PASS],
            |app| {
                probe.render(&mut app.resources)?;
                resolve_gpu_timings(&mut app.world, &mut app.resources)?;
                Ok(())
            },
        )?;
        Ok(times.pop().map(|(_, times)| times).unwrap_or_default())
    }

    /// Times the seed port as one compute pass over the target
    /// ([`pom::seed_port::SeedPortCompute`]: the plane, textures, settings, camera and light the
    /// raster pass draws with), like [`BenchScene::time`]; the scene must be showing the seed
    /// port ([`BenchScene::use_seed_port`]). Renders one frame first, for the pass to read.
    pub fn time_seed_port_compute(
        &mut self,
        surface: pom::seed_port::SeedPortSurface,
        warmup: Warmup,
        frames: usize,
    ) -> Result<Vec<f64>> {
        self.app
            .update()
            .context("rendering the frame the compute pass reads")?;
        let pass =
            pom::seed_port::SeedPortCompute::on(&self.app.world, &self.app.resources, surface)?;
        let mut times = self.time_frames(
            warmup,
            frames,
            |_| vec![pom::seed_port::SEED_PORT_COMPUTE_PASS],
            |app| {
                pass.render(&mut app.resources)?;
                resolve_gpu_timings(&mut app.world, &mut app.resources)?;
                Ok(())
            },
        )?;
        Ok(times.pop().map(|(_, times)| times).unwrap_or_default())
    }

    /// The frame number of the newest GPU timing reading.
    fn reading_frame(&self) -> Option<u64> {
        self.app
            .resources
            .get::<GpuTimings>()
            .and_then(GpuTimings::reading_frame)
    }

    /// Per pass of `passes` (chosen after the warm-up, which renders at least one frame), its
    /// milliseconds in each timed frame.
    fn time_frames(
        &mut self,
        warmup: Warmup,
        frames: usize,
        passes: impl FnOnce(&Self) -> Vec<&'static str>,
        mut render: impl FnMut(&mut App) -> Result<()>,
    ) -> Result<Vec<(&'static str, Vec<f64>)>> {
        let started = Instant::now();
        let mut warmed = 0;
        while warmed < warmup.frames.max(1) || started.elapsed() < warmup.least {
            render(&mut self.app).context("rendering a warm-up frame")?;
            warmed += 1;
        }
        self.timed_deferred = Some(self.runs_deferred());
        let mut times: Vec<(&'static str, Vec<f64>)> = passes(self)
            .into_iter()
            .map(|pass| (pass, Vec::with_capacity(frames)))
            .collect();
        // A frame counts when it gave a reading of its own (not the last frame's again) with
        // every phase in it; any other is dropped and counted. A phase that never comes fails
        // the case rather than vanishing from its sum.
        let (mut timed, mut dropped) = (0, 0);
        let mut last_reading = self.reading_frame();
        while timed < frames {
            if dropped > frames + 8 {
                let passes: Vec<_> = times.iter().map(|(pass, _)| *pass).collect();
                bail!(
                    "{dropped} timed frames had no fresh, valid timestamp for every one of \
                     {passes:?} ({timed} of {frames} did)"
                );
            }
            render(&mut self.app).context("rendering a timed frame")?;
            let reading = self.reading_frame();
            let fresh = reading.is_some() && reading != last_reading;
            last_reading = reading;
            let timings = self.app.resources.get::<GpuTimings>();
            let all: Option<Vec<f64>> = times
                .iter()
                .map(|(pass, _)| timings.and_then(|timings| timings.pass_ms(pass)))
                .collect();
            match all.filter(|_| fresh) {
                Some(frame) => {
                    for ((_, times), ms) in times.iter_mut().zip(frame) {
                        times.push(ms);
                    }
                    timed += 1;
                }
                None => dropped += 1,
            }
        }
        DROPPED_FRAMES.fetch_add(dropped, Ordering::Relaxed);
        self.check_errors().context("while timing")?;
        Ok(times)
    }
}

/// Timed frames dropped so far in this process because their timestamps were rejected or
/// missing (never counted with the last frame's values instead).
static DROPPED_FRAMES: AtomicUsize = AtomicUsize::new(0);

/// The timed frames dropped so far for missing or rejected timestamps, for the report.
pub fn dropped_frames() -> usize {
    DROPPED_FRAMES.load(Ordering::Relaxed)
}

/// Whether `app`'s last frame ran the deferred path.
pub fn last_frame_deferred(app: &App) -> bool {
    app.resources
        .get::<Renderer>()
        .is_some_and(Renderer::runs_deferred)
}

/// The name of the path a frame ran: [`RenderPath::Deferred`]'s or [`RenderPath::Forward`]'s.
pub fn path_name(deferred: bool) -> &'static str {
    if deferred {
        RenderPath::Deferred.name()
    } else {
        RenderPath::Forward.name()
    }
}

/// `phases` as a frame on its path runs them: on the deferred path the resolve follows the
/// opaque phase (at the end, if `phases` has no opaque phase).
fn on_path(phases: &[&'static str], deferred: bool) -> Vec<&'static str> {
    let mut on_path = phases.to_vec();
    if deferred {
        let after_opaque = phases
            .iter()
            .position(|phase| *phase == RenderPhase::Opaque.name())
            .map_or(phases.len(), |index| index + 1);
        on_path.insert(after_opaque, RenderPhase::Resolve.name());
    }
    on_path
}

/// The bytes of `texture`, every mip level (uncompressed formats).
fn texture_bytes(texture: &wgpu::Texture) -> u64 {
    let texel = u64::from(texture.format().block_copy_size(None).unwrap_or(4));
    let size = texture.size();
    (0..texture.mip_level_count())
        .map(|level| {
            let mip = size.mip_level_size(level, texture.dimension());
            u64::from(mip.width)
                * u64::from(mip.height)
                * u64::from(mip.depth_or_array_layers)
                * texel
        })
        .sum()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_deferred_frame_times_the_resolve_after_the_opaque_phase() {
        let phases = ["prepass", "shadows", "opaque", "post"];
        assert_eq!(on_path(&phases, false), phases);
        assert_eq!(
            on_path(&phases, true),
            ["prepass", "shadows", "opaque", "resolve", "post"]
        );
        assert_eq!(
            on_path(&MATERIAL_PHASES, true),
            ["prepass", "opaque", "resolve"]
        );
        assert_eq!(
            TIMED_PASS_DEFERRED,
            on_path(&MATERIAL_PHASES, true).join("+")
        );
        assert_eq!(TIMED_PASS, MATERIAL_PHASES.join("+"));
    }
}
