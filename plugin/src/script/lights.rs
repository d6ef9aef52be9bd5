//! A script's lights in the world: the light components, their orientation, and their scene
//! shadows when the script sets them.

use glam::Vec3;
use hecs::Entity;

use super::format::LightDesc;
use crate::{Color, DirectionalLight, PointLight, SpotLight, Transform};

/// A light's transform shining along `direction` (any up that is not parallel to it).
pub(super) fn light_towards(direction: Vec3) -> Transform {
    let up = if direction.normalize_or_zero().y.abs() > 0.99 {
        Vec3::Z
    } else {
        Vec3::Y
    };
    Transform::IDENTITY.looking_at(direction, up)
}

/// Spawns the light `desc` describes, with its `LightShadows` when the script sets them.
pub(super) fn spawn_light(world: &mut hecs::World, desc: &LightDesc) -> Entity {
    let linear = |color: &[f32; 3]| Color::linear_rgb(color[0], color[1], color[2]);
    let entity = match desc {
        LightDesc::Directional {
            direction,
            color,
            intensity,
            ..
        } => world.spawn((
            DirectionalLight {
                color: linear(color),
                intensity: *intensity,
            },
            light_towards(Vec3::from(*direction)),
        )),
        LightDesc::Point {
            position,
            color,
            intensity,
            range,
            ..
        } => world.spawn((
            PointLight {
                color: linear(color),
                intensity: *intensity,
                range: *range,
            },
            Transform::from_translation(Vec3::from(*position)),
        )),
        LightDesc::Spot {
            position,
            direction,
            color,
            intensity,
            range,
            inner_degrees,
            outer_degrees,
            ..
        } => {
            let mut transform = light_towards(Vec3::from(*direction));
            transform.translation = Vec3::from(*position);
            world.spawn((
                SpotLight {
                    color: linear(color),
                    intensity: *intensity,
                    range: *range,
                    inner_angle: inner_degrees.to_radians(),
                    outer_angle: outer_degrees.to_radians(),
                },
                transform,
            ))
        }
    };
    if let Some(shadows) = desc.shadows() {
        // Just spawned, so the entity exists.
        let _ = world.insert_one(entity, shadows);
    }
    entity
}
