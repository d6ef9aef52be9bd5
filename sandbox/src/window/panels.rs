//! The side panel: the list of parallax materials, the editor of the selected one, presets,
//! lights, spin and the screenshot button. It works on a `pom::App` and needs no window or GPU,
//! so egui_kittest can drive it.

use egui::scroll_area::ScrollBarVisibility;
use egui::style::ScrollStyle;
use egui::{Color32, Panel, ScrollArea, Ui};
use pom::hecs::Entity;
use pom::{App, ParallaxOcclusionMaterial};

use super::app_state::{LoadedScene, material_entities};
use super::display_control::display_controls;
use super::environment_control::EnvironmentControls;
use super::file_browser::FileBrowser;
use super::frame_timing::{FrameTimes, GpuTimingSource, gpu_pass_rows};
use super::light_control::{LightControls, point_controls, spot_controls};
use super::material_editor::edit_material;
use super::presets::PresetControls;
use super::render_path_control::render_path_controls;
use super::scene_open::{OpenRequest, open_request, request_for_dropped};
use super::shader_status::shader_reload_status;
use super::split_controls::SplitControls;

/// Default file of the screenshot button.
pub const DEFAULT_SCREENSHOT_PATH: &str = "target/sandbox-screenshot.png";

/// Everything the panel remembers between frames.
#[derive(Debug)]
pub struct PanelState {
    /// The material entity being edited.
    pub selected: Option<Entity>,
    /// Preset path and last outcome.
    pub presets: PresetControls,
    /// Which light the light controls move.
    pub lights: LightControls,
    /// The environment's source, time of day and parameters.
    pub environment: EnvironmentControls,
    /// Turn the selected entity a little every frame.
    pub spin_selected: bool,
    /// Where the screenshot button writes.
    pub screenshot_path: String,
    /// Set by the screenshot button; the window takes the picture and clears it.
    pub screenshot_requested: bool,
    /// Problems and results to show at the top (scene errors, autosave, screenshots).
    pub messages: Vec<String>,
    /// The last frames' CPU times, for the timing graph.
    pub frame_times: FrameTimes,
    /// The split view's switch, wipe and image B.
    pub split: SplitControls,
    /// The file browser of "Open…".
    pub browser: FileBrowser,
    /// Set when another scene was opened; the window takes it to reset its camera and label.
    pub opened: Option<LoadedScene>,
}

impl Default for PanelState {
    fn default() -> Self {
        Self {
            selected: None,
            presets: PresetControls::default(),
            lights: LightControls::default(),
            environment: EnvironmentControls::default(),
            spin_selected: false,
            screenshot_path: DEFAULT_SCREENSHOT_PATH.into(),
            screenshot_requested: false,
            messages: Vec::new(),
            frame_times: FrameTimes::default(),
            split: SplitControls::default(),
            browser: FileBrowser::default(),
            opened: None,
        }
    }
}

/// Width of the side panel when it opens, in points.
pub const PANEL_WIDTH: f32 = 380.0;

/// The side panel on the left of `ui`, as the window shows it.
pub fn side_panel(ui: &mut Ui, app: &mut App, state: &mut PanelState) {
    Panel::left("controls")
        .default_size(PANEL_WIDTH)
        .resizable(true)
        .show(ui, |ui| side_panel_contents(ui, app, state));
}

/// Draws the panel's contents into `ui`, editing `app`'s world directly.
pub fn side_panel_contents(ui: &mut Ui, app: &mut App, state: &mut PanelState) {
    // A solid bar that always shows: a floating one appears only on hover, and nothing else
    // says that the panel goes on below the window's edge.
    ui.spacing_mut().scroll = ScrollStyle::solid();
    ScrollArea::vertical()
        .scroll_bar_visibility(ScrollBarVisibility::AlwaysVisible)
        .show(ui, |ui| {
        ui.heading("POM sandbox");
        for message in &state.messages {
            ui.colored_label(Color32::from_rgb(255, 190, 90), message);
        }
        let mut request = None;
        ui.collapsing("Open…", |ui| request = state.browser.show(ui))
            .header_response
            .on_hover_text("Open a glTF scene or a height/normal/albedo image set; or drop files on the window.");
        let dropped: Vec<std::path::PathBuf> = ui.ctx().input(|input| {
            input.raw.dropped_files.iter().map(|file| file.path().to_path_buf()).collect()
        });
        if !dropped.is_empty() {
            match request_for_dropped(&dropped) {
                Ok(dropped_request) => request = Some(dropped_request),
                Err(error) => report_open_error(state, error),
            }
        }
        if let Some(request) = request {
            open(app, state, &request);
        }
        material_list(ui, app, state);
        ui.separator();
        if let Some(entity) = state.selected {
            selected_material(ui, app, state, entity);
        }
        ui.separator();
        state.split.show(ui, app, state.selected);
        ui.separator();
        ui.collapsing("Light", |ui| {
            state.lights.show(ui, &mut app.world);
            ui.collapsing("Environment", |ui| state.environment.show(ui, app))
                .header_response
                .on_hover_text("The light from all around: the sky, a constant radiance or an .hdr/.exr image.");
        });
        ui.collapsing("Spot lights", |ui| spot_controls(ui, &mut app.world))
            .header_response
            .on_hover_text("Spot lights: intensity in candela, cone angles and shadows.");
        ui.collapsing("Point lights", |ui| point_controls(ui, &mut app.world))
            .header_response
            .on_hover_text("Point lights: their shadows.");
        ui.collapsing("Display", |ui| display_controls(ui, &mut app.world))
            .header_response
            .on_hover_text("Exposure and tonemapping: how scene light maps to the screen.");
        ui.checkbox(&mut state.spin_selected, "spin selected object")
            .on_hover_text("Turns the selected object slowly, to judge the parallax in motion.");
        ui.collapsing("Timing", |ui| {
            render_path_controls(ui, app.resources.get_mut::<pom::render::Renderer>());
            state.frame_times.show(ui);
            let software_driver = app.resources.get::<pom::GpuContext>().is_some_and(|gpu| {
                gpu.adapter_info().device_type == pom::wgpu::DeviceType::Cpu
            });
            let source = GpuTimingSource {
                timings: app.resources.get::<pom::GpuTimings>(),
                software_driver,
            };
            gpu_pass_rows(ui, source);
        });
        shader_reload_status(ui, app);
        ui.separator();
        ui.horizontal(|ui| {
            if ui
                .button("Screenshot")
                .on_hover_text(
                    "Saves the whole window, panels included, as a PNG to the path beside.",
                )
                .clicked()
            {
                state.screenshot_requested = true;
            }
            let label = ui.label("to");
            ui.text_edit_singleline(&mut state.screenshot_path)
                .labelled_by(label.id)
                .on_hover_text("The PNG file the screenshot button writes.");
        });
        ui.label("Drag: orbit · right/middle drag: pan · wheel: zoom · arrows / WASD: move")
            .on_hover_text("Mouse over the 3D view; keys work when no text field is being edited.");
    });
}

/// Opens `request` in place of the current scene, or shows why it could not be opened.
fn open(app: &mut App, state: &mut PanelState, request: &OpenRequest) {
    match open_request(app, request) {
        Ok(loaded) => {
            state.browser.error = None;
            state.messages.retain(|m| !m.starts_with("could not open"));
            state.selected = None;
            if let Some(split) = app.resources.get_mut::<pom::SplitView>() {
                split.overrides.clear();
            }
            state.opened = Some(loaded);
        }
        Err(error) => report_open_error(state, error),
    }
}

fn report_open_error(state: &mut PanelState, error: String) {
    let message = format!("could not open: {error}");
    state.messages.retain(|m| !m.starts_with("could not open"));
    state.messages.push(message.clone());
    state.browser.error = Some(message);
}

fn material_list(ui: &mut Ui, app: &App, state: &mut PanelState) {
    let materials = material_entities(app);
    if materials.is_empty() {
        ui.label("This scene has no parallax material.");
        state.selected = None;
        return;
    }
    if state
        .selected
        .is_none_or(|selected| !materials.iter().any(|(e, _)| *e == selected))
    {
        state.selected = materials.first().map(|(entity, _)| *entity);
    }
    // One wrapped row, not a line each: the editor below stays in view.
    ui.horizontal_wrapped(|ui| {
        ui.label("Parallax materials")
            .on_hover_text("Pick the object whose material the controls below edit.");
        for (entity, name) in materials {
            ui.selectable_value(&mut state.selected, Some(entity), name);
        }
    });
}

fn selected_material(ui: &mut Ui, app: &mut App, state: &mut PanelState, entity: Entity) {
    let Ok(mut material) = app.world.get::<&mut ParallaxOcclusionMaterial>(entity) else {
        return;
    };
    // Edit a copy and write it back only when something changed, so an untouched panel never
    // marks the component as modified.
    let mut edited = material.clone();
    let mut changed = edit_material(ui, &mut edited);
    ui.separator();
    changed |= state.presets.show(
        ui,
        &mut edited,
        app.resources.get_mut::<pom::Assets<pom::Image>>(),
    );
    if ui
        .button("Reset to defaults")
        .on_hover_text("Puts every parameter back to Tatarchuk's defaults (textures stay).")
        .clicked()
    {
        edited.apply_preset(&pom::PomPreset::default());
        changed = true;
    }
    if changed {
        *material = edited;
    }
}
