//! The environment controls: which environment lights the scene (off, the sky, a constant
//! radiance, or an equirectangular `.hdr` / `.exr` image opened by its path), the sky's time of
//! day (which turns the scene's first directional light, the sky's sun), and the environment's
//! parameters, a row each from their declared table, written into the app's
//! `EnvironmentLight` resource.

use egui::{ComboBox, Slider, Ui};
use glam::Vec3;
use pom::{
    App, DirectionalLight, EnvironmentLight, EnvironmentSettings, EnvironmentSource, Transform,
};

use super::material_editor::parameter_row;

/// The sources the panel offers, by name.
const KINDS: [&str; 4] = ["off", "sky", "uniform", "file"];

/// What the environment controls keep between frames.
#[derive(Clone, Debug)]
pub struct EnvironmentControls {
    /// The file to open.
    pub path: String,
    /// A uniform environment's grey radiance, cd/m².
    pub radiance: f32,
    /// The hour of the sky's sun, 5 to 19.
    pub hour: f32,
    /// What the last open said, if it failed.
    pub message: Option<String>,
}

impl Default for EnvironmentControls {
    fn default() -> Self {
        Self {
            path: String::new(),
            radiance: 5_000.0,
            hour: 10.0,
            message: None,
        }
    }
}

/// The panel's name for `source`.
fn kind_of(source: &EnvironmentSource) -> &'static str {
    match source {
        EnvironmentSource::Off => "off",
        EnvironmentSource::Sky(_) => "sky",
        EnvironmentSource::Uniform(_) => "uniform",
        _ => "file",
    }
}

/// The direction towards the sun at `hour` (solar time): rising in the east (+X) at 6, highest
/// (60°) in the south (−Z) at noon, setting in the west at 18.
pub fn sun_at(hour: f32) -> Vec3 {
    let day = (hour - 6.0) / 12.0 * std::f32::consts::PI;
    let elevation = 60f32.to_radians() * day.sin();
    let across = Vec3::new(day.cos(), 0.0, -day.sin());
    (across * elevation.cos() + Vec3::Y * elevation.sin()).normalize()
}

impl EnvironmentControls {
    /// Draws the controls and writes what changed into `app`.
    pub fn show(&mut self, ui: &mut Ui, app: &mut App) {
        let mut light = app
            .resources
            .get::<EnvironmentLight>()
            .cloned()
            .unwrap_or_default();
        let mut changed = false;
        let mut kind = kind_of(&light.source);
        ComboBox::from_label("environment")
            .selected_text(kind)
            .show_ui(ui, |ui| {
                for choice in KINDS {
                    changed |= ui.selectable_value(&mut kind, choice, choice).changed();
                }
            });
        if changed {
            light.source = match kind {
                "sky" => EnvironmentSource::Sky(pom::Sky::default()),
                "uniform" => EnvironmentSource::Uniform([self.radiance; 3]),
                "file" => self.open().unwrap_or(EnvironmentSource::Off),
                _ => EnvironmentSource::Off,
            };
        }
        match kind {
            "sky" => self.time_of_day(ui, app),
            "uniform" => {
                let slider = Slider::new(&mut self.radiance, 0.0..=50_000.0)
                    .logarithmic(true)
                    .text("radiance")
                    .suffix(" cd/m²");
                if ui.add(slider).changed() {
                    light.source = EnvironmentSource::Uniform([self.radiance; 3]);
                    changed = true;
                }
            }
            _ => {}
        }
        ui.horizontal(|ui| {
            ui.text_edit_singleline(&mut self.path)
                .on_hover_text("An equirectangular .hdr or .exr image.");
            if ui.button("open environment").clicked()
                && let Some(source) = self.open()
            {
                light.source = source;
                changed = true;
            }
        });
        if let Some(message) = &self.message {
            ui.colored_label(egui::Color32::from_rgb(255, 190, 90), message);
        }
        let settings = light.settings;
        for param in EnvironmentSettings::PARAMETERS {
            parameter_row(ui, param, &mut light.settings);
        }
        if changed || light.settings != settings {
            app.insert_resource(light);
        }
    }

    /// The image at the path box, or `None` with the reason kept for the panel.
    fn open(&mut self) -> Option<EnvironmentSource> {
        match EnvironmentLight::from_file(self.path.trim()) {
            Ok(light) => {
                self.message = None;
                Some(light.source)
            }
            Err(error) => {
                self.message = Some(error.to_string());
                None
            }
        }
    }

    /// The time-of-day slider, which turns the scene's first directional light.
    fn time_of_day(&mut self, ui: &mut Ui, app: &mut App) {
        let slider = Slider::new(&mut self.hour, 5.0..=19.0)
            .text("time of day")
            .suffix(" h");
        if !ui
            .add(slider)
            .on_hover_text("Moves the scene's sun (its first directional light).")
            .changed()
        {
            return;
        }
        let sun = sun_at(self.hour);
        let suns = app.world.query_mut::<(&DirectionalLight, &mut Transform)>();
        if let Some((_, transform)) = suns.into_iter().next() {
            let position = transform.translation;
            *transform = Transform::from_translation(position).looking_at(position - sun, Vec3::Y);
        }
    }
}
