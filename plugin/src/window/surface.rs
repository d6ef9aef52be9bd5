//! A window's swapchain: configured in the surface's preferred format (the present pass takes
//! any) or, for a UI that encodes sRGB itself (egui), a non-sRGB one; reconfigured on resize and
//! when outdated, recreated when lost; frames are skipped while the window has no area.

use std::sync::Arc;

use winit::window::Window;

use super::WindowError;
use crate::GpuContext;

/// A window's surface and its configuration.
pub struct WindowSurface {
    surface: wgpu::Surface<'static>,
    config: wgpu::SurfaceConfiguration,
    window: Arc<Window>,
    /// The window's inner size in pixels as its last resize said (0 while minimised): asking
    /// the window itself fails once something outside destroyed it.
    window_size: (u32, u32),
    /// Set by a suboptimal frame: reconfigure before the next one (not while it is held).
    needs_configure: bool,
}

/// A presentable non-sRGB format, `Bgra8Unorm` by preference.
fn pick_non_srgb(formats: &[wgpu::TextureFormat]) -> Option<wgpu::TextureFormat> {
    [
        wgpu::TextureFormat::Bgra8Unorm,
        wgpu::TextureFormat::Rgba8Unorm,
    ]
    .into_iter()
    .find(|format| formats.contains(format))
    .or_else(|| formats.iter().copied().find(|format| !format.is_srgb()))
}

impl WindowSurface {
    /// Configures `surface` (created from `window` with `gpu`'s instance) for `present_mode`
    /// (vsync where the window cannot), in a non-sRGB format where `non_srgb`.
    ///
    /// # Errors
    /// [`WindowError::CannotPresent`] when the adapter cannot present to the window, or offers
    /// no non-sRGB format where one is asked for.
    pub fn new(
        surface: wgpu::Surface<'static>,
        gpu: &GpuContext,
        window: Arc<Window>,
        present_mode: wgpu::PresentMode,
        non_srgb: bool,
    ) -> Result<Self, WindowError> {
        let size = window.inner_size();
        let mut config = surface
            .get_default_config(&gpu.adapter, size.width.max(1), size.height.max(1))
            .ok_or(WindowError::CannotPresent)?;
        config.usage = wgpu::TextureUsages::RENDER_ATTACHMENT;
        let capabilities = surface.get_capabilities(&gpu.adapter);
        if non_srgb {
            config.format =
                pick_non_srgb(&capabilities.formats).ok_or(WindowError::CannotPresent)?;
        }
        let modes = capabilities.present_modes;
        config.present_mode = if matches!(
            present_mode,
            wgpu::PresentMode::AutoVsync | wgpu::PresentMode::AutoNoVsync
        ) || modes.contains(&present_mode)
        {
            present_mode
        } else {
            log::warn!("the window cannot present {present_mode:?} (it offers {modes:?}): vsync");
            wgpu::PresentMode::AutoVsync
        };
        surface.configure(&gpu.device, &config);
        Ok(Self {
            surface,
            config,
            window,
            window_size: (size.width, size.height),
            needs_configure: false,
        })
    }

    /// The swapchain's texture format.
    pub fn format(&self) -> wgpu::TextureFormat {
        self.config.format
    }

    /// The window's inner size in pixels, as the last [`WindowSurface::resize`] said.
    pub fn window_size(&self) -> (u32, u32) {
        self.window_size
    }

    /// Follows the window's size (call it on every resize event); a zero size skips frames and
    /// keeps the configuration for when the window comes back.
    pub fn resize(&mut self, gpu: &GpuContext, width: u32, height: u32) {
        self.window_size = (width, height);
        if width == 0 || height == 0 || (width, height) == (self.config.width, self.config.height) {
            return;
        }
        self.config.width = width;
        self.config.height = height;
        self.surface.configure(&gpu.device, &self.config);
    }

    /// The next image to draw into, or `None` when this frame should be skipped (minimised,
    /// occluded, timed out, or the surface had to be reconfigured or recreated).
    pub fn acquire(&mut self, gpu: &GpuContext) -> Option<wgpu::SurfaceTexture> {
        let (width, height) = self.window_size;
        if width == 0 || height == 0 {
            return None;
        }
        if self.needs_configure {
            self.needs_configure = false;
            self.surface.configure(&gpu.device, &self.config);
        }
        match self.surface.get_current_texture() {
            wgpu::CurrentSurfaceTexture::Success(frame) => Some(frame),
            wgpu::CurrentSurfaceTexture::Suboptimal(frame) => {
                // Draw this one; the next acquire uses a fresh configuration.
                self.needs_configure = true;
                Some(frame)
            }
            wgpu::CurrentSurfaceTexture::Timeout | wgpu::CurrentSurfaceTexture::Occluded => None,
            wgpu::CurrentSurfaceTexture::Outdated | wgpu::CurrentSurfaceTexture::Validation => {
                self.surface.configure(&gpu.device, &self.config);
                None
            }
            wgpu::CurrentSurfaceTexture::Lost => {
                match gpu.instance.create_surface(Arc::clone(&self.window)) {
                    Ok(surface) => {
                        surface.configure(&gpu.device, &self.config);
                        self.surface = surface;
                    }
                    Err(error) => log::warn!("could not recreate the lost window surface: {error}"),
                }
                None
            }
        }
    }
}
