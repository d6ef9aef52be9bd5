//! The winit application: creates the window, the surface and the shared GPU device, builds the
//! `pom::App` on that device, and each frame runs the UI, updates the app (which renders the
//! scene into its target) and paints egui to the window.

use std::path::PathBuf;
use std::sync::Arc;
use std::time::Instant;

use anyhow::{Context, Result, anyhow};
use egui::{CentralPanel, Panel, Sense};
use egui_wgpu::ScreenDescriptor;
use pom::glam::Vec2;
use pom::render::RenderTarget;
use pom::window::{DeviceWatch, WindowSurface};
use pom::{
    App, GpuContext, ParallaxOcclusionMaterial, PomPlugin, RenderPlugin, ShaderHotReload, SplitView,
};
use winit::application::ApplicationHandler;
use winit::event::WindowEvent;
use winit::event_loop::{ActiveEventLoop, OwnedDisplayHandle};
use winit::window::{Window, WindowId};

use super::WindowArgs;
use super::app_state::{load_scene, material_entities, record_tuned, restore_tuned, spin};
use super::autosave::{self, Autosave, TunedState};
use pom::window::{CameraInput, OrbitCamera};

use super::camera_control::{active_camera_transform, from_viewport, write_to_camera};
use super::egui_painter::{EguiFrame, EguiPainter};
use super::guarded_update::update_catching_panics;
use super::panels::{PanelState, side_panel_contents};
use super::screenshot::{ScreenshotTarget, save_png};

/// The window's size when it opens, in logical pixels.
const INITIAL_SIZE: (f64, f64) = (1280.0, 720.0);
/// Width of the side panel when it opens, in points.
const PANEL_WIDTH: f32 = 380.0;

/// The application handler; [`WindowApp::finish`] reports how it ended.
pub struct WindowApp {
    scene: Option<PathBuf>,
    camera: Option<crate::cli_types::CameraArg>,
    split_method: Option<pom::ParallaxMethod>,
    exit_after_frames: Option<u64>,
    screenshot: Option<PathBuf>,
    state_path: PathBuf,
    display: OwnedDisplayHandle,
    running: Option<Running>,
    error: Option<anyhow::Error>,
    frames: u64,
}

/// Everything that exists once the window is open.
struct Running {
    window: Arc<Window>,
    gpu: GpuContext,
    surface: WindowSurface,
    painter: EguiPainter,
    egui: egui::Context,
    egui_input: egui_winit::State,
    app: App,
    panel: PanelState,
    orbit: Option<OrbitCamera>,
    scene_label: String,
    autosave: Autosave,
    tuned: TunedState,
    last_frame: Instant,
    device: DeviceWatch,
}

impl WindowApp {
    /// A handler for `args`, using the event loop's display.
    pub fn new(args: &WindowArgs, display: OwnedDisplayHandle) -> Self {
        Self {
            scene: args.scene.clone(),
            camera: args.camera,
            split_method: args.split_method,
            exit_after_frames: args.exit_after_frames,
            screenshot: args.screenshot.clone(),
            state_path: args
                .state
                .clone()
                .unwrap_or_else(autosave::default_state_path),
            display,
            running: None,
            error: None,
            frames: 0,
        }
    }

    /// The error that closed the window, if any; saves the tuned values one last time.
    pub fn finish(mut self) -> Result<()> {
        if let Some(running) = &mut self.running
            && let Err(error) = running.save_tuned(true)
        {
            log::warn!("{error:#}");
        }
        match self.error {
            Some(error) => Err(error),
            None => Ok(()),
        }
    }

    fn fail(&mut self, event_loop: &ActiveEventLoop, error: anyhow::Error) {
        self.error = Some(error);
        event_loop.exit();
    }

    fn open(&self, event_loop: &ActiveEventLoop) -> Result<Running> {
        let attributes = Window::default_attributes()
            .with_title("POM sandbox")
            .with_inner_size(winit::dpi::LogicalSize::new(INITIAL_SIZE.0, INITIAL_SIZE.1));
        let window = Arc::new(
            event_loop
                .create_window(attributes)
                .context("cannot create the window")?,
        );
        let instance =
            wgpu::Instance::new(wgpu::InstanceDescriptor::new_with_display_handle_from_env(
                Box::new(self.display.clone()),
            ));
        let surface = instance.create_surface(Arc::clone(&window)).context(
            "cannot draw into the window: no GPU driver can present to it (without a GPU, \
                 install Mesa's software Vulkan driver: apt-get install mesa-vulkan-drivers \
                 libvulkan1; or render headless with `sandbox snapshot`)",
        )?;
        // One device for the window and the plugin: RenderPlugin finds this context and uses it.
        let gpu = GpuContext::for_surface(instance, &surface)?;
        // egui-wgpu writes gamma-encoded pixels itself: a non-sRGB swapchain.
        let surface = WindowSurface::new(
            surface,
            &gpu,
            Arc::clone(&window),
            wgpu::PresentMode::AutoVsync,
            true,
        )?;

        let size = window.inner_size();
        let mut app = App::new();
        app.insert_resource(gpu.clone());
        app.add_plugin(RenderPlugin::headless(
            size.width.max(1),
            size.height.max(1),
        ))
        .add_plugin(PomPlugin);
        if let Some(hot_reload) = std::env::current_dir()
            .ok()
            .and_then(|dir| ShaderHotReload::from_repository(&dir))
        {
            app.add_plugin(hot_reload);
        }
        let loaded = load_scene(&mut app, self.scene.as_deref(), self.camera);
        let mut panel = PanelState {
            messages: loaded.messages,
            ..PanelState::default()
        };
        let tuned = match autosave::load(&self.state_path) {
            Ok(tuned) => tuned,
            Err(error) => {
                panel
                    .messages
                    .push(format!("tuned values not restored: {error:#}"));
                TunedState::default()
            }
        };
        restore_tuned(&mut app, &loaded.label, &tuned);
        if let Some(method) = self.split_method {
            panel.split.enabled = true;
            let overrides = material_entities(&app)
                .into_iter()
                .filter_map(|(entity, _)| {
                    let material = app.world.get::<&ParallaxOcclusionMaterial>(entity).ok()?;
                    Some((
                        entity,
                        pom::ParallaxOcclusionMaterial {
                            method,
                            ..(*material).clone()
                        },
                    ))
                })
                .collect();
            app.insert_resource(SplitView {
                overrides,
                target: None,
            });
        }
        app.finish().context("starting the renderer")?;
        let orbit = active_camera_transform(&app.world)
            .map(|camera| OrbitCamera::from_transform(&camera, loaded.focus_distance));

        let target = app
            .resources
            .get::<RenderTarget>()
            .ok_or_else(|| anyhow!("the render plugin made no render target"))?;
        let painter = EguiPainter::new(&gpu, surface.format(), target);
        let egui = egui::Context::default();
        let egui_input = egui_winit::State::new(
            egui.clone(),
            egui::ViewportId::ROOT,
            &window,
            Some(window.scale_factor() as f32),
            None,
            Some(gpu.device.limits().max_texture_dimension_2d as usize),
        );
        let device = DeviceWatch::new(&gpu.device);
        Ok(Running {
            window,
            gpu,
            surface,
            painter,
            egui,
            egui_input,
            app,
            panel,
            orbit,
            scene_label: loaded.label,
            autosave: Autosave::new(self.state_path.clone(), tuned.clone()),
            tuned,
            last_frame: Instant::now(),
            device,
        })
    }

    /// Draws one frame; returns whether one was presented.
    fn redraw(&mut self, force_screenshot: bool) -> Result<bool> {
        let last_frame = self.exit_after_frames.is_some_and(|n| self.frames + 1 >= n);
        let flag_screenshot = if last_frame || force_screenshot {
            self.screenshot.clone()
        } else {
            None
        };
        let Some(running) = &mut self.running else {
            return Ok(false);
        };
        if let Some(reason) = running.device.lost() {
            // Nothing can be drawn on a lost device; save what was tuned and close clearly.
            let saved = running.save_tuned(true);
            return Err(anyhow!(
                "the GPU device was lost ({reason}); the sandbox closed. Tuned values {}; \
                 start it again to continue",
                match saved {
                    Ok(()) => format!("are saved in {}", running.autosave.path().display()),
                    Err(error) => format!("could not be saved: {error:#}"),
                }
            ));
        }
        let Some(frame) = running.surface.acquire(&running.gpu) else {
            return Ok(false);
        };
        let button_screenshot = std::mem::take(&mut running.panel.screenshot_requested)
            .then(|| PathBuf::from(&running.panel.screenshot_path));
        let shots: Vec<PathBuf> = flag_screenshot
            .into_iter()
            .chain(button_screenshot)
            .collect();
        running.draw(frame, &shots)?;
        self.frames += 1;
        Ok(true)
    }
}

impl Running {
    /// Runs the UI, updates the app and paints; writes a screenshot to each of `shots`.
    fn draw(&mut self, frame: wgpu::SurfaceTexture, shots: &[PathBuf]) -> Result<()> {
        let now = Instant::now();
        let frame_time = now.duration_since(self.last_frame).as_secs_f32();
        let dt = frame_time.min(0.1);
        self.last_frame = now;
        self.panel.frame_times.push(frame_time);

        let raw_input = self.egui_input.take_egui_input(&self.window);
        let mut viewport_pixels = None;
        let mut camera_input = CameraInput::default();
        let mut click = None;
        let (scene_texture, split_texture) =
            (self.painter.scene_texture, self.painter.split_texture);
        let (app, panel) = (&mut self.app, &mut self.panel);
        let output = self.egui.run_ui(raw_input, |ui| {
            Panel::left("controls")
                .default_size(PANEL_WIDTH)
                .resizable(true)
                .show(ui, |ui| side_panel_contents(ui, app, panel));
            let wipe = panel.split.enabled.then_some(panel.split.wipe);
            CentralPanel::default()
                .frame(egui::Frame::NONE)
                .show(ui, |ui| {
                    let size = ui.available_size();
                    let pixels = size * ui.ctx().pixels_per_point();
                    viewport_pixels = Some((pixels.x.round() as u32, pixels.y.round() as u32));
                    let image =
                        egui::Image::new((scene_texture, size)).sense(Sense::click_and_drag());
                    let response = ui.add(image);
                    if let Some(wipe) = wipe {
                        paint_split(ui, response.rect, split_texture, wipe);
                    }
                    camera_input = from_viewport(ui, &response);
                    click = clicked_pixel(&response, ui.ctx().pixels_per_point());
                });
        });
        self.egui_input
            .handle_platform_output(&self.window, output.platform_output);

        if let Some((width, height)) = viewport_pixels {
            pom::render::fit_render_target(&mut self.app.resources, &self.gpu, width, height);
        }
        if let Some(loaded) = self.panel.opened.take() {
            self.scene_opened(loaded);
        }
        if let Some((viewport, pixel)) = click {
            select_clicked(&self.app, &mut self.panel, viewport, pixel);
        }
        if let Some(orbit) = &mut self.orbit
            && !camera_input.is_idle()
        {
            orbit.apply(&camera_input);
            write_to_camera(&mut self.app.world, orbit);
        }
        if self.panel.spin_selected
            && let Some(entity) = self.panel.selected
        {
            spin(&mut self.app.world, entity, dt);
        }
        if let Err(failure) = update_catching_panics(&mut self.app) {
            // Keep the window (and the tuned values) alive; say what failed once.
            let message = failure.to_string();
            if !self.panel.messages.contains(&message) {
                self.panel.messages.push(message);
            }
        }
        if let Err(error) = self.save_tuned(false) {
            let message = format!("autosave failed: {error:#}");
            if !self.panel.messages.contains(&message) {
                self.panel.messages.push(message);
            }
        }

        let paint_jobs = self.egui.tessellate(output.shapes, output.pixels_per_point);
        let mut textures = output.textures_delta;
        let (width, height) = (frame.texture.width(), frame.texture.height());
        let screen = ScreenDescriptor {
            size_in_pixels: [width, height],
            pixels_per_point: output.pixels_per_point,
        };
        let screenshot = (!shots.is_empty())
            .then(|| ScreenshotTarget::new(&self.gpu, width, height, self.surface.format()));
        let view = frame
            .texture
            .create_view(&wgpu::TextureViewDescriptor::default());
        // The overlay phase, timed like the others; its figure arrives with the next frame's.
        let overlay_time =
            pom::render::time_pass(&mut self.app.resources, pom::RenderPhase::Overlay.name());
        let target = self
            .app
            .resources
            .get::<RenderTarget>()
            .ok_or_else(|| anyhow!("the render target is gone"))?;
        let split = self
            .app
            .resources
            .get::<SplitView>()
            .and_then(|split| split.target.as_ref())
            .unwrap_or(target);
        self.painter.paint(
            &self.gpu,
            (target, split),
            EguiFrame {
                paint_jobs: &paint_jobs,
                textures: &mut textures,
                screen,
            },
            &view,
            screenshot.as_ref(),
            overlay_time.as_ref(),
        );
        self.window.pre_present_notify();
        self.gpu.queue.present(frame);
        if let Some(screenshot) = screenshot {
            let image = screenshot.read(&self.gpu)?;
            for path in shots {
                save_png(image.clone(), path)?;
                self.panel.messages.retain(|m| !m.starts_with("screenshot"));
                self.panel
                    .messages
                    .push(format!("screenshot saved to {}", path.display()));
            }
        }
        Ok(())
    }

    /// Follows a scene opened from the panel: its label keys the tuned values, and the orbit
    /// starts from its camera.
    fn scene_opened(&mut self, loaded: super::app_state::LoadedScene) {
        self.scene_label = loaded.label;
        self.panel.messages.extend(loaded.messages);
        restore_tuned(&mut self.app, &self.scene_label, &self.tuned);
        self.orbit = active_camera_transform(&self.app.world)
            .map(|camera| OrbitCamera::from_transform(&camera, loaded.focus_distance));
    }

    /// Records the materials' values and writes them if they changed (at most once a second,
    /// unless `force`).
    fn save_tuned(&mut self, force: bool) -> Result<()> {
        record_tuned(&self.app, &self.scene_label, &mut self.tuned);
        self.autosave
            .maybe_write(&self.tuned, Instant::now(), force)
            .with_context(|| format!("writing {}", self.autosave.path().display()))
    }
}

/// Draws image B over the viewport `rect` right of the wipe, and the wipe line.
fn paint_split(ui: &egui::Ui, rect: egui::Rect, texture: egui::TextureId, wipe: f32) {
    let x = rect.left() + rect.width() * wipe.clamp(0.0, 1.0);
    let right = egui::Rect::from_min_max(egui::pos2(x, rect.top()), rect.max);
    let full_uv = egui::Rect::from_min_max(egui::pos2(0.0, 0.0), egui::pos2(1.0, 1.0));
    let painter = ui.painter().with_clip_rect(right);
    painter.image(texture, rect, full_uv, egui::Color32::WHITE);
    painter.vline(
        x,
        rect.y_range(),
        egui::Stroke::new(2.0, egui::Color32::WHITE),
    );
    let label = |pos: egui::Pos2, align: egui::Align2, text: &str| {
        ui.painter().text(
            pos,
            align,
            text,
            egui::FontId::proportional(16.0),
            egui::Color32::WHITE,
        );
    };
    label(
        rect.left_top() + egui::vec2(8.0, 8.0),
        egui::Align2::LEFT_TOP,
        "A",
    );
    label(
        rect.right_top() + egui::vec2(-8.0, 8.0),
        egui::Align2::RIGHT_TOP,
        "B",
    );
}

/// The viewport's size and the clicked point in pixels, for a primary click without a drag.
fn clicked_pixel(response: &egui::Response, pixels_per_point: f32) -> Option<(Vec2, Vec2)> {
    if !response.clicked() {
        return None;
    }
    let position = response.interact_pointer_pos()?;
    let rect = response.rect;
    let to_pixels = |v: egui::Vec2| Vec2::new(v.x, v.y) * pixels_per_point;
    Some((to_pixels(rect.size()), to_pixels(position - rect.min)))
}

/// Selects the parallax-material entity under the clicked pixel; a click on anything else
/// keeps the selection and says why.
fn select_clicked(app: &App, panel: &mut PanelState, viewport: Vec2, pixel: Vec2) {
    let Some(hit) = pom::pick_at(&app.world, &app.resources, viewport, pixel) else {
        return;
    };
    panel.messages.retain(|m| !m.starts_with("clicked object"));
    if app
        .world
        .satisfies::<&ParallaxOcclusionMaterial>(hit.entity)
    {
        panel.selected = Some(hit.entity);
    } else {
        panel
            .messages
            .push("clicked object has no parallax material".to_owned());
    }
}

impl ApplicationHandler for WindowApp {
    fn resumed(&mut self, event_loop: &ActiveEventLoop) {
        if self.running.is_some() {
            return;
        }
        match self.open(event_loop) {
            Ok(running) => {
                running.window.request_redraw();
                self.running = Some(running);
            }
            Err(error) => self.fail(event_loop, error),
        }
    }

    fn window_event(&mut self, event_loop: &ActiveEventLoop, _: WindowId, event: WindowEvent) {
        let Some(running) = &mut self.running else {
            return;
        };
        let _ = running.egui_input.on_window_event(&running.window, &event);
        match event {
            WindowEvent::CloseRequested => {
                if self.screenshot.is_some()
                    && let Err(error) = self.redraw(true)
                {
                    self.error = Some(error);
                }
                event_loop.exit();
            }
            WindowEvent::Resized(size) => {
                running
                    .surface
                    .resize(&running.gpu, size.width, size.height);
                running.window.request_redraw();
            }
            WindowEvent::RedrawRequested => {
                match self.redraw(false) {
                    Ok(_) if self.exit_after_frames.is_some_and(|n| self.frames >= n) => {
                        event_loop.exit();
                    }
                    Ok(_) => {}
                    Err(error) => return self.fail(event_loop, error),
                }
                // Redraw continuously: spinning, camera keys and autosave need frames.
                if let Some(running) = &self.running {
                    running.window.request_redraw();
                }
            }
            _ => {}
        }
    }
}

#[cfg(test)]
mod tests {
    use pom::{Assets, Camera, Mesh, TransformPlugin};

    use super::*;

    #[test]
    fn a_click_selects_the_material_under_it_and_a_miss_keeps_the_selection() {
        let mut app = App::new();
        app.add_plugin(TransformPlugin);
        let cube = app
            .resources
            .get_or_default::<Assets<Mesh>>()
            .add(Mesh::cube(1.0));
        app.world.spawn((
            Camera::perspective(60.0),
            pom::Transform::from_xyz(0.0, 0.0, 5.0),
        ));
        let left = app.world.spawn((
            cube.clone(),
            ParallaxOcclusionMaterial::default(),
            pom::Transform::from_xyz(-1.5, 0.0, 0.0),
        ));
        let right = app.world.spawn((
            cube,
            ParallaxOcclusionMaterial::default(),
            pom::Transform::from_xyz(1.5, 0.0, 0.0),
        ));
        app.update().unwrap();
        let mut panel = PanelState {
            selected: Some(left),
            ..PanelState::default()
        };
        let viewport = Vec2::new(400.0, 200.0);
        // The cubes span pixels 238..277 and 123..162 (x = ±1..2 seen from 4.5 away).
        select_clicked(&app, &mut panel, viewport, Vec2::new(258.0, 100.0));
        assert_eq!(panel.selected, Some(right));
        select_clicked(&app, &mut panel, viewport, Vec2::new(2.0, 2.0));
        assert_eq!(panel.selected, Some(right));
        select_clicked(&app, &mut panel, viewport, Vec2::new(142.0, 100.0));
        assert_eq!(panel.selected, Some(left));
    }
}
