//! The shader hot-reload line of the panel: what is watched, how many reloads, the last error.

use egui::{Color32, Ui};
use pom::{App, ShaderReloadStatus};

/// Shows the plugin's [`ShaderReloadStatus`], or that hot reload is off.
pub fn shader_reload_status(ui: &mut Ui, app: &App) {
    let Some(status) = app.resources.get::<ShaderReloadStatus>() else {
        ui.label("Shader hot reload: off (the plugin's sources are not on this machine)");
        return;
    };
    ui.label(format!(
        "Shader hot reload: {} reload{}",
        status.reloads,
        if status.reloads == 1 { "" } else { "s" }
    ))
    .on_hover_text(format!(
        "Editing a WGSL file under {} recompiles the shaders; on an error the last good \
         pipeline stays.",
        status.source_dir.display()
    ));
    if let Some(error) = &status.error {
        ui.colored_label(
            Color32::from_rgb(255, 110, 90),
            format!("shader error (previous pipeline kept): {error}"),
        );
    }
}
