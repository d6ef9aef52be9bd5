//! [`RenderPlugin`]: the renderer's settings, the stores and systems it adds, and the GPU
//! state it makes when the app finishes its plugins.

use super::standard_features::{RenderFeature, RenderFeatures};
use super::{
    DrawPhase, EnvironmentMaps, FrameNodes, FrameUniformBuffer, FullScreenStage, LightBuffers,
    RenderPath, RenderPhases, RenderTarget, Renderer, SettledDepth, ShadowMaps, SortedDraws,
    TargetFormat, VISIBILITY_BYTES_PER_PIXEL, VisibilityIds, VisiblePolygons, extract_frame,
    prepare_frame, render_frame, target,
};
use crate::gpu::{
    GpuAssets, GpuContext, TimingMode, UploadStats, resolve_gpu_timings, set_gpu_timing,
};
use crate::{
    AmbientLight, App, Assets, BoxedError, Image, Mesh, Plugin, Stage, TransformPlugin,
    free_unused_assets,
};

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
    /// GPU pass timing ([`GpuTimings`](crate::GpuTimings)), when the adapter supports it; `None` turns it off.
    pub gpu_timing: Option<TimingMode>,
    /// Whether opaque geometry is drawn into a depth prepass first, so the opaque phase
    /// shades each pixel once (on by default; off draws and shades in one pass).
    pub depth_prepass: bool,
    /// Whether deferred frames find the visibility of large few-triangle draws in compute
    /// (the polygon pass, on by default; off rasterizes every draw in the visibility pass).
    pub polygon_pass: bool,
    /// Where post-processing runs.
    pub post_process: PostProcessPath,
    /// Where opaque surfaces are shaded: forward, deferred, or the faster on the adapter.
    pub path: RenderPath,
    /// The standard features added with the core (all by default).
    pub features: RenderFeatures,
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
    /// A plugin rendering into a `width`×`height` sRGB target: offscreen, or fitted to the
    /// window where a window runner drives the app.
    pub fn new(width: u32, height: u32) -> Self {
        Self {
            width,
            height,
            format: TargetFormat::Srgb8,
            gpu_timing: Some(TimingMode::NonBlocking),
            depth_prepass: true,
            polygon_pass: true,
            post_process: PostProcessPath::Fastest,
            path: RenderPath::Auto,
            features: RenderFeatures::default(),
        }
    }

    /// The same plugin without the standard `feature` (its plugin is not added).
    pub fn without(self, feature: RenderFeature) -> Self {
        Self {
            features: self.features.without(feature),
            ..self
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

    /// The same plugin with the polygon pass on or off.
    pub fn with_polygon_pass(self, polygon_pass: bool) -> Self {
        Self {
            polygon_pass,
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
        Self::new(1280, 720)
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
        app.resources.get_or_default::<FrameNodes>();
        app.add_system(Stage::PostUpdate, free_unused_assets::<Mesh>)
            .add_system(Stage::PostUpdate, free_unused_assets::<Image>)
            .add_system(Stage::Extract, extract_frame)
            .add_system(Stage::Prepare, prepare_frame)
            .add_system(Stage::Render, render_frame)
            .add_system(Stage::Render, resolve_gpu_timings);
        self.features.add_to(app);
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
            environment: EnvironmentMaps::new(gpu),
            lights: LightBuffers::new(gpu),
            path: self.path,
            deferred: false,
            ran_opaque_pass: false,
            settled_depth: SettledDepth::default(),
            deferred_unavailable: None,
            visibility: None,
            background: None,
            visibility_ids: VisibilityIds::default(),
            prepass_order: SortedDraws::new(DrawPhase::Prepass),
            polygons: VisiblePolygons::new(false),
            candidate_polygons: VisiblePolygons::new(true),
            polygon_pass: self.polygon_pass,
            ran_polygon_pass: false,
            ran_depth_prepass: false,
            resolves_write_background: false,
            ran_background_pass: false,
            candidate_order: SortedDraws::new(DrawPhase::Candidates),
            transparent: SortedDraws::new(DrawPhase::Transparent),
            first_frame: true,
            full_screen_stage: full_screen_stage(gpu, self.format, self.post_process),
            post_images: Default::default(),
            last_upload: UploadStats::default(),
        };
        app.insert_resource(target).insert_resource(renderer);
        set_gpu_timing(&mut app.resources, self.gpu_timing);
        Ok(())
    }
}

/// Where full-screen passes run for display targets of `format`: compute where the adapter
/// can write that format from compute, unless `path` asks for the full-screen triangle.
fn full_screen_stage(
    gpu: &GpuContext,
    format: TargetFormat,
    path: PostProcessPath,
) -> FullScreenStage {
    match path {
        PostProcessPath::Fastest if gpu.can_store(format.texture_format()) => {
            FullScreenStage::Compute
        }
        _ => FullScreenStage::Fragment,
    }
}
