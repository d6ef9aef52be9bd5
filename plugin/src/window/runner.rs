//! [`App::run`]: the winit event loop of a windowed app. It opens the window on the first
//! `resumed`, makes the GPU context for its surface before the plugins finish (so the renderer
//! draws on the device that presents), then per redraw: fits the render target to the window
//! (or to the part an overlay leaves the scene), updates the app (errors and panics reported
//! once), draws the display target into the swapchain, then any overlay, and presents. Redraws run continuously while the window is visible; a window
//! with no area (minimised) neither updates nor draws until it has one again. A lost GPU
//! device is replaced: a new context for the window, every plugin's GPU setup redone on it
//! ([`App::redo_plugin_setup`]), the assets uploaded again as the next frame draws them.

use std::panic::{AssertUnwindSafe, catch_unwind};
use std::sync::Arc;
use std::time::Instant;

use glam::Vec2;
use winit::application::ApplicationHandler;
use winit::dpi::LogicalSize;
use winit::event::{DeviceEvent, DeviceId, WindowEvent};
use winit::event_loop::{ActiveEventLoop, EventLoop, OwnedDisplayHandle};
use winit::window::{Window, WindowId};

use super::frame_times::FrameTimes;
use super::input::{InputEvent, PendingInput};
use super::panic_report::{OncePanicHook, panic_message};
use super::present::{PresentError, Presenter, ScreenRect};
use super::reported_failures::ReportedFailures;
use super::screenshot::ScreenshotTexture;
use super::{
    AppExit, Automation, DeviceWatch, ScreenshotRequest, ScreenshotSaved, WindowError,
    WindowOverlay, WindowPlugin, WindowSurface,
};

use crate::render::{RenderTarget, fit_render_target};
use crate::{App, GpuContext};

impl App {
    /// Opens the window its [`WindowPlugin`] describes and runs the app in it until the window
    /// closes, a system inserts an [`AppExit`] resource, or `POM_EXIT_AFTER_FRAMES` frames were
    /// presented. What goes wrong is printed as one line on standard error and ends the app
    /// with a non-zero status; the app (its world and resources) is handed back afterwards.
    pub fn run(&mut self) -> AppExit {
        match self.try_run(None) {
            Ok(exit) => exit,
            Err(error) => {
                eprintln!("error: {error}");
                AppExit::error()
            }
        }
    }

    /// [`App::run`] with `overlay` drawn over the scene and fed the window's events first (a
    /// UI: the sandbox's egui panels), returning what went wrong instead of printing it.
    /// The app's [`Automation`] resource, where it has one, replaces the environment's.
    ///
    /// # Errors
    /// A [`WindowError`] that ended the run (or kept it from starting).
    pub fn try_run(
        &mut self,
        overlay: Option<Box<dyn WindowOverlay>>,
    ) -> Result<AppExit, WindowError> {
        let settings = self
            .resources
            .get::<WindowPlugin>()
            .cloned()
            .ok_or(WindowError::NoWindowPlugin)?;
        settings.validate()?;
        let automation = match self.resources.remove::<Automation>() {
            Some(automation) => automation,
            None => Automation::from_env()?,
        };
        let event_loop =
            EventLoop::new().map_err(|error| WindowError::NoDisplay(error.to_string()))?;
        let _hook = OncePanicHook::install();
        let mut runner = Runner {
            app: std::mem::take(self),
            settings,
            frame_times: FrameTimes::new(automation.frame_times.is_some()),
            automation,
            display: event_loop.owned_display_handle(),
            open: None,
            frames: 0,
            visible: true,
            outcome: None,
            reported: ReportedFailures::default(),
            overlay,
            scene_rect: None,
        };
        let ran = event_loop.run_app(&mut runner);
        *self = std::mem::take(&mut runner.app);
        ran.map_err(|error| WindowError::NoDisplay(error.to_string()))?;
        runner.outcome.unwrap_or(Ok(AppExit::Success))
    }
}

/// The event loop's handler.
struct Runner {
    app: App,
    settings: WindowPlugin,
    automation: Automation,
    display: OwnedDisplayHandle,
    open: Option<OpenWindow>,
    /// Frames presented.
    frames: u64,
    visible: bool,
    /// How the run ended, once it has.
    outcome: Option<Result<AppExit, WindowError>>,
    /// Failures already reported (each is reported once).
    reported: ReportedFailures,
    frame_times: FrameTimes,
    overlay: Option<Box<dyn WindowOverlay>>,
    /// Where the last frame put the scene (`None`: the whole window).
    scene_rect: Option<ScreenRect>,
}

/// Everything that exists once the window is open.
struct OpenWindow {
    window: Arc<Window>,
    gpu: GpuContext,
    surface: WindowSurface,
    presenter: Presenter,
    device: DeviceWatch,
}

impl Runner {
    fn open_window(&mut self, event_loop: &ActiveEventLoop) -> Result<OpenWindow, WindowError> {
        let attributes = Window::default_attributes()
            .with_title(&self.settings.title)
            .with_inner_size(LogicalSize::new(self.settings.width, self.settings.height))
            .with_resizable(self.settings.resizable);
        let window = Arc::new(
            event_loop
                .create_window(attributes)
                .map_err(|error| WindowError::CreateWindow(error.to_string()))?,
        );
        // A context the game made itself is kept; else one for this window's surface.
        let (gpu, surface) = match self.app.resources.get::<GpuContext>() {
            Some(gpu) => {
                let surface = gpu
                    .instance
                    .create_surface(Arc::clone(&window))
                    .map_err(|_| WindowError::CannotPresent)?;
                if !gpu.adapter.is_surface_supported(&surface) {
                    return Err(WindowError::CannotPresent);
                }
                (gpu.clone(), surface)
            }
            None => {
                let instance = wgpu::Instance::new(
                    wgpu::InstanceDescriptor::new_with_display_handle_from_env(Box::new(
                        self.display.clone(),
                    )),
                );
                let surface = instance
                    .create_surface(Arc::clone(&window))
                    .map_err(|_| WindowError::CannotPresent)?;
                let gpu = GpuContext::for_surface(instance, &surface)?;
                self.app.insert_resource(gpu.clone());
                (gpu, surface)
            }
        };
        self.app.finish()?;
        self.present_on(window, gpu, surface)
    }

    /// What the window presents with on `gpu` (whose plugins are finished): the configured
    /// swapchain, the present pass, the device watch, and a render target of the window's size.
    fn present_on(
        &mut self,
        window: Arc<Window>,
        gpu: GpuContext,
        surface: wgpu::Surface<'static>,
    ) -> Result<OpenWindow, WindowError> {
        let encodes_srgb = self.overlay.as_ref().is_some_and(|o| o.encodes_srgb());
        let surface = WindowSurface::new(
            surface,
            &gpu,
            Arc::clone(&window),
            self.settings.present_mode,
            encodes_srgb,
        )?;
        let (width, height) = surface.window_size();
        fit_render_target(&mut self.app.resources, &gpu, width, height);
        if let Some(overlay) = &mut self.overlay {
            overlay
                .opened(&mut self.app, &window, &gpu, surface.format())
                .map_err(|error| WindowError::Overlay(error.to_string()))?;
        }
        Ok(OpenWindow {
            presenter: Presenter::new(&gpu),
            device: DeviceWatch::new(&gpu.device),
            window,
            gpu,
            surface,
        })
    }

    /// Goes on after the GPU device was lost: a new device for the window from the same
    /// instance, every plugin's GPU setup made again on it; the world, the assets and the
    /// game's resources stay as they are.
    fn replace_lost_device(&mut self, reason: &str) -> Result<(), WindowError> {
        let Some(OpenWindow { window, gpu, .. }) = self.open.take() else {
            return Ok(());
        };
        eprintln!(
            "warning: the GPU device was lost ({reason}); making a new one and uploading the assets again"
        );
        let instance = gpu.instance.clone();
        // The old swapchain is gone with `open`; the window takes a surface again.
        let surface = instance
            .create_surface(Arc::clone(&window))
            .map_err(|_| WindowError::CannotPresent)?;
        let gpu = GpuContext::for_surface(instance, &surface)?;
        self.app.redo_plugin_setup(gpu.clone())?;
        let open = self.present_on(window, gpu, surface)?;
        open.window.request_redraw();
        self.open = Some(open);
        eprintln!("warning: the app goes on on a new GPU device");
        Ok(())
    }

    /// Asks the window for the size a system set in the [`WindowPlugin`] resource.
    fn follow_size_request(&mut self) -> Result<(), WindowError> {
        let Some(asked) = self.app.resources.get::<WindowPlugin>() else {
            return Ok(());
        };
        if (asked.width, asked.height) == (self.settings.width, self.settings.height) {
            return Ok(());
        }
        asked.validate()?;
        (self.settings.width, self.settings.height) = (asked.width, asked.height);
        if let Some(open) = &self.open {
            // The answer, if any, comes as a resize event.
            let _ = open
                .window
                .request_inner_size(LogicalSize::new(asked.width, asked.height));
        }
        Ok(())
    }

    /// Keeps the [`WindowPlugin`] resource's size at the window's, in logical pixels.
    fn record_size(&mut self, width: u32, height: u32) {
        let Some(open) = &self.open else {
            return;
        };
        if width == 0 || height == 0 {
            return;
        }
        let logical = winit::dpi::PhysicalSize::new(width, height)
            .to_logical::<u32>(open.window.scale_factor());
        (self.settings.width, self.settings.height) = (logical.width, logical.height);
        if let Some(resource) = self.app.resources.get_mut::<WindowPlugin>() {
            (resource.width, resource.height) = (logical.width, logical.height);
        }
    }

    /// Ends the run with `outcome`, writing the screenshot `POM_SCREENSHOT` asks for first.
    fn end(&mut self, event_loop: &ActiveEventLoop, outcome: Result<AppExit, WindowError>) {
        if self.outcome.is_some() {
            return;
        }
        let screenshot = match (&outcome, self.automation.screenshot.clone()) {
            (Ok(_), Some(path)) if self.frames > 0 => self
                .write_screenshot(&path)
                .map_err(|reason| WindowError::Screenshot { path, reason }),
            _ => Ok(()),
        };
        if let Some(overlay) = &mut self.overlay {
            overlay.exiting(&mut self.app);
        }
        let times = match &self.automation.frame_times {
            Some(path) => {
                self.frame_times
                    .write_csv(path)
                    .map_err(|error| WindowError::FrameTimes {
                        path: path.clone(),
                        reason: error.reason(),
                    })
            }
            None => Ok(()),
        };
        self.outcome = Some(screenshot.and(times).and(outcome));
        event_loop.exit();
    }

    /// Writes the window as the last frame showed it to `path`; once the window is gone, the
    /// scene alone (the display target).
    fn write_screenshot(&mut self, path: &std::path::Path) -> Result<(), String> {
        let Some(open) = &self.open else {
            let image = crate::capture(&self.app).map_err(|error| error.to_string())?;
            return crate::files::write_png(path, &image).map_err(|error| error.reason());
        };
        let gpu = open.gpu.clone();
        let (format, size) = (open.surface.format(), open.surface.window_size());
        let shot = ScreenshotTexture::new(&gpu, size, format);
        let mut encoder = gpu
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("window screenshot encoder"),
            });
        self.draw_frame(&mut encoder, &shot.view, (format, size))
            .map_err(|error| error.to_string())?;
        gpu.queue.submit([encoder.finish()]);
        shot.save(&gpu, path)
    }

    /// Records the frame into `view` (`format`, `size` pixels): the scene, then the overlay.
    fn draw_frame(
        &mut self,
        encoder: &mut wgpu::CommandEncoder,
        view: &wgpu::TextureView,
        (format, size): (wgpu::TextureFormat, (u32, u32)),
    ) -> Result<(), PresentError> {
        let Some(open) = &mut self.open else {
            return Ok(());
        };
        if let Some(target) = self.app.resources.get::<RenderTarget>() {
            open.presenter.record(
                &open.gpu,
                target,
                encoder,
                view,
                (format, size),
                self.scene_rect,
            )?;
        }
        if let Some(overlay) = &mut self.overlay {
            overlay.draw(&mut self.app, &open.gpu, encoder, view, size);
        }
        Ok(())
    }

    /// Reports a failed frame once ([`ReportedFailures`]); ends the run where the game asked
    /// for that.
    fn frame_failed(&mut self, event_loop: &ActiveEventLoop, failure: String) {
        for line in self.reported.report(failure) {
            eprintln!("error: {line}");
        }
        if self.settings.exit_on_error {
            self.end(event_loop, Ok(AppExit::error()));
        }
    }

    fn queue(&mut self, event: InputEvent) {
        self.app
            .resources
            .get_or_default::<PendingInput>()
            .0
            .push(event);
    }

    /// One frame: check the device and the size, update the app, draw and present.
    fn redraw(&mut self, event_loop: &ActiveEventLoop) {
        let start = Instant::now();
        let Some((gpu, window, size)) = self.ready_to_draw(event_loop) else {
            return;
        };
        self.frame_times.add(start, |time| &mut time.fit);
        let start = Instant::now();
        self.update_app(event_loop, &gpu, &window, size);
        self.frame_times.add(start, |time| &mut time.update);
        self.present(event_loop, &gpu, &window, size);
        if let Some(exit) = self.app.resources.remove::<AppExit>() {
            return self.end(event_loop, Ok(exit));
        }
        if self
            .automation
            .exit_after_frames
            .is_some_and(|frames| self.frames >= frames)
        {
            self.end(event_loop, Ok(AppExit::Success));
        }
    }

    /// The device and window to draw with and the window's size, once a lost device is
    /// replaced and the size a system asked for is requested; `None` when there is nothing to
    /// draw (the run ended, no window, no area).
    fn ready_to_draw(
        &mut self,
        event_loop: &ActiveEventLoop,
    ) -> Option<(GpuContext, Arc<Window>, (u32, u32))> {
        let (None, Some(open)) = (&self.outcome, &self.open) else {
            return None;
        };
        if let Some(reason) = open.device.lost()
            && let Err(error) = self.replace_lost_device(&reason)
        {
            let error = WindowError::DeviceLost {
                reason,
                replacing: error.to_string(),
            };
            self.end(event_loop, Err(error));
            return None;
        }
        if let Err(error) = self.follow_size_request() {
            self.frame_failed(event_loop, error.to_string());
        }
        let open = self.open.as_ref()?;
        let (width, height) = open.surface.window_size();
        (width > 0 && height > 0)
            .then(|| (open.gpu.clone(), Arc::clone(&open.window), (width, height)))
    }

    /// Fits the target to where the scene goes and runs the app's stages (and the overlay's
    /// work around them); a failure is reported once.
    fn update_app(
        &mut self,
        event_loop: &ActiveEventLoop,
        gpu: &GpuContext,
        window: &Window,
        (width, height): (u32, u32),
    ) {
        self.scene_rect = self
            .overlay
            .as_mut()
            .and_then(|overlay| overlay.before_update(&mut self.app, window))
            .and_then(|rect| rect.within(width, height));
        let (scene_width, scene_height) = self
            .scene_rect
            .map_or((width, height), |rect| (rect.width, rect.height));
        fit_render_target(&mut self.app.resources, gpu, scene_width, scene_height);
        let app = &mut self.app;
        let failure = match catch_unwind(AssertUnwindSafe(|| app.update())) {
            Ok(Ok(())) => None,
            Ok(Err(error)) => Some(error.to_string()),
            Err(payload) => Some(format!(
                "a system panicked: {}",
                panic_message(payload.as_ref())
            )),
        };
        if let Some(overlay) = &mut self.overlay {
            overlay.after_update(&mut self.app, failure.as_deref());
        }
        if let Some(failure) = failure {
            self.frame_failed(event_loop, failure);
        }
    }

    /// Draws the frame into the next swapchain image and presents it (nothing when the run
    /// ended, the device was lost during the update, or no image came).
    fn present(
        &mut self,
        event_loop: &ActiveEventLoop,
        gpu: &GpuContext,
        window: &Window,
        size: (u32, u32),
    ) {
        let start = Instant::now();
        let Some(open) = &mut self.open else {
            return;
        };
        // Lost during the update: nothing more is drawn on it; the next redraw replaces it.
        if self.outcome.is_some() || open.device.lost().is_some() {
            return;
        }
        // A system may retitle the window through the WindowPlugin resource.
        if let Some(settings) = self.app.resources.get::<WindowPlugin>()
            && settings.title != self.settings.title
        {
            open.window.set_title(&settings.title);
            self.settings.title.clone_from(&settings.title);
        }
        let Some(frame) = open.surface.acquire(&open.gpu) else {
            return;
        };
        let format = open.surface.format();
        self.frame_times.add(start, |time| &mut time.acquire);
        let start = Instant::now();
        let view = frame
            .texture
            .create_view(&wgpu::TextureViewDescriptor::default());
        let mut encoder = gpu
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("present encoder"),
            });
        if let Err(error) = self.draw_frame(&mut encoder, &view, (format, size)) {
            return self.end(event_loop, Err(WindowError::Present(error)));
        }
        let commands = encoder.finish();
        self.frame_times.add(start, |time| &mut time.record);
        let start = Instant::now();
        gpu.queue.submit([commands]);
        window.pre_present_notify();
        gpu.queue.present(frame);
        if let Some(ScreenshotRequest(path)) = self.app.resources.remove::<ScreenshotRequest>() {
            let saved = self.write_screenshot(&path).map(|()| path);
            self.app.insert_resource(ScreenshotSaved(saved));
        }
        self.frames += 1;
        self.frame_times.add(start, |time| &mut time.present);
        self.frame_times.presented();
    }
}

impl ApplicationHandler for Runner {
    fn resumed(&mut self, event_loop: &ActiveEventLoop) {
        if self.open.is_some() || self.outcome.is_some() {
            return;
        }
        match self.open_window(event_loop) {
            Ok(open) => {
                open.window.request_redraw();
                self.open = Some(open);
            }
            Err(error) => self.end(event_loop, Err(error)),
        }
    }

    fn window_event(&mut self, event_loop: &ActiveEventLoop, _: WindowId, event: WindowEvent) {
        if let WindowEvent::RedrawRequested = event {
            return self.redraw(event_loop);
        }
        let start = Instant::now();
        let consumed = match (&mut self.overlay, &self.open) {
            (Some(overlay), Some(open)) => overlay.window_event(&open.window, &event),
            _ => false,
        };
        self.handle(event_loop, event, consumed);
        self.frame_times.add(start, |time| &mut time.events);
    }

    fn device_event(&mut self, _: &ActiveEventLoop, _: DeviceId, event: DeviceEvent) {
        let start = Instant::now();
        if let DeviceEvent::MouseMotion { delta: (x, y) } = event {
            self.queue(InputEvent::Motion(Vec2::new(x as f32, y as f32)));
        }
        self.frame_times.add(start, |time| &mut time.events);
    }

    fn about_to_wait(&mut self, _: &ActiveEventLoop) {
        let start = Instant::now();
        // Continuous while visible: games animate whether or not an event came.
        if let (true, Some(open)) = (self.visible, &self.open) {
            open.window.request_redraw();
        }
        self.frame_times.add(start, |time| &mut time.events);
    }
}

impl Runner {
    /// Handles a window event other than a redraw; an overlay that `consumed` it keeps its
    /// input from the app.
    fn handle(&mut self, event_loop: &ActiveEventLoop, event: WindowEvent, consumed: bool) {
        match event {
            WindowEvent::CloseRequested => {
                self.queue(InputEvent::CloseRequested);
                self.end(event_loop, Ok(AppExit::Success));
            }
            // Destroyed from outside (not asked to close): nothing of it may be touched again.
            WindowEvent::Destroyed => {
                self.open = None;
                self.end(event_loop, Ok(AppExit::Success));
            }
            WindowEvent::Resized(size) => {
                self.queue(InputEvent::Resized(size.width, size.height));
                self.record_size(size.width, size.height);
                if let Some(open) = &mut self.open {
                    open.surface.resize(&open.gpu, size.width, size.height);
                    open.window.request_redraw();
                }
            }
            WindowEvent::Focused(focused) => self.queue(InputEvent::Focused(focused)),
            WindowEvent::Occluded(occluded) => {
                self.visible = !occluded;
                if let (true, Some(open)) = (self.visible, &self.open) {
                    open.window.request_redraw();
                }
            }
            // Input the overlay took (a click on its panel) stays from the game.
            event if !consumed => {
                if let Some(input) = InputEvent::from_window_event(&event) {
                    self.queue(input);
                }
            }
            _ => {}
        }
    }
}
