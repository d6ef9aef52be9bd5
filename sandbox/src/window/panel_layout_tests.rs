//! The side panel's layout at the window's opening size: what an artist tunes all the time
//! (the essential parameters, presets, light, display, timing, the screenshot button) is in
//! view without scrolling, the other parameter groups are one click away, and values show
//! their units. Laid out by egui_kittest as the window lays it out, without a window or GPU.

use egui_kittest::Harness;
use egui_kittest::kittest::{Queryable, by};
use pom::material::ParamGroup;
use pom::{App, Name, ParallaxOcclusionMaterial};

use super::panels::{PanelState, side_panel};
use super::window_app::INITIAL_SIZE;

struct Fixture {
    app: App,
    panel: PanelState,
}

/// The panel beside an empty viewport at the window's opening size, over as many materials as
/// the street corner has (each takes room in the list at the top).
fn window_sized_panel() -> Harness<'static, Fixture> {
    let mut app = App::new();
    for name in ["floor", "wall", "sign", "doormat", "crate"] {
        app.world
            .spawn((ParallaxOcclusionMaterial::default(), Name(name.into())));
    }
    let fixture = Fixture {
        app,
        panel: PanelState::default(),
    };
    let (width, height) = INITIAL_SIZE;
    let mut harness = Harness::builder()
        .with_size(egui::vec2(width as f32, height as f32))
        .build_ui_state(
            |ui, fixture: &mut Fixture| side_panel(ui, &mut fixture.app, &mut fixture.panel),
            fixture,
        );
    harness.run();
    harness
}

/// Whether a widget labelled `label` is laid out (a slider's label and its value are two).
fn shown(harness: &Harness<'_, Fixture>, label: &str) -> bool {
    harness.query_all_by_label(label).next().is_some()
}

/// Asserts that the widgets labelled `label` exist and lie wholly inside the window's height.
fn assert_in_view(harness: &Harness<'_, Fixture>, label: &str) {
    assert!(shown(harness, label), "no widget labelled {label:?}");
    let height = INITIAL_SIZE.1 as f32;
    for node in harness.query_all_by_label(label) {
        let rect = node.rect();
        assert!(
            rect.min.y >= 0.0 && rect.max.y <= height,
            "{label:?} lies at y {}..{}, outside the window's {height} points",
            rect.min.y,
            rect.max.y
        );
    }
}

#[test]
fn the_controls_used_all_the_time_are_in_view_at_1280_by_720() {
    let harness = window_sized_panel();
    for group in ParamGroup::ALL {
        assert_in_view(&harness, group.heading());
    }
    let essential = ParallaxOcclusionMaterial::PARAMETERS
        .iter()
        .filter(|param| param.spec.group == ParamGroup::Essential);
    for param in essential {
        assert_in_view(&harness, &param.label());
    }
    for label in [
        "Preset file",
        "Save preset…",
        "Load preset…",
        "Copy as Rust",
        "Light",
        "Display",
        "Timing",
        "Screenshot",
    ] {
        assert_in_view(&harness, label);
    }
}

#[test]
fn the_essential_group_is_open_and_the_others_closed() {
    let harness = window_sized_panel();
    for param in ParallaxOcclusionMaterial::PARAMETERS {
        assert_eq!(
            shown(&harness, &param.label()),
            param.spec.group == ParamGroup::Essential,
            "{} is in group {:?}",
            param.name,
            param.spec.group
        );
    }
}

#[test]
fn opening_a_group_shows_its_parameters() {
    let mut harness = window_sized_panel();
    assert!(!shown(&harness, "secant steps"));
    harness.get_by_label(ParamGroup::Method.heading()).click();
    harness.run();
    assert!(shown(&harness, "secant steps"));
}

#[test]
fn values_show_their_declared_units() {
    let harness = window_sized_panel();
    let with_units = ParallaxOcclusionMaterial::PARAMETERS
        .iter()
        .filter(|param| param.spec.group == ParamGroup::Essential && !param.spec.unit.is_empty());
    let mut checked = 0;
    for param in with_units {
        let label = param.label();
        // The number beside a slider is a spin button carrying the slider's label.
        let value = harness
            .get(by().role(egui::accesskit::Role::SpinButton).label(&label))
            .value()
            .unwrap_or_default();
        assert!(
            value.ends_with(&format!(" {}", param.spec.unit)),
            "{label} shows {value:?}, without its unit {:?}",
            param.spec.unit
        );
        checked += 1;
    }
    assert!(
        checked >= 2,
        "only {checked} essential parameters have a unit"
    );
}
