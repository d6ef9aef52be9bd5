//! Orbit / pan / zoom around a target point, driven by the mouse over the viewport and by keys,
//! applied by rewriting the active camera entity's `Transform`.

use egui::{Key, PointerButton, Response, Ui, Vec2};
use glam::Vec3;
use pom::hecs::World;
use pom::{Camera, Transform};

/// Radians of orbit per point of mouse drag.
const ORBIT_PER_POINT: f32 = 0.008;
/// Radians of orbit per second while an arrow key is held.
const ORBIT_PER_SECOND: f32 = 1.2;
/// Fraction of the distance moved per second while W/A/S/D is held.
const WALK_PER_SECOND: f32 = 0.8;
/// Keeps the camera off the poles, where "up" stops being defined.
const MAX_PITCH: f32 = 1.5;
/// Nearest and farthest the camera gets to its target.
const DISTANCE_RANGE: (f32, f32) = (0.05, 500.0);

/// Where the camera is, as angles and a distance around the point it looks at.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OrbitCamera {
    /// The point looked at.
    pub target: Vec3,
    /// Radians around +Y; 0 puts the camera on the +Z side of the target.
    pub yaw: f32,
    /// Radians above the horizon.
    pub pitch: f32,
    /// From the camera to the target.
    pub distance: f32,
}

/// What the user asked for this frame.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct CameraInput {
    /// Orbit drag, in points.
    pub orbit: Vec2,
    /// Pan drag, in points.
    pub pan: Vec2,
    /// Wheel scroll, in points (positive = towards the target).
    pub zoom: f32,
    /// Arrow keys: x = right − left, y = up − down, scaled by the frame time.
    pub orbit_keys: Vec2,
    /// W/A/S/D: x = right − left, y = forward − back, scaled by the frame time.
    pub walk_keys: Vec2,
}

impl CameraInput {
    /// Reads the mouse over `viewport` and, when no text field has the keyboard, the keys.
    pub fn from_viewport(ui: &Ui, viewport: &Response) -> Self {
        let mut input = Self::default();
        if viewport.dragged_by(PointerButton::Primary) {
            input.orbit = viewport.drag_delta();
        }
        if viewport.dragged_by(PointerButton::Secondary)
            || viewport.dragged_by(PointerButton::Middle)
        {
            input.pan = viewport.drag_delta();
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
                input.orbit_keys = Vec2::new(
                    axis(&[Key::ArrowRight], &[Key::ArrowLeft]),
                    axis(&[Key::ArrowUp], &[Key::ArrowDown]),
                ) * dt;
                input.walk_keys =
                    Vec2::new(axis(&[Key::D], &[Key::A]), axis(&[Key::W], &[Key::S])) * dt;
            });
        }
        input
    }

    /// Whether anything moves.
    pub fn is_idle(&self) -> bool {
        *self == Self::default()
    }
}

impl OrbitCamera {
    /// The orbit that reproduces `transform`, looking at the point `focus_distance` ahead.
    pub fn from_transform(transform: &Transform, focus_distance: f32) -> Self {
        let forward = transform.rotation * Vec3::NEG_Z;
        let distance = focus_distance.clamp(DISTANCE_RANGE.0, DISTANCE_RANGE.1);
        let back = -forward;
        Self {
            target: transform.translation + forward * distance,
            yaw: back.x.atan2(back.z),
            pitch: back.y.clamp(-1.0, 1.0).asin().clamp(-MAX_PITCH, MAX_PITCH),
            distance,
        }
    }

    /// The camera's transform.
    pub fn transform(&self) -> Transform {
        let back = Vec3::new(
            self.pitch.cos() * self.yaw.sin(),
            self.pitch.sin(),
            self.pitch.cos() * self.yaw.cos(),
        );
        Transform::from_translation(self.target + back * self.distance)
            .looking_at(self.target, Vec3::Y)
    }

    /// Applies one frame of input.
    pub fn apply(&mut self, input: &CameraInput) {
        self.yaw -= input.orbit.x * ORBIT_PER_POINT + input.orbit_keys.x * ORBIT_PER_SECOND;
        self.pitch =
            (self.pitch + input.orbit.y * ORBIT_PER_POINT + input.orbit_keys.y * ORBIT_PER_SECOND)
                .clamp(-MAX_PITCH, MAX_PITCH);
        let rotation = self.transform().rotation;
        let (right, up) = (rotation * Vec3::X, rotation * Vec3::Y);
        // A drag of the viewport's height moves the target about one distance: the scene
        // follows the mouse whatever the zoom.
        let pan_scale = self.distance * 0.0025;
        self.target += (-right * input.pan.x + up * input.pan.y) * pan_scale;
        let flat_forward = Vec3::new(-self.yaw.sin(), 0.0, -self.yaw.cos());
        let flat_right = Vec3::new(self.yaw.cos(), 0.0, -self.yaw.sin());
        self.target += (flat_right * input.walk_keys.x + flat_forward * input.walk_keys.y)
            * self.distance
            * WALK_PER_SECOND;
        self.distance =
            (self.distance * (-input.zoom * 0.002).exp()).clamp(DISTANCE_RANGE.0, DISTANCE_RANGE.1);
    }
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_orbit_reproduces_the_transform_it_came_from() {
        let start =
            Transform::from_xyz(3.0, 2.0, 4.0).looking_at(Vec3::new(0.5, 0.0, 0.0), Vec3::Y);
        let orbit = OrbitCamera::from_transform(&start, 5.0);
        let again = orbit.transform();
        assert!(again.translation.abs_diff_eq(start.translation, 1e-4));
        assert!((again.rotation * Vec3::NEG_Z).abs_diff_eq(start.rotation * Vec3::NEG_Z, 1e-4));
    }

    #[test]
    fn zooming_in_moves_closer_and_orbiting_keeps_the_distance() {
        let mut orbit = OrbitCamera {
            target: Vec3::ZERO,
            yaw: 0.0,
            pitch: 0.3,
            distance: 4.0,
        };
        orbit.apply(&CameraInput {
            zoom: 100.0,
            ..Default::default()
        });
        assert!(orbit.distance < 4.0);
        let distance = orbit.distance;
        orbit.apply(&CameraInput {
            orbit: Vec2::new(40.0, 10.0),
            ..Default::default()
        });
        let position = orbit.transform().translation;
        assert!((position.length() - distance).abs() < 1e-4);
    }
}
