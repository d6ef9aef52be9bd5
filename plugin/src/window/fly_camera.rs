//! Free flight: [`FlyCamera`] on a camera entity, moved by [`FlyCameraPlugin`]'s system from
//! the input resources. W/A/S/D fly forward, left, back and right along the view, E up and
//! Q down, Shift goes four times faster; dragging with the left or right mouse
//! button held turns the view (a window keeps its cursor: no grab needed).

use glam::{EulerRot, Quat, Vec3};

use super::input::{ButtonInput, KeyCode, MouseButton, MouseMotion};
use crate::{App, Plugin, Resources, Stage, Time, Transform};

/// How much faster Shift flies.
const SHIFT_FACTOR: f32 = 4.0;
/// Keeps the view off straight up and down, where turning left and right stops being defined.
const MAX_PITCH: f32 = 1.54;

/// A camera that flies where it looks. A component: with [`FlyCameraPlugin`], the entity's
/// `Transform` follows it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FlyCamera {
    /// Where the camera is.
    pub position: Vec3,
    /// Radians around +Y; 0 looks along −Z.
    pub yaw: f32,
    /// Radians above the horizon.
    pub pitch: f32,
    /// Metres per second.
    pub speed: f32,
    /// Radians of turn per pixel of mouse drag.
    pub turn_per_pixel: f32,
}

impl FlyCamera {
    /// The flight that starts at `transform` (its roll is dropped), at 2 m/s.
    pub fn from_transform(transform: &Transform) -> Self {
        let (yaw, pitch, _) = transform.rotation.to_euler(EulerRot::YXZ);
        Self {
            position: transform.translation,
            yaw,
            pitch: pitch.clamp(-MAX_PITCH, MAX_PITCH),
            speed: 2.0,
            turn_per_pixel: 0.004,
        }
    }

    /// The camera's transform.
    pub fn transform(&self) -> Transform {
        Transform {
            translation: self.position,
            rotation: Quat::from_euler(EulerRot::YXZ, self.yaw, self.pitch, 0.0),
            ..Transform::IDENTITY
        }
    }

    /// Turns by a mouse drag of `drag` pixels, then flies `steer` (x right, y up, z forward,
    /// each −1 to 1 or more) for `seconds`.
    pub fn apply(&mut self, drag: glam::Vec2, steer: Vec3, seconds: f32) {
        self.yaw -= drag.x * self.turn_per_pixel;
        self.pitch = (self.pitch - drag.y * self.turn_per_pixel).clamp(-MAX_PITCH, MAX_PITCH);
        let rotation = self.transform().rotation;
        let direction =
            rotation * Vec3::X * steer.x + Vec3::Y * steer.y - rotation * Vec3::Z * steer.z;
        self.position += direction * self.speed * seconds;
    }
}

/// Moves every camera that has a [`FlyCamera`] by the mouse and keys, in [`Stage::Update`].
/// Needs [`super::WindowPlugin`]'s input resources.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct FlyCameraPlugin;

impl Plugin for FlyCameraPlugin {
    fn build(&self, app: &mut App) {
        app.add_system(Stage::Update, fly_cameras);
    }
}

/// [`FlyCameraPlugin`]'s system: turns and flies every [`FlyCamera`] by this frame's input and
/// writes its transform.
pub fn fly_cameras(world: &mut hecs::World, resources: &mut Resources) {
    let turning = resources
        .get::<ButtonInput<MouseButton>>()
        .is_some_and(|buttons| buttons.any_pressed([MouseButton::Left, MouseButton::Right]));
    let drag = match (turning, resources.get::<MouseMotion>()) {
        (true, Some(motion)) => motion.delta,
        _ => glam::Vec2::ZERO,
    };
    let (steer, faster) =
        resources
            .get::<ButtonInput<KeyCode>>()
            .map_or((Vec3::ZERO, false), |keys| {
                let axis = |plus: &[KeyCode], minus: &[KeyCode]| {
                    let held = |set: &[KeyCode]| {
                        f32::from(u8::from(keys.any_pressed(set.iter().copied())))
                    };
                    held(plus) - held(minus)
                };
                let steer = Vec3::new(
                    axis(&[KeyCode::KeyD], &[KeyCode::KeyA]),
                    axis(&[KeyCode::KeyE], &[KeyCode::KeyQ]),
                    axis(&[KeyCode::KeyW], &[KeyCode::KeyS]),
                );
                let faster = keys.any_pressed([KeyCode::ShiftLeft, KeyCode::ShiftRight]);
                (steer, faster)
            });
    let seconds = resources.get::<Time>().map_or(0.0, Time::delta_secs)
        * if faster { SHIFT_FACTOR } else { 1.0 };
    for (fly, transform) in world.query_mut::<(&mut FlyCamera, &mut Transform)>() {
        fly.apply(drag, steer, seconds);
        *transform = fly.transform();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_flight_reproduces_the_transform_it_came_from() {
        let start =
            Transform::from_xyz(3.0, 2.0, 4.0).looking_at(Vec3::new(0.5, 0.0, 0.0), Vec3::Y);
        let again = FlyCamera::from_transform(&start).transform();
        assert!(again.translation.abs_diff_eq(start.translation, 1e-5));
        assert!((again.rotation * Vec3::NEG_Z).abs_diff_eq(start.rotation * Vec3::NEG_Z, 1e-4));
    }

    #[test]
    fn w_flies_where_the_camera_looks_and_a_drag_turns_it() {
        let mut resources = Resources::default();
        super::super::input::insert_input_resources(&mut resources);
        resources.insert(Time::fixed(std::time::Duration::from_millis(500)));
        resources
            .get_or_default::<Time>()
            .advance(std::time::Instant::now());
        resources
            .get_or_default::<ButtonInput<KeyCode>>()
            .press(KeyCode::KeyW);
        let mut world = hecs::World::new();
        let start =
            Transform::from_xyz(0.0, 1.0, 5.0).looking_at(Vec3::new(0.0, 1.0, 0.0), Vec3::Y);
        let camera = world.spawn((FlyCamera::from_transform(&start), start));
        fly_cameras(&mut world, &mut resources);
        let moved = world.get::<&Transform>(camera).unwrap().translation;
        // 2 m/s for half a second, towards −Z.
        assert!(moved.abs_diff_eq(Vec3::new(0.0, 1.0, 4.0), 1e-4), "{moved}");

        resources
            .get_or_default::<ButtonInput<KeyCode>>()
            .release(KeyCode::KeyW);
        resources
            .get_or_default::<ButtonInput<MouseButton>>()
            .press(MouseButton::Right);
        resources.get_or_default::<MouseMotion>().delta = glam::Vec2::new(100.0, 0.0);
        fly_cameras(&mut world, &mut resources);
        let forward = world.get::<&Transform>(camera).unwrap().rotation * Vec3::NEG_Z;
        assert!(forward.x > 0.3, "dragging right turns right: {forward}");
        let position = world.get::<&Transform>(camera).unwrap().translation;
        assert!(position.abs_diff_eq(moved, 1e-5), "turning does not move");
    }
}
