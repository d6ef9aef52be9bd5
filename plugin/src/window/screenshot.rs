//! Pictures of the window as shown (the scene and any overlay): the frame is drawn a second
//! time into a texture of the swapchain's format and read back, since not every platform
//! lets a swapchain image be read. [`ScreenshotRequest`] asks for one after a frame;
//! `POM_SCREENSHOT` takes one of the last frame.

use std::path::{Path, PathBuf};

use image::RgbaImage;

use crate::GpuContext;

/// Asks the runner for a picture of the window after this frame, written as a PNG to the path
/// (its folder made if missing). A resource: the runner takes it and leaves a
/// [`ScreenshotSaved`].
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ScreenshotRequest(pub PathBuf);

/// How the last [`ScreenshotRequest`] went: the file written, or why not. A resource.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ScreenshotSaved(pub Result<PathBuf, String>);

/// A texture to draw a frame into for reading back.
pub(crate) struct ScreenshotTexture {
    pub texture: wgpu::Texture,
    pub view: wgpu::TextureView,
}

impl ScreenshotTexture {
    /// A `width` × `height` texture of `format` (the swapchain's).
    pub fn new(gpu: &GpuContext, (width, height): (u32, u32), format: wgpu::TextureFormat) -> Self {
        let texture = gpu.device.create_texture(&wgpu::TextureDescriptor {
            label: Some("window screenshot"),
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
        let view = texture.create_view(&wgpu::TextureViewDescriptor::default());
        Self { texture, view }
    }

    /// Reads the texture back (after the frame drawn into it was submitted) and writes it to
    /// `path` as an opaque PNG, making its folder.
    pub fn save(&self, gpu: &GpuContext, path: &Path) -> Result<(), String> {
        let mut bytes =
            crate::gpu::read_texture(gpu, &self.texture).map_err(|error| error.to_string())?;
        match self.texture.format() {
            wgpu::TextureFormat::Rgba8Unorm | wgpu::TextureFormat::Rgba8UnormSrgb => {}
            wgpu::TextureFormat::Bgra8Unorm | wgpu::TextureFormat::Bgra8UnormSrgb => {
                for pixel in bytes.chunks_exact_mut(4) {
                    pixel.swap(0, 2);
                }
            }
            other => return Err(format!("a window of {other:?} cannot be saved as a PNG")),
        }
        // What the screen shows is opaque, whatever the frame left in alpha.
        for pixel in bytes.chunks_exact_mut(4) {
            pixel[3] = 255;
        }
        let image = RgbaImage::from_raw(self.texture.width(), self.texture.height(), bytes)
            .ok_or("the frame read back has the wrong number of bytes")?;
        if let Some(folder) = path.parent().filter(|dir| !dir.as_os_str().is_empty()) {
            std::fs::create_dir_all(folder)
                .map_err(|error| format!("creating {}: {error}", folder.display()))?;
        }
        crate::files::write_png(path, &image).map_err(|error| error.reason())
    }
}
