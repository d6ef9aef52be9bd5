//! What a UI over the scene plugs into the window runner ([`crate::App::run_with_overlay`]):
//! it sees the window's events first, changes the app before each update, says where in the
//! window the scene goes, and draws over the presented scene (the sandbox's egui panels).

use std::sync::Arc;

use winit::event::WindowEvent;
use winit::window::Window;

use super::ScreenRect;
use crate::{App, BoxedError, GpuContext};

/// A layer drawn over the scene, with the window's raw events (a UI toolkit's integration).
/// Every method but [`WindowOverlay::draw`] has a default that does nothing.
pub trait WindowOverlay: 'static {
    /// Whether it writes sRGB-encoded colour itself (egui does): the window then gets a
    /// non-sRGB swapchain, and the scene is presented encoded to match.
    fn encodes_srgb(&self) -> bool {
        false
    }

    /// The window is open and the plugins are finished on `gpu`, whose swapchain has
    /// `format`. Called again after a lost device was replaced: make every GPU object anew.
    ///
    /// # Errors
    /// Whatever keeps the overlay from starting; the run ends with it.
    fn opened(
        &mut self,
        app: &mut App,
        window: &Arc<Window>,
        gpu: &GpuContext,
        format: wgpu::TextureFormat,
    ) -> Result<(), BoxedError> {
        let _ = (app, window, gpu, format);
        Ok(())
    }

    /// A window event, before the app's input resources see it; returning `true` keeps it
    /// from them (the pointer was over a panel, say). Resizes and close requests are followed
    /// whatever it returns.
    fn window_event(&mut self, window: &Window, event: &WindowEvent) -> bool {
        let _ = (window, event);
        false
    }

    /// Before each update: may change the app, and says where the scene goes in the window
    /// (`None`: all of it). The render target takes that rectangle's size.
    fn before_update(&mut self, app: &mut App, window: &Window) -> Option<ScreenRect> {
        let _ = (app, window);
        None
    }

    /// After each update, with what failed in it (already reported once on standard error).
    fn after_update(&mut self, app: &mut App, failure: Option<&str>) {
        let _ = (app, failure);
    }

    /// Records into `encoder` what it draws over the scene in `view` (the swapchain image, or
    /// a screenshot's texture of the same format and size), `size` pixels; the image already
    /// holds the scene, so its pass loads rather than clears. A screenshot draws the frame's
    /// overlay a second time.
    fn draw(
        &mut self,
        app: &mut App,
        gpu: &GpuContext,
        encoder: &mut wgpu::CommandEncoder,
        view: &wgpu::TextureView,
        size: (u32, u32),
    );

    /// The run is ending (the window closes or the app asked to exit).
    fn exiting(&mut self, app: &mut App) {
        let _ = app;
    }
}
