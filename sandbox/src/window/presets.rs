//! Save / load a material preset (RON) by path, and copy it as a Rust literal. Errors are shown
//! in the panel; the material is only changed by a load that fully succeeded.

use egui::{Color32, Ui};
use pom::{Assets, Image, ParallaxOcclusionMaterial, PomPreset};

/// Default preset file name offered in the path field.
pub const DEFAULT_PRESET_PATH: &str = "material.ron";

/// The preset controls' state: the path being typed and the outcome of the last action.
#[derive(Debug)]
pub struct PresetControls {
    /// The file the buttons act on.
    pub path: String,
    /// What the last button did, or why it failed.
    pub status: Option<Status>,
}

/// The outcome of the last preset action.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Status {
    /// It worked; the text says what happened.
    Done(String),
    /// It failed; the text says why.
    Failed(String),
}

impl Default for PresetControls {
    fn default() -> Self {
        Self {
            path: DEFAULT_PRESET_PATH.into(),
            status: None,
        }
    }
}

/// The preset at `path` and the layers its files describe (relative to its folder), added to
/// `images`; nothing is added unless all of it loads.
fn load(
    path: &str,
    images: Option<&mut Assets<Image>>,
) -> Result<(PomPreset, Option<pom::ParallaxLayers>), String> {
    let preset = PomPreset::load(path).map_err(|error| error.to_string())?;
    let files = preset
        .read_layer_files_beside(path.as_ref(), pom::files::FileAccess::InsideFolder)
        .map_err(|error| error.to_string())?;
    let layers = match (files, images) {
        (None, _) => None,
        (Some(files), Some(images)) => Some(
            files
                .into_layers(images)
                .map_err(|error| error.to_string())?,
        ),
        (Some(_), None) => return Err("no image store for the preset's layers".into()),
    };
    Ok((preset, layers))
}

impl PresetControls {
    /// Shows the path field and the buttons for `material` (a preset's layer files are added
    /// to `images`); returns whether it changed.
    pub fn show(
        &mut self,
        ui: &mut Ui,
        material: &mut ParallaxOcclusionMaterial,
        images: Option<&mut Assets<Image>>,
    ) -> bool {
        let mut changed = false;
        ui.horizontal(|ui| {
            let label = ui.label("Preset file").on_hover_text(
                "Path of the RON preset file the buttons below save to or load from.",
            );
            ui.text_edit_singleline(&mut self.path)
                .labelled_by(label.id);
        });
        ui.horizontal(|ui| {
            if ui
                .button("Save preset…")
                .on_hover_text("Writes this material's parameters (not its textures) to the file.")
                .clicked()
            {
                self.status = Some(match material.preset().save(&self.path) {
                    Ok(()) => Status::Done(format!("saved {}", self.path)),
                    Err(error) => Status::Failed(format!("could not save: {error}")),
                });
            }
            if ui
                .button("Load preset…")
                .on_hover_text(
                    "Reads the file's parameters into this material (its textures stay).",
                )
                .clicked()
            {
                self.status = Some(match load(&self.path, images) {
                    Ok((preset, layers)) => {
                        if let Some(layers) = layers {
                            material.layers = Some(layers);
                        }
                        material.apply_preset(&preset);
                        changed = true;
                        Status::Done(format!("loaded {}", self.path))
                    }
                    Err(error) => Status::Failed(format!("could not load: {error}")),
                });
            }
            if ui
                .button("Copy as Rust")
                .on_hover_text("Puts this material as a Rust struct literal on the clipboard.")
                .clicked()
            {
                ui.ctx().copy_text(material.preset().to_rust());
                self.status = Some(Status::Done("copied the Rust literal".into()));
            }
        });
        match &self.status {
            Some(Status::Done(text)) => {
                ui.label(text);
            }
            Some(Status::Failed(text)) => {
                ui.colored_label(Color32::from_rgb(255, 110, 100), text);
            }
            None => {}
        }
        changed
    }
}
