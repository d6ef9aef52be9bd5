//! The renderer: GPU context, offscreen target, extract / prepare / render systems, capture.

mod capture;
mod context;
mod draw_view;
mod extract;
mod frame_uniform;
mod gpu_assets;
mod gpu_timing;
mod gpu_types;
pub(crate) mod layout;
mod lowest_mip;
pub(crate) mod object_buffer;
pub mod shaders;
mod target;
#[cfg(feature = "dev-tools")]
mod texel_rate_probe;
pub(crate) mod texture_bind_groups;

pub(crate) use capture::read_rgba32f;
pub use capture::{CaptureError, read_rgba8, read_texture};
pub use context::{GpuContext, GpuError};
pub use draw_view::DrawView;
pub(crate) use extract::{ExtractedFrame, extract_frame};
pub(crate) use frame_uniform::FrameUniformBuffer;
pub(crate) use gpu_assets::GpuAssets;
pub use gpu_assets::{DefaultTexture, UploadStats};
pub use gpu_timing::{GpuTimer, GpuTimings, TimingMode, resolve_gpu_timings, set_gpu_timing};
pub(crate) use gpu_timing::{PassTimestamps, time_pass};
#[cfg(test)]
pub(crate) use gpu_types::FrameUniform;
pub use gpu_types::MeshTransform;
pub(crate) use lowest_mip::{MeshLodCache, PixelFootprint};
pub use target::{RenderTarget, TargetFormat, clearing_attachment};
#[cfg(feature = "dev-tools")]
pub use texel_rate_probe::{PROBE_PASS, TEXEL_RATE_PROBE, TexelRateProbe};

use std::any::TypeId;

use image::{Rgba32FImage, RgbaImage};

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
}

impl RenderPlugin {
    /// A plugin rendering into a `width`×`height` offscreen sRGB image.
    pub fn headless(width: u32, height: u32) -> Self {
        Self {
            width,
            height,
            format: TargetFormat::Srgb8,
            gpu_timing: Some(TimingMode::NonBlocking),
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

/// The renderer's GPU state: uploaded assets and the frame uniform. A resource.
#[derive(Debug)]
pub struct Renderer {
    /// GPU copies of meshes and images.
    pub(crate) assets: GpuAssets,
    /// Camera and lights, shared by every main-pass pipeline.
    pub(crate) frame: FrameUniformBuffer,
    /// What the last Prepare stage uploaded (the core's frame data and every material's).
    pub last_upload: UploadStats,
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
}

impl Plugin for RenderPlugin {
    fn build(&self, app: &mut App) {
        if !app.has_plugin::<TransformPlugin>() {
            app.add_plugin(TransformPlugin);
        }
        app.resources.get_or_default::<Assets<Mesh>>();
        app.resources.get_or_default::<Assets<Image>>();
        app.resources.get_or_default::<AmbientLight>();
        app.resources.get_or_default::<MainPassDraws>();
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
        let renderer = Renderer {
            assets: GpuAssets::new(gpu),
            frame,
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
            renderer.assets.release_freed(meshes, images);
            renderer.last_upload = UploadStats {
                uniform_bytes: renderer.frame.upload(gpu, &extracted.frame),
                ..UploadStats::default()
            };
            Ok(())
        })
        .unwrap_or_else(|| Err(AppError::missing::<Renderer>()))
}

/// Records draws into the main pass, given the resources and the open pass.
pub type MainPassDraw = fn(&Resources, &mut wgpu::RenderPass<'_>);

/// The draws of the main pass, in the order their plugins were added; one per owner type, so a
/// plugin added twice draws once. A resource.
#[derive(Debug, Default)]
pub struct MainPassDraws(Vec<(TypeId, MainPassDraw)>);

impl MainPassDraws {
    /// Adds `draw` for `Owner` (a material type, say) unless `Owner` has one already.
    pub fn add<Owner: 'static>(&mut self, draw: MainPassDraw) {
        let owner = TypeId::of::<Owner>();
        if !self.0.iter().any(|(id, _)| *id == owner) {
            self.0.push((owner, draw));
        }
    }

    /// How many draws are registered.
    pub fn len(&self) -> usize {
        self.0.len()
    }

    /// Whether none is.
    pub fn is_empty(&self) -> bool {
        self.0.is_empty()
    }
}

/// The Render stage's system: clears the target, records every registered [`MainPassDraw`],
/// and submits.
pub fn render_frame(_: &mut hecs::World, resources: &mut Resources) -> Result<(), AppError> {
    let timestamps = time_pass(resources, "main pass");
    let gpu = resources.require::<GpuContext>()?;
    let target = resources.require::<RenderTarget>()?;
    let extracted = resources.require::<ExtractedFrame>()?;
    let mut encoder = gpu
        .device
        .create_command_encoder(&wgpu::CommandEncoderDescriptor {
            label: Some("frame encoder"),
        });
    {
        let clear = extracted.clear_color;
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("main pass"),
            color_attachments: &[Some(clearing_attachment(
                &target.color_view,
                wgpu::Color {
                    r: f64::from(clear.r),
                    g: f64::from(clear.g),
                    b: f64::from(clear.b),
                    a: f64::from(clear.a),
                },
            ))],
            depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                view: &target.depth_view,
                depth_ops: Some(wgpu::Operations {
                    load: wgpu::LoadOp::Clear(1.0),
                    store: wgpu::StoreOp::Discard,
                }),
                stencil_ops: None,
            }),
            timestamp_writes: timestamps.as_ref().map(PassTimestamps::render),
            occlusion_query_set: None,
            multiview_mask: None,
        });
        if extracted.has_camera
            && let Some(MainPassDraws(draws)) = resources.get::<MainPassDraws>()
        {
            for (_, draw) in draws {
                draw(resources, &mut pass);
            }
        }
    }
    gpu.queue.submit([encoder.finish()]);
    Ok(())
}

/// Reads the last rendered frame back as sRGB-encoded RGBA8 pixels.
///
/// # Example
/// ```no_run
/// # fn main() -> Result<(), Box<dyn std::error::Error>> {
/// let mut app = pom::App::new();
/// app.add_plugin(pom::RenderPlugin::headless(64, 64));
/// app.update()?;
/// let image = pom::capture(&app)?;
/// assert_eq!(image.dimensions(), (64, 64));
/// # Ok(()) }
/// ```
pub fn capture(app: &App) -> Result<RgbaImage, RenderError> {
    let (Some(gpu), Some(target)) = (
        app.resources.get::<GpuContext>(),
        app.resources.get::<RenderTarget>(),
    ) else {
        return Err(RenderError::NotRendered);
    };
    Ok(read_rgba8(gpu, &target.color)?)
}

/// Reads the last rendered frame of a [`TargetFormat::Float32`] target back as raw floats.
pub fn capture_f32(app: &App) -> Result<Rgba32FImage, RenderError> {
    let (Some(gpu), Some(target)) = (
        app.resources.get::<GpuContext>(),
        app.resources.get::<RenderTarget>(),
    ) else {
        return Err(RenderError::NotRendered);
    };
    Ok(read_rgba32f(gpu, &target.color)?)
}
