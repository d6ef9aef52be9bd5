//! Orbit / pan / zoom around a target point: [`OrbitCamera`] on a camera entity, moved by
//! [`OrbitCameraPlugin`]'s system from the input resources (left drag orbits, right or middle
//! drag pans, the wheel zooms, arrows orbit, W/A/S/D walk the target), or by any other input
//! through [`CameraInput`] (the sandbox feeds it from its egui viewport).

use glam::{Vec2, Vec3};

use super::input::{ButtonInput, KeyCode, MouseButton, MouseMotion, MouseScroll};
use crate::{App, Plugin, Resources, Stage, Time, Transform};

/// Radians of orbit per pixel of mouse drag.
const ORBIT_PER_PIXEL: f32 = 0.008;
/// Radians of orbit per second while an arrow key is held.
const ORBIT_PER_SECOND: f32 = 1.2;
/// Fraction of the distance moved per second while W/A/S/D is held.
const WALK_PER_SECOND: f32 = 0.8;
/// Pixels of zoom one wheel step counts as.
const PIXELS_PER_WHEEL_STEP: f32 = 50.0;
/// Keeps the camera off the poles, where "up" stops being defined.
const MAX_PITCH: f32 = 1.5;
/// Nearest and farthest the camera gets to its target.
const DISTANCE_RANGE: (f32, f32) = (0.05, 500.0);

/// Where a camera is, as angles and a distance around the point it looks at. A component: with
/// [`OrbitCameraPlugin`], the entity's `Transform` follows it.
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

/// What the user asked of the camera this frame.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct CameraInput {
    /// Orbit drag, in pixels.
    pub orbit: Vec2,
    /// Pan drag, in pixels.
    pub pan: Vec2,
    /// Scroll, in pixels (positive = towards the target).
    pub zoom: f32,
    /// Arrow keys: x = right − left, y = up − down, times the frame time in seconds.
    pub orbit_keys: Vec2,
    /// W/A/S/D: x = right − left, y = forward − back, times the frame time in seconds.
    pub walk_keys: Vec2,
}

impl CameraInput {
    /// This frame's camera input from the window's input resources and [`Time`].
    pub fn from_resources(resources: &Resources) -> Self {
        let mut input = Self::default();
        let motion = resources
            .get::<MouseMotion>()
            .map_or(Vec2::ZERO, |m| m.delta);
        if let Some(buttons) = resources.get::<ButtonInput<MouseButton>>() {
            if buttons.pressed(MouseButton::Left) {
                input.orbit = motion;
            } else if buttons.any_pressed([MouseButton::Right, MouseButton::Middle]) {
                input.pan = motion;
            }
        }
        if let Some(scroll) = resources.get::<MouseScroll>() {
            input.zoom = scroll.lines.y * PIXELS_PER_WHEEL_STEP + scroll.pixels.y;
        }
        if let Some(keys) = resources.get::<ButtonInput<KeyCode>>() {
            let axis = |plus: KeyCode, minus: KeyCode| {
                f32::from(u8::from(keys.pressed(plus))) - f32::from(u8::from(keys.pressed(minus)))
            };
            let dt = resources.get::<Time>().map_or(0.0, Time::delta_secs);
            input.orbit_keys = Vec2::new(
                axis(KeyCode::ArrowRight, KeyCode::ArrowLeft),
                axis(KeyCode::ArrowUp, KeyCode::ArrowDown),
            ) * dt;
            input.walk_keys = Vec2::new(
                axis(KeyCode::KeyD, KeyCode::KeyA),
                axis(KeyCode::KeyW, KeyCode::KeyS),
            ) * dt;
        }
        input
    }

    /// Whether nothing moves.
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
        self.yaw -= input.orbit.x * ORBIT_PER_PIXEL + input.orbit_keys.x * ORBIT_PER_SECOND;
        self.pitch =
            (self.pitch + input.orbit.y * ORBIT_PER_PIXEL + input.orbit_keys.y * ORBIT_PER_SECOND)
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

/// Moves every camera that has an [`OrbitCamera`] by the mouse and keys, in
/// [`Stage::Update`]. Needs [`super::WindowPlugin`]'s input resources.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct OrbitCameraPlugin;

impl Plugin for OrbitCameraPlugin {
    fn build(&self, app: &mut App) {
        app.add_system(Stage::Update, orbit_cameras);
    }
}

/// [`OrbitCameraPlugin`]'s system: applies this frame's [`CameraInput`] to every
/// [`OrbitCamera`] and writes its transform.
pub fn orbit_cameras(world: &mut hecs::World, resources: &mut Resources) {
    let input = CameraInput::from_resources(resources);
    for (orbit, transform) in world.query_mut::<(&mut OrbitCamera, &mut Transform)>() {
        orbit.apply(&input);
        *transform = orbit.transform();
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

    #[test]
    fn a_left_drag_orbits_a_right_drag_pans_and_the_wheel_zooms() {
        let mut resources = Resources::default();
        super::super::input::insert_input_resources(&mut resources);
        resources.get_or_default::<MouseMotion>().delta = Vec2::new(10.0, 0.0);
        resources
            .get_or_default::<ButtonInput<MouseButton>>()
            .press(MouseButton::Left);
        resources.get_or_default::<MouseScroll>().lines = Vec2::Y;
        let input = CameraInput::from_resources(&resources);
        assert_eq!((input.orbit, input.pan), (Vec2::new(10.0, 0.0), Vec2::ZERO));
        assert_eq!(input.zoom, PIXELS_PER_WHEEL_STEP);
        let buttons = resources.get_or_default::<ButtonInput<MouseButton>>();
        buttons.release(MouseButton::Left);
        buttons.press(MouseButton::Right);
        let input = CameraInput::from_resources(&resources);
        assert_eq!((input.orbit, input.pan), (Vec2::ZERO, Vec2::new(10.0, 0.0)));
    }
}
