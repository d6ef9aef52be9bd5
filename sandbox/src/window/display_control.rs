//! The display controls: the active camera's exposure (EV100) and tonemapping operator,
//! written into its `Exposure` and `Tonemapping` components, and kept with the tuned state.

use egui::{Slider, Ui};
use pom::hecs::World;
use pom::{Camera, Exposure, Tonemapping};
use serde::{Deserialize, Serialize};

use super::material_editor::choose;

/// What the state file keeps of the display controls.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct DisplayState {
    /// Exposure in EV100.
    pub ev100: f32,
    /// The tonemapping operator.
    pub tonemap: Tonemapping,
}

/// The active camera's exposure and operator (their defaults where it has none).
pub fn active_display(world: &World) -> Option<DisplayState> {
    world
        .query::<(&Camera, Option<&Exposure>, Option<&Tonemapping>)>()
        .iter()
        .find(|(camera, _, _)| camera.active)
        .map(|(_, exposure, tonemap)| DisplayState {
            ev100: exposure.copied().unwrap_or_default().ev100,
            tonemap: tonemap.copied().unwrap_or_default(),
        })
}

/// Puts `state` on the active cameras.
pub fn apply_display(world: &mut World, state: DisplayState) {
    pom::set_camera_display_mapping(world, Exposure { ev100: state.ev100 }, state.tonemap);
}

/// Shows the exposure slider and the operator choice; edits the active camera.
pub fn display_controls(ui: &mut Ui, world: &mut World) {
    let Some(mut state) = active_display(world) else {
        ui.label("no active camera");
        return;
    };
    let before = state;
    ui.add(
        Slider::new(&mut state.ev100, Exposure::RANGE)
            .text("exposure (EV100)")
            .step_by(0.1),
    )
    .on_hover_text(
        "Higher is darker: +1 halves the light. The default, 14.7 (daylight), shows white in a 100,000 lux sun as 1.",
    );
    if ui
        .button("default exposure")
        .on_hover_text("Back to 14.7 EV100.")
        .clicked()
    {
        state.ev100 = Exposure::DEFAULT_EV100;
    }
    choose(ui, "tonemapping", &mut state.tonemap);
    if state != before {
        apply_display(world, state);
    }
}
