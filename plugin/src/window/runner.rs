//! [`App::run`]: the winit event loop of a windowed app. It opens the window on the first
//! `resumed`, makes the GPU context for its surface before the plugins finish (so the renderer
//! draws on the device that presents), then per redraw: fits the render target to the window,
//! updates the app (errors and panics reported once), draws the display target into the
//! swapchain and presents. Redraws run continuously while the window is visible; a window
//! with no area (minimised) neither updates nor draws until it has one again. A lost GPU
//! device is replaced: a new context for the window, every plugin's GPU setup redone on it
//! ([`App::redo_plugin_setup`]), the assets uploaded again as the next frame draws them.

use std::panic::{AssertUnwindSafe, catch_unwind};
use std::sync::Arc;
use std::time::Instant;

use glam::Vec2;
use winit::application::ApplicationHandler;
use winit::dpi::LogicalSize;
use winit::event::{DeviceEvent, DeviceId, ElementState, MouseScrollDelta, WindowEvent};
use winit::event_loop::{ActiveEventLoop, EventLoop, OwnedDisplayHandle};
use winit::keyboard::PhysicalKey;
use winit::window::{Window, WindowId};

use super::frame_times::FrameTimes;
use super::input::{InputEvent, PendingInput};
use super::{AppExit, Automation, DeviceWatch, WindowError, WindowPlugin, WindowSurface};
use crate::render::{Presenter, RenderTarget, fit_render_target};
use crate::{App, GpuContext};

impl App {
    /// Opens the window its [`WindowPlugin`] describes and runs the app in it until the window
    /// closes, a system inserts an [`AppExit`] resource, or `POM_EXIT_AFTER_FRAMES` frames were
    /// presented. What goes wrong is printed as one line on standard error and ends the app
    /// with a non-zero status; the app (its world and resources) is handed back afterwards.
    pub fn run(&mut self) -> AppExit {
        match self.run_window() {
            Ok(exit) => exit,
            Err(error) => {
                eprintln!("error: {error}");
                AppExit::error()
            }
        }
    }

    fn run_window(&mut self) -> Result<AppExit, WindowError> {
        let settings = self
            .resources
            .get::<WindowPlugin>()
            .cloned()
            .ok_or(WindowError::NoWindowPlugin)?;
        settings.validate()?;
        let automation = Automation::from_env()?;
        let event_loop =
            EventLoop::new().map_err(|error| WindowError::NoDisplay(error.to_string()))?;
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
            reported: Vec::new(),
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
    reported: Vec<String>,
    frame_times: FrameTimes,
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
        let surface = WindowSurface::new(
            surface,
            &gpu,
            Arc::clone(&window),
            self.settings.present_mode,
            false,
        )?;
        let (width, height) = surface.window_size();
        fit_render_target(&mut self.app.resources, &gpu, width, height);
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
        // The split view's second target is the game's resource, made on the old device.
        #[cfg(feature = "dev-tools")]
        if let Some(split) = self.app.resources.get_mut::<crate::SplitView>() {
            split.target = None;
        }
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
        let screenshot = match (&outcome, &self.automation.screenshot) {
            (Ok(_), Some(path)) if self.frames > 0 => self.write_screenshot(path),
            _ => Ok(()),
        };
        let times = match &self.automation.frame_times {
            Some(path) => {
                self.frame_times
                    .write_csv(path)
                    .map_err(|error| WindowError::FrameTimes {
                        path: path.clone(),
                        reason: error.to_string(),
                    })
            }
            None => Ok(()),
        };
        self.outcome = Some(screenshot.and(times).and(outcome));
        event_loop.exit();
    }

    fn write_screenshot(&self, path: &std::path::Path) -> Result<(), WindowError> {
        let failed = |reason: String| WindowError::Screenshot {
            path: path.to_owned(),
            reason,
        };
        let image = crate::capture(&self.app).map_err(|error| failed(error.to_string()))?;
        image.save(path).map_err(|error| failed(error.to_string()))
    }

    /// Reports a failed frame once; ends the run where the game asked for that.
    fn frame_failed(&mut self, event_loop: &ActiveEventLoop, failure: String) {
        if !self.reported.contains(&failure) {
            eprintln!("error: {failure}");
            self.reported.push(failure);
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

    fn redraw(&mut self, event_loop: &ActiveEventLoop) {
        let start = Instant::now();
        let (None, Some(open)) = (&self.outcome, &self.open) else {
            return;
        };
        if let Some(reason) = open.device.lost()
            && let Err(error) = self.replace_lost_device(&reason)
        {
            let error = WindowError::DeviceLost {
                reason,
                replacing: error.to_string(),
            };
            return self.end(event_loop, Err(error));
        }
        if let Err(error) = self.follow_size_request() {
            self.frame_failed(event_loop, error.to_string());
        }
        let Some(open) = &self.open else {
            return;
        };
        let (width, height) = open.surface.window_size();
        if width == 0 || height == 0 {
            return;
        }
        let gpu = open.gpu.clone();
        fit_render_target(&mut self.app.resources, &gpu, width, height);
        self.frame_times.add(start, |time| &mut time.fit);
        let start = Instant::now();
        let app = &mut self.app;
        match catch_unwind(AssertUnwindSafe(|| app.update())) {
            Ok(Ok(())) => {}
            Ok(Err(error)) => self.frame_failed(event_loop, error.to_string()),
            Err(payload) => {
                let message = panic_message(payload.as_ref());
                self.frame_failed(event_loop, format!("a system panicked: {message}"));
            }
        }
        self.frame_times.add(start, |time| &mut time.update);
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
        self.frame_times.add(start, |time| &mut time.acquire);
        let start = Instant::now();
        let view = frame
            .texture
            .create_view(&wgpu::TextureViewDescriptor::default());
        let mut encoder = open
            .gpu
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("present encoder"),
            });
        if let Some(target) = self.app.resources.get::<RenderTarget>()
            && let Err(error) = open.presenter.record(
                &open.gpu,
                target,
                &mut encoder,
                &view,
                open.surface.format(),
            )
        {
            return self.end(event_loop, Err(WindowError::Present(error)));
        }
        open.gpu.queue.submit([encoder.finish()]);
        open.window.pre_present_notify();
        open.gpu.queue.present(frame);
        self.frames += 1;
        self.frame_times.add(start, |time| &mut time.present);
        self.frame_times.presented();
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
}

/// The message of a caught panic (`catch_unwind`'s payload): its text, or "(no message)".
pub fn panic_message(payload: &(dyn std::any::Any + Send)) -> String {
    if let Some(text) = payload.downcast_ref::<&str>() {
        (*text).to_owned()
    } else if let Some(text) = payload.downcast_ref::<String>() {
        text.clone()
    } else {
        "(no message)".to_owned()
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
        self.handle(event_loop, event);
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
    /// Handles a window event other than a redraw.
    fn handle(&mut self, event_loop: &ActiveEventLoop, event: WindowEvent) {
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
            WindowEvent::KeyboardInput { event, .. } => {
                if let PhysicalKey::Code(key) = event.physical_key {
                    let down = event.state == ElementState::Pressed;
                    self.queue(InputEvent::Key { key, down });
                }
            }
            WindowEvent::MouseInput { state, button, .. } => {
                let down = state == ElementState::Pressed;
                self.queue(InputEvent::Mouse { button, down });
            }
            WindowEvent::CursorMoved { position, .. } => {
                let position = Vec2::new(position.x as f32, position.y as f32);
                self.queue(InputEvent::Cursor(Some(position)));
            }
            WindowEvent::CursorLeft { .. } => self.queue(InputEvent::Cursor(None)),
            WindowEvent::MouseWheel { delta, .. } => {
                let (lines, pixels) = match delta {
                    MouseScrollDelta::LineDelta(x, y) => (Vec2::new(x, y), Vec2::ZERO),
                    MouseScrollDelta::PixelDelta(p) => {
                        (Vec2::ZERO, Vec2::new(p.x as f32, p.y as f32))
                    }
                };
                self.queue(InputEvent::Scroll { lines, pixels });
            }
            _ => {}
        }
    }
}
