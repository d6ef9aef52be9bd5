//! The offscreen colour and depth textures a frame is drawn into.

use super::GpuContext;

/// What the colour target stores.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum TargetFormat {
    /// 8-bit sRGB: display-ready pixels, what screenshots and reference images use.
    #[default]
    Srgb8,
    /// 32-bit float per channel, no sRGB curve: raw shader output for measurements (debug views,
    /// NaN checks). Read it back with [`crate::render::capture_f32`].
    Float32,
}

impl TargetFormat {
    /// The wgpu texture format.
    pub fn texture_format(self) -> wgpu::TextureFormat {
        match self {
            TargetFormat::Srgb8 => wgpu::TextureFormat::Rgba8UnormSrgb,
            TargetFormat::Float32 => wgpu::TextureFormat::Rgba32Float,
        }
    }

    /// The format of [`RenderTarget::display_view`]: the stored bytes without sRGB decoding.
    pub fn display_view_format(self) -> wgpu::TextureFormat {
        self.texture_format().remove_srgb_suffix()
    }
}
/// A colour attachment that clears `view` to `clear` and stores what the pass draws.
pub fn clearing_attachment(
    view: &wgpu::TextureView,
    clear: wgpu::Color,
) -> wgpu::RenderPassColorAttachment<'_> {
    wgpu::RenderPassColorAttachment {
        view,
        depth_slice: None,
        resolve_target: None,
        ops: wgpu::Operations {
            load: wgpu::LoadOp::Clear(clear),
            store: wgpu::StoreOp::Store,
        },
    }
}

/// The depth buffer format.
pub const DEPTH_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;

/// An offscreen colour + depth target of a fixed size; a resource of the render plugin.
#[derive(Debug)]
pub struct RenderTarget {
    /// The colour texture (render attachment, copy source, sampleable).
    pub color: wgpu::Texture,
    /// A view of [`RenderTarget::color`].
    pub color_view: wgpu::TextureView,
    /// A view of [`RenderTarget::color`] that reads the stored sRGB bytes as plain `Unorm`
    /// (no decoding), for UIs that sample gamma-encoded textures, such as egui.
    pub display_view: wgpu::TextureView,
    /// The depth texture.
    pub depth: wgpu::Texture,
    /// A view of [`RenderTarget::depth`].
    pub depth_view: wgpu::TextureView,
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
        // Listed only when it differs: a float target needs no second view format.
        let display_formats: Vec<wgpu::TextureFormat> = Some(format.display_view_format())
            .filter(|display| *display != format.texture_format())
            .into_iter()
            .collect();
        let color = gpu.device.create_texture(&wgpu::TextureDescriptor {
            label: Some("render target colour"),
            size,
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: format.texture_format(),
            usage: wgpu::TextureUsages::RENDER_ATTACHMENT
                | wgpu::TextureUsages::COPY_SRC
                | wgpu::TextureUsages::TEXTURE_BINDING,
            view_formats: &display_formats,
        });
        let depth = gpu.device.create_texture(&wgpu::TextureDescriptor {
            label: Some("render target depth"),
            size,
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: DEPTH_FORMAT,
            usage: wgpu::TextureUsages::RENDER_ATTACHMENT,
            view_formats: &[],
        });
        let color_view = color.create_view(&wgpu::TextureViewDescriptor {
            label: Some("render target colour view"),
            ..Default::default()
        });
        let display_view = color.create_view(&wgpu::TextureViewDescriptor {
            label: Some("render target display view"),
            format: Some(format.display_view_format()),
            ..Default::default()
        });
        let depth_view = depth.create_view(&wgpu::TextureViewDescriptor {
            label: Some("render target depth view"),
            ..Default::default()
        });
        Self {
            color,
            color_view,
            display_view,
            depth,
            depth_view,
        }
    }

    /// Width and height in pixels.
    pub fn size(&self) -> (u32, u32) {
        (self.color.width(), self.color.height())
    }

    /// The colour texture's format.
    pub fn format(&self) -> wgpu::TextureFormat {
        self.color.format()
    }

    /// Width divided by height.
    pub fn aspect(&self) -> f32 {
        let (width, height) = self.size();
        width as f32 / height as f32
    }
}
