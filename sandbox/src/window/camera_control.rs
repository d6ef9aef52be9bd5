//! The sandbox's camera: pom's orbit camera (`pom::window::OrbitCamera`) driven by the mouse
//! over the egui viewport and by keys, applied by rewriting the active camera entity's
//! `Transform`.

use egui::{Key, PointerButton, Response, Ui};
use pom::hecs::World;
use pom::window::{CameraInput, OrbitCamera};
use pom::{Camera, Transform};

fn to_glam(v: egui::Vec2) -> glam::Vec2 {
    glam::Vec2::new(v.x, v.y)
}

/// The camera input of the mouse over `viewport` (in points, which the orbit reads as pixels)
/// and, when no text field has the keyboard, of the keys.
pub fn from_viewport(ui: &Ui, viewport: &Response) -> CameraInput {
    let mut input = CameraInput::default();
    if viewport.dragged_by(PointerButton::Primary) {
        input.orbit = to_glam(viewport.drag_delta());
    }
    if viewport.dragged_by(PointerButton::Secondary) || viewport.dragged_by(PointerButton::Middle) {
        input.pan = to_glam(viewport.drag_delta());
    }
    if viewport.hovered() {
        input.zoom = ui.input(|i| i.smooth_scroll_delta.y);
    }
    if !ui.ctx().egui_wants_keyboard_input() {
        ui.input(|i| {
            let axis = |plus: &[Key], minus: &[Key]| {
                let held = |keys: &[Key]| keys.iter().any(|key| i.key_down(*key));
                f32::from(u8::from(held(plus))) - f32::from(u8::from(held(minus)))
            };
            let dt = i.stable_dt.min(0.1);
            input.orbit_keys = glam::Vec2::new(
                axis(&[Key::ArrowRight], &[Key::ArrowLeft]),
                axis(&[Key::ArrowUp], &[Key::ArrowDown]),
            ) * dt;
            input.walk_keys =
                glam::Vec2::new(axis(&[Key::D], &[Key::A]), axis(&[Key::W], &[Key::S])) * dt;
        });
    }
    input
}

/// The active camera's transform, for starting an orbit from it.
pub fn active_camera_transform(world: &World) -> Option<Transform> {
    world
        .query::<(&Camera, &Transform)>()
        .iter()
        .find(|(camera, _)| camera.active)
        .map(|(_, transform)| *transform)
}

/// Writes the orbit into every active camera's transform.
pub fn write_to_camera(world: &mut World, orbit: &OrbitCamera) {
    for (camera, transform) in world.query_mut::<(&Camera, &mut Transform)>() {
        if camera.active {
            *transform = orbit.transform();
        }
    }
}
