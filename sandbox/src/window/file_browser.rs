//! A small file browser inside the panel (no system dialog, so no GTK or portal needed): walk
//! folders, pick a glTF scene, or pick a height map with optional normal and albedo maps.

use std::path::{Path, PathBuf};

use egui::{Color32, ScrollArea, Ui};

use super::scene_open::{ImageSet, OpenRequest, is_image_file, is_scene_file};

/// Most entries listed per folder (a huge folder must not stall the UI).
const MAX_ENTRIES: usize = 500;

/// What the browser remembers between frames.
#[derive(Clone, Debug)]
pub struct FileBrowser {
    /// The folder listed.
    pub dir: PathBuf,
    /// The path typed or clicked last.
    pub path: String,
    /// The image set being put together.
    pub images: ImageSet,
    /// The last problem (unreadable folder, file that would not open).
    pub error: Option<String>,
}

impl Default for FileBrowser {
    fn default() -> Self {
        let dir = std::env::current_dir().unwrap_or_else(|_| PathBuf::from("."));
        Self {
            dir,
            path: String::new(),
            images: ImageSet::default(),
            error: None,
        }
    }
}

impl FileBrowser {
    /// Shows the browser; returns what the user asked to open this frame.
    pub fn show(&mut self, ui: &mut Ui) -> Option<OpenRequest> {
        if let Some(error) = &self.error {
            ui.colored_label(Color32::from_rgb(255, 110, 90), error);
        }
        ui.horizontal(|ui| {
            if ui
                .button("Up")
                .on_hover_text("The parent folder.")
                .clicked()
                && let Some(parent) = self.dir.parent()
            {
                self.dir = parent.to_path_buf();
            }
            ui.label(self.dir.display().to_string());
        });
        self.entries(ui);
        let label = ui.label("file");
        ui.text_edit_singleline(&mut self.path)
            .labelled_by(label.id)
            .on_hover_text("The file to open: click one above, or type its path.");
        let path = PathBuf::from(self.path.trim());
        let mut request = None;
        ui.horizontal_wrapped(|ui| {
            if ui
                .button("Open scene")
                .on_hover_text("Opens this .gltf or .glb file instead of the current scene.")
                .clicked()
            {
                request = Some(OpenRequest::Scene(path.clone()));
            }
            for (name, slot) in [
                ("height", &mut self.images.height),
                ("normal", &mut self.images.normal),
                ("albedo", &mut self.images.albedo),
            ] {
                if ui
                    .button(format!("Use as {name}"))
                    .on_hover_text(format!("This image becomes the set's {name} map."))
                    .clicked()
                {
                    *slot = Some(path.clone());
                }
            }
        });
        for (name, slot) in [
            ("height", &self.images.height),
            ("normal", &self.images.normal),
            ("albedo", &self.images.albedo),
        ] {
            let file = slot
                .as_ref()
                .map_or("—".into(), |p| p.display().to_string());
            ui.label(format!("{name}: {file}"));
        }
        if ui
            .add_enabled(
                self.images.height.is_some(),
                egui::Button::new("Open image set"),
            )
            .on_hover_text("Shows the height map (and the normal and albedo maps) on a plane.")
            .clicked()
        {
            request = Some(OpenRequest::ImageSet(self.images.clone()));
        }
        request
    }

    /// The folder's subfolders and the scenes and images in it, as buttons.
    fn entries(&mut self, ui: &mut Ui) {
        let listed = list_dir(&self.dir);
        let entries = match listed {
            Ok(entries) => entries,
            Err(error) => {
                ui.colored_label(Color32::from_rgb(255, 110, 90), error);
                return;
            }
        };
        ScrollArea::vertical()
            .id_salt("file browser entries")
            .max_height(160.0)
            .show(ui, |ui| {
                for (path, is_dir) in entries {
                    let name = path
                        .file_name()
                        .map_or_else(String::new, |n| n.to_string_lossy().into_owned());
                    let text = if is_dir { format!("{name}/") } else { name };
                    if ui.selectable_label(false, text).clicked() {
                        if is_dir {
                            self.dir = path;
                        } else {
                            self.path = path.display().to_string();
                        }
                    }
                }
            });
    }
}

/// Folders first, then scene and image files, each sorted by name.
fn list_dir(dir: &Path) -> Result<Vec<(PathBuf, bool)>, String> {
    let read = std::fs::read_dir(dir).map_err(|error| format!("{}: {error}", dir.display()))?;
    let mut entries: Vec<(PathBuf, bool)> = read
        .filter_map(Result::ok)
        .map(|entry| (entry.path(), entry.path().is_dir()))
        // Only regular files: a FIFO or a device named like an image is not offered.
        .filter(|(path, is_dir)| {
            *is_dir || (path.is_file() && (is_scene_file(path) || is_image_file(path)))
        })
        .take(MAX_ENTRIES)
        .collect();
    entries.sort_by(|a, b| b.1.cmp(&a.1).then_with(|| a.0.cmp(&b.0)));
    Ok(entries)
}
