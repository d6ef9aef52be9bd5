//! The screenshot target: when a picture is asked for, the egui pass (which already holds the
//! 3D view as an image) is drawn a second time into this texture, in the surface's format, and
//! read back. Reading the swapchain itself is not possible on every platform.

use std::path::Path;

use anyhow::{Context, Result, bail};
use image::RgbaImage;
use pom::GpuContext;

/// An offscreen colour texture the size of the window.
pub struct ScreenshotTarget {
    /// The texture (render attachment, copy source).
    pub texture: wgpu::Texture,
    /// Its view.
    pub view: wgpu::TextureView,
}

impl ScreenshotTarget {
    /// A `width`×`height` texture of `format` (the surface's).
    pub fn new(gpu: &GpuContext, width: u32, height: u32, format: wgpu::TextureFormat) -> Self {
        let texture = gpu.device.create_texture(&wgpu::TextureDescriptor {
            label: Some("screenshot target"),
            size: wgpu::Extent3d {
                width: width.max(1),
                height: height.max(1),
                depth_or_array_layers: 1,
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format,
            usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
            view_formats: &[],
        });
        let view = texture.create_view(&wgpu::TextureViewDescriptor {
            label: Some("screenshot target view"),
            ..Default::default()
        });
        Self { texture, view }
    }

    /// Reads the texture back as RGBA pixels (after the pass drawing it was submitted).
    pub fn read(&self, gpu: &GpuContext) -> Result<RgbaImage> {
        let mut bytes =
            pom::render::read_texture(gpu, &self.texture).context("reading the screenshot back")?;
        match self.texture.format() {
            wgpu::TextureFormat::Rgba8Unorm | wgpu::TextureFormat::Rgba8UnormSrgb => {}
            wgpu::TextureFormat::Bgra8Unorm | wgpu::TextureFormat::Bgra8UnormSrgb => {
                for pixel in bytes.chunks_exact_mut(4) {
                    pixel.swap(0, 2);
                }
            }
            other => bail!("screenshots of a {other:?} window are not supported"),
        }
        RgbaImage::from_raw(self.texture.width(), self.texture.height(), bytes)
            .context("the screenshot has the wrong number of bytes")
    }
}

/// Writes `image` as a PNG, creating the folder; the picture's alpha is made opaque, as shown.
pub fn save_png(mut image: RgbaImage, path: &Path) -> Result<()> {
    for pixel in image.pixels_mut() {
        pixel.0[3] = 255;
    }
    if let Some(dir) = path.parent().filter(|dir| !dir.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir).with_context(|| format!("creating {}", dir.display()))?;
    }
    image
        .save(path)
        .with_context(|| format!("writing the screenshot {}", path.display()))
}
