//! The display controls: the active camera's exposure (EV100), tonemapping operator and
//! anti-aliasing (with the parameters of TAA or FXAA, a row each from their declared tables as a
//! material's), written into its `Exposure`, `Tonemapping`, `AntiAliasing`,
//! `TemporalAntiAliasing` and `FastApproximateAntiAliasing` components, and kept with the tuned
//! state.

use egui::{Slider, Ui};
use pom::hecs::World;
use pom::{
    AntiAliasing, Camera, Exposure, FastApproximateAntiAliasing, TemporalAntiAliasing, Tonemapping,
};
use serde::{Deserialize, Serialize};

use super::material_editor::{choose, parameter_row};

/// What the state file keeps of the display controls.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct DisplayState {
    /// Exposure in EV100.
    pub ev100: f32,
    /// The tonemapping operator.
    pub tonemap: Tonemapping,
    /// Anti-aliasing (TAA, the window's default, in state files from before it).
    #[serde(default = "window_default")]
    pub aa: AntiAliasing,
    /// TAA's parameters.
    #[serde(default)]
    pub taa: TemporalAntiAliasing,
    /// FXAA's parameters.
    #[serde(default)]
    pub fxaa: FastApproximateAntiAliasing,
}

/// What a window's camera without an `AntiAliasing` runs (`WindowPlugin`'s resource).
fn window_default() -> AntiAliasing {
    AntiAliasing::Taa
}

/// The active camera's exposure and operator (their defaults where it has none).
pub fn active_display(world: &World) -> Option<DisplayState> {
    world
        .query::<(
            &Camera,
            Option<&Exposure>,
            Option<&Tonemapping>,
            Option<&AntiAliasing>,
            Option<&TemporalAntiAliasing>,
            Option<&FastApproximateAntiAliasing>,
        )>()
        .iter()
        .find(|(camera, ..)| camera.active)
        .map(|(_, exposure, tonemap, aa, taa, fxaa)| DisplayState {
            ev100: exposure.copied().unwrap_or_default().ev100,
            tonemap: tonemap.copied().unwrap_or_default(),
            aa: aa.copied().unwrap_or_else(window_default),
            taa: taa.copied().unwrap_or_default(),
            fxaa: fxaa.copied().unwrap_or_default(),
        })
}

/// Puts `state` on the active cameras.
pub fn apply_display(world: &mut World, state: DisplayState) {
    pom::set_camera_display_mapping(world, Exposure { ev100: state.ev100 }, state.tonemap);
    pom::set_camera_anti_aliasing(world, state.aa, state.taa);
    pom::set_camera_fxaa(world, state.fxaa);
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
    choose(ui, "anti-aliasing", &mut state.aa);
    match state.aa {
        AntiAliasing::Taa => {
            for param in TemporalAntiAliasing::PARAMETERS {
                parameter_row(ui, param, &mut state.taa);
            }
        }
        AntiAliasing::Fxaa => {
            for param in FastApproximateAntiAliasing::PARAMETERS {
                parameter_row(ui, param, &mut state.fxaa);
            }
        }
        _ => {}
    }
    if state != before {
        apply_display(world, state);
    }
}
