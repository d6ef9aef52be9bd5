//! The sandbox's window: pom's window runner (`App::try_run`) with egui as its overlay. Before
//! each update the UI runs (its panels edit the `pom::App`'s components and resources) and
//! says where the scene goes; the runner presents the scene there and egui paints the panels
//! over it. Surface, resizes, time, input, device loss and screenshots are the runner's.

use std::path::PathBuf;
use std::sync::Arc;
use std::time::Instant;

use anyhow::{Result, anyhow};
use egui::{CentralPanel, Sense};
use egui_wgpu::ScreenDescriptor;
use pom::glam::Vec2;
use pom::render::RenderTarget;
use pom::window::ScreenRect;
use pom::window::{
    Automation, CameraInput, OrbitCamera, ScreenshotRequest, ScreenshotSaved, WindowError,
    WindowOverlay, WindowPlugin,
};
use pom::{
    App, BoxedError, GpuContext, ParallaxOcclusionMaterial, PomPlugin, RenderPlugin,
    ShaderHotReload, SplitView, Time,
};
use winit::event::WindowEvent;
use winit::window::Window;

use super::WindowArgs;
use super::app_state::{load_scene, material_entities, record_tuned, restore_tuned, spin};
use super::autosave::{self, Autosave, TunedState};
use super::camera_control::{active_camera_transform, from_viewport, write_to_camera};
use super::egui_painter::{EguiFrame, EguiPainter};
use super::guarded_update::catching_panics;
use super::panels::{PanelState, side_panel};

/// The window's size when it opens, in logical pixels.
pub(super) const INITIAL_SIZE: (u32, u32) = (1280, 720);

/// Opens the sandbox window on `args`' scene and runs it until it is closed (or
/// `--exit-after-frames` is reached).
pub fn run(args: &WindowArgs) -> Result<()> {
    let mut app = App::new();
    app.add_plugin(WindowPlugin {
        title: "POM sandbox".to_owned(),
        width: INITIAL_SIZE.0,
        height: INITIAL_SIZE.1,
        ..WindowPlugin::default()
    })
    .add_plugin(RenderPlugin::new(INITIAL_SIZE.0, INITIAL_SIZE.1))
    .add_plugin(PomPlugin);
    if let Some(hot_reload) = std::env::current_dir()
        .ok()
        .and_then(|dir| ShaderHotReload::from_repository(&dir))
    {
        app.add_plugin(hot_reload);
    }
    let overlay = SandboxOverlay::new(&mut app, args);
    app.insert_resource(Automation {
        exit_after_frames: args.exit_after_frames,
        screenshot: args.screenshot.clone(),
        frame_times: None,
    });
    match app.try_run(Some(Box::new(overlay))) {
        Ok(exit) if exit.is_success() => Ok(()),
        Ok(exit) => Err(anyhow!("the sandbox ended with {exit:?}")),
        Err(WindowError::NoDisplay(error)) => Err(anyhow!(
            "cannot open a window ({error}): no display? Render headless instead with \
             `sandbox snapshot --out FILE.png` (this scene) or `sandbox render --help`"
        )),
        Err(error) => Err(error.into()),
    }
}

/// The egui side of the window, from the window opening on.
struct OnWindow {
    painter: EguiPainter,
    egui_input: egui_winit::State,
}

/// One frame of egui output between the UI run and the paint.
struct PendingPaint {
    paint_jobs: Vec<egui::ClippedPrimitive>,
    textures: egui::TexturesDelta,
    pixels_per_point: f32,
}

/// The most messages the panel lists.
const MOST_MESSAGES: usize = 32;

/// Adds `message` to `messages` unless it is there already, up to [`MOST_MESSAGES`]: the last
/// place says more came, and later ones go to the log.
fn say_once(messages: &mut Vec<String>, message: String) {
    if messages.contains(&message) {
        return;
    }
    if messages.len() + 1 < MOST_MESSAGES {
        messages.push(message);
    } else {
        if messages.len() + 1 == MOST_MESSAGES {
            messages.push(MORE_MESSAGES.into());
        }
        log::warn!("{message}");
    }
}

/// The panel's last message where more came than it lists.
const MORE_MESSAGES: &str = "more messages than the panel shows: see the log";

/// The sandbox's UI over the scene: panels, the orbit camera on the viewport, the split
/// view's wipe, autosave of the tuned values.
struct SandboxOverlay {
    egui: egui::Context,
    on_window: Option<OnWindow>,
    output: Option<egui::FullOutput>,
    pending: Option<PendingPaint>,
    panel: PanelState,
    orbit: Option<OrbitCamera>,
    scene_label: String,
    autosave: Autosave,
    tuned: TunedState,
}

impl SandboxOverlay {
    /// Loads `args`' scene into `app` and restores its tuned values.
    fn new(app: &mut App, args: &WindowArgs) -> Self {
        let loaded = load_scene(app, args.scene.as_deref(), args.camera);
        let mut panel = PanelState {
            messages: loaded.messages,
            ..PanelState::default()
        };
        let state_path = args
            .state
            .clone()
            .unwrap_or_else(autosave::default_state_path);
        let tuned = match autosave::load(&state_path) {
            Ok(tuned) => tuned,
            Err(error) => {
                panel
                    .messages
                    .push(format!("tuned values not restored: {error:#}"));
                TunedState::default()
            }
        };
        restore_tuned(app, &loaded.label, &tuned);
        if let Some(method) = args.split_method {
            panel.split.enabled = true;
            let overrides = material_entities(app)
                .into_iter()
                .filter_map(|(entity, _)| {
                    let material = app.world.get::<&ParallaxOcclusionMaterial>(entity).ok()?;
                    Some((
                        entity,
                        ParallaxOcclusionMaterial {
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
        let orbit = active_camera_transform(&app.world)
            .map(|camera| OrbitCamera::from_transform(&camera, loaded.focus_distance));
        Self {
            egui: egui::Context::default(),
            on_window: None,
            output: None,
            pending: None,
            panel,
            orbit,
            scene_label: loaded.label,
            autosave: Autosave::new(state_path, tuned.clone()),
            tuned,
        }
    }

    /// Follows a scene opened from the panel: its label keys the tuned values, and the orbit
    /// starts from its camera.
    fn scene_opened(&mut self, app: &mut App, loaded: super::app_state::LoadedScene) {
        self.scene_label = loaded.label;
        self.panel.messages.extend(loaded.messages);
        restore_tuned(app, &self.scene_label, &self.tuned);
        self.orbit = active_camera_transform(&app.world)
            .map(|camera| OrbitCamera::from_transform(&camera, loaded.focus_distance));
    }

    /// Records the materials' values and writes them if they changed (at most once a second,
    /// unless `force`).
    fn save_tuned(&mut self, app: &App, force: bool) -> Result<()> {
        record_tuned(app, &self.scene_label, &mut self.tuned);
        self.autosave
            .maybe_write(&self.tuned, Instant::now(), force)
            .map_err(|error| anyhow!("writing {}: {error:#}", self.autosave.path().display()))
    }

    /// Adds `message` to the panel's unless it is there already, up to [`MOST_MESSAGES`] (a
    /// failure whose text changes every frame must not grow the panel); later ones go to the
    /// log.
    fn say_once(&mut self, message: String) {
        say_once(&mut self.panel.messages, message);
    }
}

impl WindowOverlay for SandboxOverlay {
    // egui-wgpu writes gamma-encoded pixels itself.
    fn encodes_srgb(&self) -> bool {
        true
    }

    fn opened(
        &mut self,
        app: &mut App,
        window: &Arc<Window>,
        gpu: &GpuContext,
        format: wgpu::TextureFormat,
    ) -> Result<(), BoxedError> {
        let target = app
            .resources
            .get::<RenderTarget>()
            .ok_or("the render plugin made no render target")?;
        // After a replaced device, egui starts over, so that its textures (the fonts) are sent
        // to the new painter again.
        if self.on_window.is_some() {
            self.egui = egui::Context::default();
            self.pending = None;
        }
        let egui_input = egui_winit::State::new(
            self.egui.clone(),
            egui::ViewportId::ROOT,
            window,
            Some(window.scale_factor() as f32),
            None,
            Some(gpu.device.limits().max_texture_dimension_2d as usize),
        );
        self.on_window = Some(OnWindow {
            painter: EguiPainter::new(gpu, format, target),
            egui_input,
        });
        Ok(())
    }

    fn window_event(&mut self, window: &Window, event: &WindowEvent) -> bool {
        self.on_window
            .as_mut()
            .is_some_and(|on_window| on_window.egui_input.on_window_event(window, event).consumed)
    }

    fn before_update(&mut self, app: &mut App, window: &Window) -> Option<ScreenRect> {
        if let Some(ScreenshotSaved(saved)) = app.resources.remove::<ScreenshotSaved>() {
            self.panel.messages.retain(|m| !m.starts_with("screenshot"));
            self.panel.messages.push(match saved {
                Ok(path) => format!("screenshot saved to {}", path.display()),
                Err(error) => format!("screenshot failed: {error}"),
            });
        }
        let on_window = self.on_window.as_mut()?;
        let raw_input = on_window.egui_input.take_egui_input(window);
        let mut viewport = None;
        let mut camera_input = CameraInput::default();
        let mut click = None;
        let split_texture = on_window.painter.split_texture;
        let panel = &mut self.panel;
        let output = self.egui.run_ui(raw_input, |ui| {
            side_panel(ui, app, panel);
            let wipe = panel.split.enabled.then_some(panel.split.wipe);
            CentralPanel::default()
                .frame(egui::Frame::NONE)
                .show(ui, |ui| {
                    // The runner presents the scene here, under the panels.
                    let rect = ui.available_rect_before_wrap();
                    let response = ui.allocate_rect(rect, Sense::click_and_drag());
                    viewport = Some(rect * ui.ctx().pixels_per_point());
                    if let Some(wipe) = wipe {
                        paint_split(ui, response.rect, split_texture, wipe);
                    }
                    camera_input = from_viewport(ui, &response);
                    click = clicked_pixel(&response, ui.ctx().pixels_per_point());
                });
        });
        on_window
            .egui_input
            .handle_platform_output(window, output.platform_output.clone());
        self.output = Some(output);
        if let Some(loaded) = self.panel.opened.take() {
            self.scene_opened(app, loaded);
        }
        if let Some((viewport, pixel)) = click {
            select_clicked(app, &mut self.panel, viewport, pixel);
        }
        if let Some(orbit) = &mut self.orbit
            && !camera_input.is_idle()
        {
            orbit.apply(&camera_input);
            write_to_camera(&mut app.world, orbit);
        }
        if std::mem::take(&mut self.panel.screenshot_requested) {
            let path = PathBuf::from(&self.panel.screenshot_path);
            app.insert_resource(ScreenshotRequest(path));
        }
        let rect = viewport?;
        Some(ScreenRect {
            x: rect.min.x.round().max(0.0) as u32,
            y: rect.min.y.round().max(0.0) as u32,
            width: rect.width().round().max(0.0) as u32,
            height: rect.height().round().max(0.0) as u32,
        })
    }

    fn after_update(&mut self, app: &mut App, failure: Option<&str>) {
        let dt = app.resources.get::<Time>().map_or(0.0, Time::delta_secs);
        self.panel.frame_times.push(dt);
        if self.panel.spin_selected
            && let Some(entity) = self.panel.selected
        {
            spin(&mut app.world, entity, dt.min(0.1));
        }
        // Keep the window (and the tuned values) alive; say what failed once.
        if let Some(failure) = failure {
            self.say_once(format!("updating the scene: {failure}"));
        } else if let Err(failure) = catching_panics(|| pom::render_split_view(app)) {
            self.say_once(failure.to_string());
        }
        if let Err(error) = self.save_tuned(app, false) {
            self.say_once(format!("autosave failed: {error:#}"));
        }
        if let Some(output) = self.output.take() {
            self.pending = Some(PendingPaint {
                paint_jobs: self.egui.tessellate(output.shapes, output.pixels_per_point),
                textures: output.textures_delta,
                pixels_per_point: output.pixels_per_point,
            });
        }
    }

    fn draw(
        &mut self,
        app: &mut App,
        gpu: &GpuContext,
        encoder: &mut wgpu::CommandEncoder,
        view: &wgpu::TextureView,
        (width, height): (u32, u32),
    ) {
        let (Some(on_window), Some(pending)) = (&mut self.on_window, &mut self.pending) else {
            return;
        };
        // The overlay phase, timed like the others; its figure arrives with the next frame's.
        let overlay_time =
            pom::gpu::time_pass(&mut app.resources, pom::RenderPhase::Overlay.name());
        let Some(target) = app.resources.get::<RenderTarget>() else {
            return;
        };
        let split = app
            .resources
            .get::<SplitView>()
            .and_then(|split| split.target.as_ref())
            .unwrap_or(target);
        on_window.painter.paint(
            gpu,
            (target, split),
            EguiFrame {
                paint_jobs: &pending.paint_jobs,
                textures: &mut pending.textures,
                screen: ScreenDescriptor {
                    size_in_pixels: [width, height],
                    pixels_per_point: pending.pixels_per_point,
                },
            },
            (encoder, view),
            overlay_time.as_ref(),
        );
    }

    fn exiting(&mut self, app: &mut App) {
        if let Err(error) = self.save_tuned(app, true) {
            log::warn!("{error:#}");
        }
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

#[cfg(test)]
mod tests {
    use pom::{Assets, Camera, Mesh, TransformPlugin};

    use super::*;

    #[test]
    fn a_message_is_said_once_and_the_panel_lists_a_bounded_number() {
        let mut messages = Vec::new();
        say_once(&mut messages, "the same".into());
        say_once(&mut messages, "the same".into());
        assert_eq!(messages, ["the same"]);
        // A failure whose text changes every frame.
        for frame in 0..1000 {
            say_once(&mut messages, format!("frame {frame} failed"));
        }
        assert_eq!(messages.len(), MOST_MESSAGES);
        assert_eq!(messages[MOST_MESSAGES - 1], MORE_MESSAGES);
    }

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
