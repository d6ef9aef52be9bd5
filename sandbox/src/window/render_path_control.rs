//! The render path in the Timing panel: a choice of forward, deferred or auto, which the
//! renderer takes from the next frame, and the path the last frame ran (with the reason when a
//! deferred request ran forward).

use egui::{ComboBox, Ui};
use pom::RenderPath;
use pom::render::{DeferredUnavailable, Renderer};

/// The status line: the path the last frame ran, and why it ran forward where the renderer was
/// asked for deferred (`unavailable`, from [`Renderer::deferred_unavailable`]).
pub fn path_status(runs_deferred: bool, unavailable: Option<DeferredUnavailable>) -> String {
    match (runs_deferred, unavailable) {
        (true, _) => "path: deferred".to_owned(),
        (false, None) => "path: forward".to_owned(),
        (false, Some(reason)) => format!("path: forward (deferred unavailable: {reason})"),
    }
}

/// Shows the path choice, which sets [`Renderer::set_path`], and the path that runs; without a
/// renderer (before the GPU starts) says there is none.
pub fn render_path_controls(ui: &mut Ui, renderer: Option<&mut Renderer>) {
    let Some(renderer) = renderer else {
        ui.label("path: n/a (no renderer)");
        return;
    };
    let mut path = renderer.path();
    ComboBox::from_label("render path")
        .selected_text(path.name())
        .show_ui(ui, |ui| {
            for choice in RenderPath::ALL {
                ui.selectable_value(&mut path, choice, choice.name());
            }
        })
        .response
        .on_hover_text(
            "Where opaque surfaces shade: forward in fragment shaders, deferred in compute from \
             a visibility buffer, auto deferred on a GPU and forward on a software driver. \
             Takes effect from the next frame.",
        );
    if path != renderer.path() {
        renderer.set_path(path);
    }
    ui.label(path_status(
        renderer.runs_deferred(),
        renderer.deferred_unavailable(),
    ))
    .on_hover_text(
        "The path the last frame ran. Deferred runs forward where the adapter or a material \
         cannot run it; the reason is shown.",
    );
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_status_names_the_path_that_ran_and_why_deferred_did_not() {
        assert_eq!(path_status(true, None), "path: deferred");
        assert_eq!(path_status(false, None), "path: forward");
        assert_eq!(
            path_status(false, Some(DeferredUnavailable::NoDepthPrepass)),
            "path: forward (deferred unavailable: the depth prepass is off \
             (RenderPlugin::depth_prepass))"
        );
    }
}
