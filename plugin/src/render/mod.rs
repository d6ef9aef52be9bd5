//! The renderer: GPU context, offscreen target, extract / prepare / render systems, capture.
//! A frame runs the [`RenderPhase`]s in their documented order (see `phases.rs`).

mod capture;
mod context;
mod deferred_background;
mod derived_textures;
mod draw_view;
mod extract;
mod fragment_counter;
mod frame_uniform;
mod gpu_assets;
mod gpu_timing;
pub(crate) mod gpu_types;
pub(crate) mod layout;
mod lowest_mip;
mod max_pyramid;
pub(crate) mod object_buffer;
mod phases;
mod post_process;
mod present;
mod render_path;
pub mod shaders;
mod shadow_maps;
mod shadow_views;
mod target;
#[cfg(feature = "dev-tools")]
mod texel_rate_probe;
pub(crate) mod texture_bind_groups;
mod transparent;
mod visibility;

pub use capture::{
    CaptureError, capture, capture_f32, capture_scene, read_rgba8, read_texture, read_texture_level,
};
pub use context::{GpuContext, GpuError};
pub use deferred_background::DEFERRED_BACKGROUND;
use deferred_background::DeferredBackground;
pub use derived_textures::{
    DERIVED_TEXTURES_PASS, DerivedTexture, DerivedTextures, MAX_DERIVED_TEXTURES, TextureDerivation,
};
pub use draw_view::DrawView;
pub(crate) use extract::{ExtractedFrame, extract_frame};
pub use fragment_counter::FragmentInvocationCounter;
pub(crate) use frame_uniform::FrameUniformBuffer;
pub(crate) use gpu_assets::GpuAssets;
pub use gpu_assets::{DefaultTexture, UploadStats};
pub use gpu_timing::{GpuTimer, GpuTimings, TimingMode, resolve_gpu_timings, set_gpu_timing};
pub use gpu_timing::{PassTimestamps, time_pass};
pub(crate) use gpu_types::FrameUniform;
pub use gpu_types::MeshTransform;
pub(crate) use lowest_mip::{MeshLodCache, PixelFootprint};
pub use max_pyramid::MAX_PYRAMID_SHADER;
#[cfg(feature = "scene-tests")]
pub use max_pyramid::read_max_pyramid;
pub use phases::{
    DrawPhase, HasDraws, PhaseDraw, PhaseWork, RenderPhase, RenderPhases, ResolveDispatch,
    ShadowDraw, TransparentDraw,
};
pub(crate) use post_process::POST_SHADERS;
pub use post_process::{PostProcess, PostSettings};
pub use present::{PRESENT_SHADER, PresentError, Presenter, ScreenRect};
pub(crate) use render_path::DEFERRED_FEATURES;
pub use render_path::{DeferredUnavailable, RenderPath, UnknownRenderPath};
pub(crate) use shadow_maps::{SHADOW_MAP_FORMAT, ShadowMaps};
pub use shadow_views::MAX_SHADOW_VIEWS;
pub use target::{RenderTarget, TargetFormat, clearing_attachment, fit_render_target};
#[cfg(feature = "dev-tools")]
pub use texel_rate_probe::{PROBE_PASS, TEXEL_RATE_PROBE, TexelRateProbe};
pub(crate) use transparent::TransparentPhase;
pub use visibility::VISIBILITY_BYTES_PER_PIXEL;
pub(crate) use visibility::{VisibilityBuffer, VisibilityIds};

use crate::{
    AmbientLight, App, AppError, Assets, BoxedError, Image, Mesh, Plugin, Resources, Stage,
    TransformPlugin, free_unused_assets,
};

/// Everything that can go wrong when rendering or capturing a frame.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum RenderError {
    /// GPU setup failed.
    #[error(transparent)]
    Gpu(#[from] GpuError),
    /// Reading the image back failed.
    #[error(transparent)]
    Capture(#[from] CaptureError),
    /// The render plugin's resources are missing.
    #[error("nothing has been rendered yet: add RenderPlugin and call App::update first")]
    NotRendered,
}

/// Renders every mesh entity into an offscreen target of a fixed size.
///
/// Adds [`TransformPlugin`] if missing, the `Assets<Mesh>` and `Assets<Image>` stores, an
/// [`AmbientLight`], and the Extract, Prepare and Render systems. The GPU context is created in
/// [`Plugin::finish`] unless a [`GpuContext`] resource was inserted before (to share a device
/// with a window, say).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RenderPlugin {
    /// Target width in pixels.
    pub width: u32,
    /// Target height in pixels.
    pub height: u32,
    /// What the target stores: display pixels or raw floats.
    pub format: TargetFormat,
    /// GPU pass timing ([`GpuTimings`]), when the adapter supports it; `None` turns it off.
    pub gpu_timing: Option<TimingMode>,
    /// Whether opaque geometry is drawn into a depth prepass first, so the opaque phase
    /// shades each pixel once (on by default; off draws and shades in one pass).
    pub depth_prepass: bool,
    /// Where post-processing runs.
    pub post_process: PostProcessPath,
    /// Where opaque surfaces are shaded: forward, deferred, or the faster on the adapter.
    pub path: RenderPath,
}

/// Where the post-processing phase runs.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[non_exhaustive]
pub enum PostProcessPath {
    /// Compute where the adapter can write the display format from compute, else a
    /// full-screen triangle.
    #[default]
    Fastest,
    /// Always the full-screen triangle (to compare the two, or to work around a driver).
    Fragment,
}

impl RenderPlugin {
    /// A plugin rendering into a `width`×`height` offscreen sRGB image.
    pub fn headless(width: u32, height: u32) -> Self {
        Self {
            width,
            height,
            format: TargetFormat::Srgb8,
            gpu_timing: Some(TimingMode::NonBlocking),
            depth_prepass: true,
            post_process: PostProcessPath::Fastest,
            path: RenderPath::Auto,
        }
    }

    /// The same plugin shading opaque surfaces on `path`.
    pub fn with_path(self, path: RenderPath) -> Self {
        Self { path, ..self }
    }

    /// The same plugin with the depth prepass on or off.
    pub fn with_depth_prepass(self, depth_prepass: bool) -> Self {
        Self {
            depth_prepass,
            ..self
        }
    }

    /// The same plugin with post-processing on `path`.
    pub fn with_post_process(self, post_process: PostProcessPath) -> Self {
        Self {
            post_process,
            ..self
        }
    }

    /// The same plugin rendering raw floats (for measurements) instead.
    pub fn with_format(self, format: TargetFormat) -> Self {
        Self { format, ..self }
    }

    /// The same plugin with GPU timing in `mode`, or off with `None`.
    pub fn with_gpu_timing(self, gpu_timing: Option<TimingMode>) -> Self {
        Self { gpu_timing, ..self }
    }
}

impl Default for RenderPlugin {
    fn default() -> Self {
        Self::headless(1280, 720)
    }
}

/// The renderer's GPU state: uploaded assets, the frame uniform, post-processing. A resource.
#[derive(Debug)]
pub struct Renderer {
    /// GPU copies of meshes and images.
    pub(crate) assets: GpuAssets,
    /// Camera and lights, shared by every material pipeline.
    pub(crate) frame: FrameUniformBuffer,
    /// Whether frames run the depth prepass.
    pub(crate) depth_prepass: bool,
    /// A 1 × 1 depth texture bound where the real one is being written.
    pub(crate) dummy_depth: wgpu::TextureView,
    /// A one-key visibility buffer bound where the real one is not written.
    pub(crate) dummy_visibility: wgpu::Buffer,
    /// Every light's shadow maps.
    pub(crate) shadow_maps: ShadowMaps,
    /// The path asked for.
    path: RenderPath,
    /// Whether this frame runs deferred (decided in the Prepare stage).
    pub(crate) deferred: bool,
    /// Why the last frame that asked for deferred ran forward, as logged.
    deferred_unavailable: Option<DeferredUnavailable>,
    /// The deferred path's visibility buffer, once a frame has needed it.
    pub(crate) visibility: Option<VisibilityBuffer>,
    /// The deferred path's background pass, once a frame has needed it.
    background: Option<DeferredBackground>,
    /// This frame's visibility ids, handed to the materials' batches as they prepare.
    pub(crate) visibility_ids: VisibilityIds,
    /// This frame's blended draws of every material, drawn farthest first.
    pub(crate) transparent: TransparentPhase,
    /// No frame has chosen its path yet (the first choice is always logged).
    first_frame: bool,
    /// Tonemapping (the lights carry the exposure).
    post: PostProcess,
    /// What the last Prepare stage uploaded (the core's frame data and every material's).
    pub last_upload: UploadStats,
}

impl Renderer {
    /// Whether frames run the depth prepass.
    pub fn depth_prepass(&self) -> bool {
        self.depth_prepass
    }

    /// Whether post-processing runs as a compute pass (else as a full-screen triangle).
    pub fn post_process_is_compute(&self) -> bool {
        self.post.is_compute()
    }

    /// The path asked for (see [`Renderer::runs_deferred`] for the one that runs).
    pub fn path(&self) -> RenderPath {
        self.path
    }

    /// Asks for `path` from the next frame on (the choice is logged).
    pub fn set_path(&mut self, path: RenderPath) {
        self.path = path;
    }

    /// Whether the last prepared frame ran the deferred path.
    pub fn runs_deferred(&self) -> bool {
        self.deferred
    }

    /// Why the last frame runs forward although its path asked for deferred, if it does.
    pub fn deferred_unavailable(&self) -> Option<DeferredUnavailable> {
        self.deferred_unavailable
    }

    /// Decides whether this frame runs deferred, logging when the decision changes, and makes
    /// the visibility buffer on the first deferred frame of a target.
    /// `blocker` is what of the app stops the deferred path (a material, a draw, a counter).
    fn choose_path(
        &mut self,
        gpu: &GpuContext,
        target: &RenderTarget,
        blocker: Option<DeferredUnavailable>,
    ) {
        let wants = match self.path {
            RenderPath::Forward => false,
            RenderPath::Deferred => true,
            RenderPath::Auto => render_path::auto_picks_deferred(gpu),
        };
        let unavailable = if wants {
            render_path::deferred_support(gpu, self.depth_prepass, target)
                .and_then(|()| blocker.map_or(Ok(()), Err))
                .err()
        } else {
            None
        };
        let deferred = wants && unavailable.is_none();
        if (deferred, unavailable) != (self.deferred, self.deferred_unavailable) || self.first_frame
        {
            match unavailable {
                Some(reason) => {
                    log::warn!("render path {}: runs forward, since {reason}", self.path)
                }
                None => log::info!(
                    "render path {}: runs {}",
                    self.path,
                    if deferred { "deferred" } else { "forward" }
                ),
            }
        }
        self.first_frame = false;
        self.deferred = deferred;
        self.deferred_unavailable = unavailable;
        if deferred {
            match &mut self.visibility {
                Some(visibility) => visibility.follow(gpu, target),
                None => self.visibility = Some(VisibilityBuffer::new(gpu, target)),
            }
        }
        if deferred && self.background.is_none() {
            self.background = Some(DeferredBackground::new(gpu, target.scene_format()));
        }
    }
}

/// What materials bind as the prepass depth, shadow maps and visibility keys for `target`: its
/// depth after a prepass, else the dummy; the target's visibility buffer once made, else a
/// stand-in (fields apart, so the renderer's assets stay borrowable).
pub(crate) fn depth_bindings<'a>(
    depth_prepass: bool,
    dummy: &'a wgpu::TextureView,
    shadow_maps: &'a ShadowMaps,
    (visibility, dummy_visibility): (Option<&'a VisibilityBuffer>, &'a wgpu::Buffer),
    target: &'a RenderTarget,
) -> crate::material::DepthBindings<'a> {
    let visibility = visibility.filter(|visibility| visibility.target == target.id());
    crate::material::DepthBindings {
        visibility: visibility.map_or(dummy_visibility, |visibility| &visibility.keys),
        dummy_visibility,
        opaque: if depth_prepass {
            &target.depth_view
        } else {
            dummy
        },
        dummy,
        shadow_maps: shadow_maps.array_view(),
        dummy_shadow_maps: shadow_maps.dummy_view(),
        shadow_views: shadow_maps.views_buffer(),
        shadow_sampler: shadow_maps.sampler(),
        bound: (target.id(), shadow_maps.generation(), visibility.is_some()),
    }
}

impl Renderer {
    /// The texture an image was uploaded to, for reading it back ([`read_rgba8`]); `None`
    /// until the Prepare stage has uploaded it.
    pub fn gpu_texture(&self, image: crate::AssetId<Image>) -> Option<&wgpu::Texture> {
        self.assets.image(image).map(|image| &image.texture)
    }

    /// Whether a mesh is uploaded and valid (an invalid mesh is logged once and not drawn).
    pub fn has_gpu_mesh(&self, mesh: crate::AssetId<Mesh>) -> bool {
        self.assets.mesh(mesh).is_some()
    }

    /// How many textures derived from images (maximum pyramids) the GPU holds: one per image
    /// and derivation some draw used in the last frame.
    pub fn derived_texture_count(&self) -> usize {
        self.assets.derived_count()
    }
}

impl Plugin for RenderPlugin {
    fn build(&self, app: &mut App) {
        if !app.has_plugin::<TransformPlugin>() {
            app.add_plugin(TransformPlugin);
        }
        app.resources.get_or_default::<Assets<Mesh>>();
        app.resources.get_or_default::<Assets<Image>>();
        app.resources.get_or_default::<AmbientLight>();
        app.resources.get_or_default::<RenderPhases>();
        app.resources.get_or_default::<MeshLodCache>();
        app.add_system(Stage::PostUpdate, free_unused_assets::<Mesh>)
            .add_system(Stage::PostUpdate, free_unused_assets::<Image>)
            .add_system(Stage::Extract, extract_frame)
            .add_system(Stage::Prepare, prepare_frame)
            .add_system(Stage::Render, render_frame)
            .add_system(Stage::Render, resolve_gpu_timings);
    }

    fn finish(&self, app: &mut App) -> Result<(), BoxedError> {
        if !app.resources.contains::<GpuContext>() {
            app.insert_resource(GpuContext::headless()?);
        }
        let gpu = app.resources.require::<GpuContext>()?;
        let target = RenderTarget::new(gpu, self.width, self.height, self.format);
        let frame = FrameUniformBuffer::new(gpu);
        let dummy_depth = gpu
            .device
            .create_texture(&wgpu::TextureDescriptor {
                label: Some("dummy depth"),
                size: wgpu::Extent3d::default(),
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format: target::DEPTH_FORMAT,
                usage: wgpu::TextureUsages::TEXTURE_BINDING,
                view_formats: &[],
            })
            .create_view(&wgpu::TextureViewDescriptor::default());
        let renderer = Renderer {
            assets: GpuAssets::new(gpu),
            frame,
            depth_prepass: self.depth_prepass,
            dummy_depth,
            dummy_visibility: gpu.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("visibility stand-in"),
                size: VISIBILITY_BYTES_PER_PIXEL,
                usage: wgpu::BufferUsages::STORAGE,
                mapped_at_creation: false,
            }),
            shadow_maps: ShadowMaps::new(gpu),
            path: self.path,
            deferred: false,
            deferred_unavailable: None,
            visibility: None,
            background: None,
            visibility_ids: VisibilityIds::default(),
            transparent: TransparentPhase::default(),
            first_frame: true,
            post: PostProcess::new(
                gpu,
                self.format,
                self.post_process == PostProcessPath::Fragment,
            ),
            last_upload: UploadStats::default(),
        };
        app.insert_resource(target).insert_resource(renderer);
        set_gpu_timing(&mut app.resources, self.gpu_timing);
        Ok(())
    }
}

/// The Prepare stage's system: frees GPU copies of dropped assets and uploads the frame uniform.
/// It runs before every material's Prepare system (materials need [`RenderPlugin`] first), and
/// starts this frame's [`Renderer::last_upload`] count.
pub fn prepare_frame(_: &mut hecs::World, resources: &mut Resources) -> Result<(), AppError> {
    resources
        .scope(|resources, renderer: &mut Renderer| {
            let gpu = resources.require::<GpuContext>()?;
            let extracted = resources.require::<ExtractedFrame>()?;
            let meshes = resources.require::<Assets<Mesh>>()?;
            let images = resources.require::<Assets<Image>>()?;
            let target = resources.require::<RenderTarget>()?;
            renderer.choose_path(gpu, target, render_path::deferred_blocker(resources));
            renderer.visibility_ids.reset();
            if let (true, Some(background), Some(visibility)) = (
                renderer.deferred,
                &mut renderer.background,
                &renderer.visibility,
            ) {
                background.prepare(gpu, target, visibility, clear_value(extracted.clear_color));
            }
            renderer.assets.release_freed(meshes, images);
            let settings = PostSettings::new(extracted.tonemapping, target.target_format());
            // Each shadow map sees the frame from its light: the same lights, the light's eye.
            let light_views: Vec<FrameUniform> = extracted
                .shadow_views
                .iter()
                .map(|plan| FrameUniform {
                    view_projection: plan.gpu.view_projection,
                    camera_position: plan.eye.extend(1.0).into(),
                    view_direction: plan
                        .forward
                        .extend(if plan.orthographic { 1.0 } else { 0.0 })
                        .into(),
                    ..extracted.frame
                })
                .collect();
            renderer.last_upload = UploadStats {
                uniform_bytes: renderer.frame.upload(gpu, &extracted.frame, &light_views)
                    + renderer.shadow_maps.prepare(gpu, &extracted.shadow_views)
                    + renderer.post.upload(gpu, settings),
                ..UploadStats::default()
            };
            Ok(())
        })
        .unwrap_or_else(|| Err(AppError::missing::<Renderer>()))
}

/// The Render stage's system: builds the textures derived this frame, then runs the phases in
/// order (prepass, shadows, opaque, transparent; then post-processing in a second submission;
/// the overlay belongs to the application), each timed under its name.
pub fn render_frame(_: &mut hecs::World, resources: &mut Resources) -> Result<(), AppError> {
    // Every material has prepared its blended draws: order them across materials.
    resources.require_mut::<Renderer>()?.transparent.sort();
    let has_camera = resources.require::<ExtractedFrame>()?.has_camera;
    let renderer = resources.require::<Renderer>()?;
    let (prepass, deferred) = (renderer.depth_prepass, renderer.deferred);
    let phases = resources.get::<RenderPhases>();
    let has =
        |phase: DrawPhase| has_camera && phases.is_some_and(|p| p.has_draws(phase, resources));
    let has_work =
        |phase: RenderPhase| has_camera && phases.is_some_and(|p| p.work(phase).next().is_some());
    let shadow_map_count = resources.require::<ExtractedFrame>()?.shadow_views.len();
    let run_shadow_maps =
        shadow_map_count > 0 && phases.is_some_and(|p| p.shadow_draws().next().is_some());
    let (run_prepass, run_shadows, run_transparent) = (
        prepass && has(DrawPhase::Prepass),
        run_shadow_maps || has_work(RenderPhase::Shadows),
        has(DrawPhase::Transparent) || (has_camera && !renderer.transparent.is_empty()),
    );
    let run_resolve =
        deferred && run_prepass && has_camera && phases.is_some_and(|p| p.has_resolves(resources));
    // A deferred frame whose opaque phase draws nothing writes the background from compute
    // instead of clearing the scene in an empty render pass (a full-screen fragment pass).
    let background_in_compute = run_resolve && !has(DrawPhase::Opaque);
    let builds_derived_textures = !resources
        .require::<Renderer>()?
        .assets
        .pending_derived_builds()
        .is_empty();
    // Reserve the timestamps first: the timer is borrowed mutably.
    let mut time = |run: bool, phase: RenderPhase| {
        if run {
            time_pass(resources, phase.name())
        } else {
            None
        }
    };
    let prepass_time = time(run_prepass, RenderPhase::Prepass);
    let shadows_time = time(run_shadow_maps, RenderPhase::Shadows);
    let opaque_time = time(!background_in_compute, RenderPhase::Opaque);
    let resolve_time = time(run_resolve, RenderPhase::Resolve);
    let transparent_time = time(run_transparent, RenderPhase::Transparent);
    let post_time = time(true, RenderPhase::PostProcess);
    // Reserved last: where a frame times more passes than the timer holds, the phases keep theirs.
    let derived_time = builds_derived_textures
        .then(|| time_pass(resources, DERIVED_TEXTURES_PASS))
        .flatten();

    let gpu = resources.require::<GpuContext>()?;
    let target = resources.require::<RenderTarget>()?;
    let extracted = resources.require::<ExtractedFrame>()?;
    let phases = resources.get::<RenderPhases>();
    let mut encoder = gpu
        .device
        .create_command_encoder(&wgpu::CommandEncoderDescriptor {
            label: Some("frame encoder"),
        });
    // Textures derived in the Prepare stage are built before every phase that may read them.
    resources
        .require::<Renderer>()?
        .assets
        .pending_derived_builds()
        .record(&mut encoder, derived_time.as_ref());
    let draw_phase = |phase: DrawPhase, pass: &mut wgpu::RenderPass<'_>| {
        if let (true, Some(phases)) = (has_camera, phases) {
            for draw in phases.draws(phase) {
                draw(resources, pass);
            }
        }
    };
    let depth_attachment = |ops: Option<wgpu::Operations<f32>>| {
        Some(wgpu::RenderPassDepthStencilAttachment {
            view: &target.depth_view,
            depth_ops: ops,
            stencil_ops: None,
        })
    };
    if run_prepass {
        // On the deferred path the prepass is the visibility pass: its fragments also merge
        // each pixel's draw and triangle into the visibility keys (0: none).
        if let (true, Some(visibility)) = (deferred, &resources.require::<Renderer>()?.visibility) {
            encoder.clear_buffer(&visibility.keys, 0, None);
        }
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some(if deferred { "visibility" } else { "prepass" }),
            color_attachments: &[],
            depth_stencil_attachment: depth_attachment(Some(wgpu::Operations {
                load: wgpu::LoadOp::Clear(1.0),
                store: wgpu::StoreOp::Store,
            })),
            timestamp_writes: prepass_time.as_ref().map(PassTimestamps::render),
            occlusion_query_set: None,
            multiview_mask: None,
        });
        draw_phase(DrawPhase::Prepass, &mut pass);
    }
    if run_shadow_maps && let Some(phases) = phases {
        let shadow_maps = &resources.require::<Renderer>()?.shadow_maps;
        let layer_size = shadow_maps.layer_size();
        for (index, plan) in extracted.shadow_views.iter().enumerate() {
            let Some(layer) = shadow_maps.layer_view(plan.gpu.layer) else {
                continue;
            };
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("shadow map"),
                color_attachments: &[],
                depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                    view: layer,
                    depth_ops: Some(wgpu::Operations {
                        load: wgpu::LoadOp::Clear(1.0),
                        store: wgpu::StoreOp::Store,
                    }),
                    stencil_ops: None,
                }),
                // The phase's span: the first map's pass begins it, the last one ends it.
                timestamp_writes: shadows_time
                    .as_ref()
                    .filter(|_| index == 0 || index + 1 == shadow_map_count)
                    .map(|time| time.render_part(index == 0, index + 1 == shadow_map_count)),
                occlusion_query_set: None,
                multiview_mask: None,
            });
            // A smaller map draws into a corner of its layer.
            let size = plan.map_size.min(layer_size) as f32;
            pass.set_viewport(0.0, 0.0, size, size, 0.0, 1.0);
            for draw in phases.shadow_draws() {
                draw(resources, &mut pass, 1 + index as u32);
            }
        }
    }
    if run_shadows && let Some(phases) = phases {
        for work in phases.work(RenderPhase::Shadows) {
            work(resources, &mut encoder);
        }
    }
    if !background_in_compute {
        let [r, g, b, a] = clear_value(extracted.clear_color).map(f64::from);
        // After a prepass the depth is read-only: materials test against it, and may sample it.
        let depth_ops = if run_prepass {
            None
        } else {
            Some(wgpu::Operations {
                load: wgpu::LoadOp::Clear(1.0),
                store: if run_transparent {
                    wgpu::StoreOp::Store
                } else {
                    wgpu::StoreOp::Discard
                },
            })
        };
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("opaque"),
            color_attachments: &[Some(clearing_attachment(
                &target.scene_view,
                wgpu::Color { r, g, b, a },
            ))],
            depth_stencil_attachment: depth_attachment(depth_ops),
            timestamp_writes: opaque_time.as_ref().map(PassTimestamps::render),
            occlusion_query_set: None,
            multiview_mask: None,
        });
        draw_phase(DrawPhase::Opaque, &mut pass);
    }
    if run_resolve && let Some(phases) = phases {
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("deferred resolve"),
            timestamp_writes: resolve_time.as_ref().map(PassTimestamps::compute),
        });
        if background_in_compute
            && let Some(background) = &resources.require::<Renderer>()?.background
        {
            background.record(&mut pass);
        }
        for dispatch in phases.resolves() {
            dispatch(resources, &mut pass);
        }
    }
    if run_transparent {
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("transparent"),
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view: &target.scene_view,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations {
                    load: wgpu::LoadOp::Load,
                    store: wgpu::StoreOp::Store,
                },
            })],
            depth_stencil_attachment: depth_attachment(None),
            timestamp_writes: transparent_time.as_ref().map(PassTimestamps::render),
            occlusion_query_set: None,
            multiview_mask: None,
        });
        if let Some(phases) = phases {
            let blended = &resources.require::<Renderer>()?.transparent;
            blended.record(phases, resources, &mut pass);
        }
        draw_phase(DrawPhase::Transparent, &mut pass);
    }
    // Post-processing borrows the renderer mutably (its bind group follows the target).
    gpu.queue.submit([encoder.finish()]);
    resources
        .scope(|resources, renderer: &mut Renderer| {
            renderer.assets.derived_builds_submitted();
            let gpu = resources.require::<GpuContext>()?;
            let target = resources.require::<RenderTarget>()?;
            let mut encoder = gpu
                .device
                .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                    label: Some("post-process encoder"),
                });
            renderer
                .post
                .record(gpu, target, &mut encoder, post_time.as_ref());
            if let Some(phases) = resources.get::<RenderPhases>() {
                for work in phases.work(RenderPhase::PostProcess) {
                    work(resources, &mut encoder);
                }
            }
            gpu.queue.submit([encoder.finish()]);
            Ok(())
        })
        .unwrap_or_else(|| Err(AppError::missing::<Renderer>()))
}

/// What the scene is cleared to: the clear colour as set, its negative alpha marking it
/// display-referred (post_process.wgsl), so neither exposure nor tonemapping changes the
/// background.
fn clear_value(clear: crate::Color) -> [f32; 4] {
    [clear.r, clear.g, clear.b, -1.0 - clear.a.clamp(0.0, 1.0)]
}
