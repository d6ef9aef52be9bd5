//! The offscreen textures a frame is drawn into: the HDR scene colour and depth the material
//! phases draw into, and the display colour post-processing writes.

use std::sync::atomic::{AtomicU64, Ordering};

use crate::gpu::GpuContext;

/// What the colour target stores.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum TargetFormat {
    /// 8-bit sRGB-encoded display pixels (scene in `Rgba16Float`): what screenshots and
    /// reference images use.
    #[default]
    Srgb8,
    /// 32-bit float per channel, no sRGB curve (scene in `Rgba32Float` too): linear display
    /// values and exact debug-view data for measurements. Read it back with
    /// [`crate::capture_f32`], the (pre-exposed) scene before tonemapping with
    /// [`crate::capture_scene`].
    Float32,
}

impl TargetFormat {
    /// The display texture's format. 8-bit pixels are stored as plain `Unorm` holding
    /// sRGB-encoded bytes: compute shaders cannot write sRGB formats, so post-processing
    /// encodes them itself.
    pub fn texture_format(self) -> wgpu::TextureFormat {
        match self {
            TargetFormat::Srgb8 => wgpu::TextureFormat::Rgba8Unorm,
            TargetFormat::Float32 => wgpu::TextureFormat::Rgba32Float,
        }
    }

    /// The HDR scene texture's format: what materials draw into.
    pub fn scene_format(self) -> wgpu::TextureFormat {
        match self {
            TargetFormat::Srgb8 => wgpu::TextureFormat::Rgba16Float,
            TargetFormat::Float32 => wgpu::TextureFormat::Rgba32Float,
        }
    }
}

/// The depth buffer format.
pub const DEPTH_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;

/// Gives every target its own id, so passes can tell when a bind group is for another one.
static NEXT_TARGET_ID: AtomicU64 = AtomicU64::new(1);

/// An offscreen target of a fixed size: HDR scene colour, depth, and the display colour.
/// A resource of the render plugin.
#[derive(Debug)]
pub struct RenderTarget {
    /// The display texture post-processing writes (copy source, sampleable).
    pub color: wgpu::Texture,
    /// A view of [`RenderTarget::color`].
    pub color_view: wgpu::TextureView,
    /// The same view: the display texture holds gamma-encoded bytes as plain `Unorm`, what
    /// UIs that sample such textures (egui) expect.
    pub display_view: wgpu::TextureView,
    /// The HDR scene texture the material phases draw into.
    pub scene: wgpu::Texture,
    /// A view of [`RenderTarget::scene`].
    pub scene_view: wgpu::TextureView,
    /// The depth texture (the prepass writes it, the opaque phase reads it).
    pub depth: wgpu::Texture,
    /// A view of [`RenderTarget::depth`].
    pub depth_view: wgpu::TextureView,
    id: u64,
    /// The device its textures live on: a target made before a device was replaced is
    /// stale ([`RenderTarget::made_on`]).
    device: wgpu::Device,
}

/// A 2D texture of one level and one sample, `width`×`height`: what the target and the
/// textures that follow its size (TAA's history, the post chain's images, the motion numbers)
/// are made of.
pub(crate) fn plain_texture(
    gpu: &GpuContext,
    label: &str,
    (width, height): (u32, u32),
    format: wgpu::TextureFormat,
    usage: wgpu::TextureUsages,
) -> wgpu::Texture {
    gpu.device.create_texture(&wgpu::TextureDescriptor {
        label: Some(label),
        size: wgpu::Extent3d {
            width,
            height,
            depth_or_array_layers: 1,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format,
        usage,
        view_formats: &[],
    })
}

impl RenderTarget {
    /// Creates a target of `width`×`height`, each clamped to 1..=the device's 2D texture limit.
    pub fn new(gpu: &GpuContext, width: u32, height: u32, format: TargetFormat) -> Self {
        let limit = gpu.device.limits().max_texture_dimension_2d;
        let size = wgpu::Extent3d {
            width: width.clamp(1, limit),
            height: height.clamp(1, limit),
            depth_or_array_layers: 1,
        };
        if (size.width, size.height) != (width, height) {
            log::warn!(
                "render target {width}×{height} clamped to {}×{} (device limit {limit})",
                size.width,
                size.height
            );
        }
        let texture = |label, format, usage| {
            plain_texture(gpu, label, (size.width, size.height), format, usage)
        };
        let display = format.texture_format();
        // Post-processing writes it from compute where the adapter allows, else as an attachment.
        let storage = if gpu
            .adapter
            .get_texture_format_features(display)
            .allowed_usages
            .contains(wgpu::TextureUsages::STORAGE_BINDING)
        {
            wgpu::TextureUsages::STORAGE_BINDING
        } else {
            wgpu::TextureUsages::empty()
        };
        let color = texture(
            "render target display colour",
            display,
            wgpu::TextureUsages::RENDER_ATTACHMENT
                | wgpu::TextureUsages::COPY_SRC
                | wgpu::TextureUsages::TEXTURE_BINDING
                | storage,
        );
        // Storage: the deferred resolve writes the pixels it shades from compute.
        let scene = texture(
            "render target scene colour",
            format.scene_format(),
            wgpu::TextureUsages::RENDER_ATTACHMENT
                | wgpu::TextureUsages::COPY_SRC
                | wgpu::TextureUsages::TEXTURE_BINDING
                | wgpu::TextureUsages::STORAGE_BINDING,
        );
        let depth = texture(
            "render target depth",
            DEPTH_FORMAT,
            wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::TEXTURE_BINDING,
        );
        let view = |texture: &wgpu::Texture, label| {
            texture.create_view(&wgpu::TextureViewDescriptor {
                label: Some(label),
                ..Default::default()
            })
        };
        Self {
            color_view: view(&color, "render target display view"),
            display_view: view(&color, "render target display view (UI)"),
            scene_view: view(&scene, "render target scene view"),
            depth_view: view(&depth, "render target depth view"),
            color,
            scene,
            depth,
            id: NEXT_TARGET_ID.fetch_add(1, Ordering::Relaxed),
            device: gpu.device.clone(),
        }
    }

    /// An id no other target of this process has: passes keep bind groups per target id.
    pub fn id(&self) -> u64 {
        self.id
    }

    /// The HDR scene texture's format.
    pub fn scene_format(&self) -> wgpu::TextureFormat {
        self.scene.format()
    }

    /// What the display texture stores.
    pub fn target_format(&self) -> TargetFormat {
        if self.color.format() == TargetFormat::Float32.texture_format() {
            TargetFormat::Float32
        } else {
            TargetFormat::Srgb8
        }
    }

    /// Whether the target's textures live on `gpu`'s device (not on one since replaced).
    pub fn made_on(&self, gpu: &GpuContext) -> bool {
        self.device == gpu.device
    }

    /// Width and height in pixels.
    pub fn size(&self) -> (u32, u32) {
        (self.color.width(), self.color.height())
    }

    /// The display texture's format.
    pub fn format(&self) -> wgpu::TextureFormat {
        self.color.format()
    }

    /// Width divided by height.
    pub fn aspect(&self) -> f32 {
        let (width, height) = self.size();
        width as f32 / height as f32
    }
}

/// Replaces the `resources`' render target with an `Srgb8` one of `width`×`height` when its
/// size differs (a window was resized: pipelines do not depend on the size, so only the target
/// is new); a size of 0 keeps the last one.
pub fn fit_render_target(
    resources: &mut crate::Resources,
    gpu: &GpuContext,
    width: u32,
    height: u32,
) {
    if width == 0 || height == 0 {
        return;
    }
    let fits = resources
        .get::<RenderTarget>()
        .is_some_and(|target| target.size() == (width, height) && target.made_on(gpu));
    if !fits {
        resources.insert(RenderTarget::new(gpu, width, height, TargetFormat::Srgb8));
    }
}
