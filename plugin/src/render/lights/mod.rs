//! Point, spot and directional lights: [`LightsPlugin`]'s Extract system copies every
//! [`DirectionalLight`], [`PointLight`] and [`SpotLight`] of the world, in physical units times
//! the camera's exposure, into the frame uniform's light arrays (frame.wgsl's `light_at` reads
//! them), with each slot's entity in the frame's `lights` for the features that follow
//! (the shadows plan each casting light's maps; the environment's sky takes its sun from the
//! first directional light). It runs right after the core's extract, before every other
//! feature's.

use hecs::World;

use crate::render::gpu_types::{
    DirectionalLightGpu, MAX_DIRECTIONAL_LIGHTS, MAX_POINT_LIGHTS, PointLightGpu,
};
use crate::render::{ExtractedFrame, extract::radiance};
use crate::{
    App, AppError, DirectionalLight, GlobalTransform, Plugin, PointLight, Resources, SpotLight,
    Stage,
};

/// Puts the world's lights in the frame (the render plugin adds it first of its standard
/// features; without it no light shines, only the ambient and environment light).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct LightsPlugin;

impl Plugin for LightsPlugin {
    fn build(&self, app: &mut App) {
        app.add_system(Stage::Extract, extract_lights);
    }
}

/// The Extract stage's system: the lights into [`ExtractedFrame`], after the core's extract.
fn extract_lights(world: &mut World, resources: &mut Resources) -> Result<(), AppError> {
    let extracted = resources.require_mut::<ExtractedFrame>()?;
    // Lux and candela to what the shaders multiply with the albedo, as the ambient light
    // (see extract.rs): ρ·E/π towards the eye, times the exposure.
    let light_scale = std::f32::consts::FRAC_1_PI * extracted.exposure.multiplier();
    let mut lights = LightExtraction {
        extracted,
        light_scale,
    };
    let directional_count = lights.directional_lights(world);
    let point_count = lights.point_and_spot_lights(world);
    lights.extracted.frame.light_counts = [directional_count as u32, point_count as u32, 0, 0];
    Ok(())
}

/// The frame's lights being filled in, with their entities.
struct LightExtraction<'a> {
    extracted: &'a mut ExtractedFrame,
    light_scale: f32,
}

impl LightExtraction<'_> {
    /// Fills in the directional lights (with their cascades); returns how many.
    fn directional_lights(&mut self, world: &World) -> usize {
        let mut count = 0;
        for (entity, light, transform) in world
            .query::<(hecs::Entity, &DirectionalLight, &GlobalTransform)>()
            .iter()
        {
            if count == MAX_DIRECTIONAL_LIGHTS {
                log::warn!(
                    "more than {MAX_DIRECTIONAL_LIGHTS} directional lights: the rest are ignored"
                );
                break;
            }
            self.extracted.frame.directional_lights[count] = DirectionalLightGpu {
                direction_to_light: (-transform.forward()).extend(0.0).into(),
                radiance: radiance(light.color, light.intensity, self.light_scale),
                ..DirectionalLightGpu::default()
            };
            self.extracted.lights.directional.push(entity);
            count += 1;
        }
        count
    }

    /// Fills in the point lights, then the spot lights, which share their array; returns how
    /// many.
    fn point_and_spot_lights(&mut self, world: &World) -> usize {
        let mut count = 0;
        for (entity, light, transform) in world
            .query::<(hecs::Entity, &PointLight, &GlobalTransform)>()
            .iter()
        {
            if count == MAX_POINT_LIGHTS {
                log::warn!("more than {MAX_POINT_LIGHTS} point lights: the rest are ignored");
                break;
            }
            self.extracted.frame.point_lights[count] = PointLightGpu {
                position_range: transform.translation().extend(light.range.max(0.0)).into(),
                radiance: radiance(light.color, light.intensity, self.light_scale),
                spot_direction: [0.0, 0.0, -1.0, 0.0],
                // Scale 0, offset 1: full strength in every direction.
                spot_cone: [0.0, 1.0, 0.0, 0.0],
                ..PointLightGpu::default()
            };
            self.extracted.lights.point.push(entity);
            count += 1;
        }
        for (entity, light, transform) in world
            .query::<(hecs::Entity, &SpotLight, &GlobalTransform)>()
            .iter()
        {
            if count == MAX_POINT_LIGHTS {
                log::warn!(
                    "more than {MAX_POINT_LIGHTS} point and spot lights: the rest are ignored"
                );
                break;
            }
            self.extracted.frame.point_lights[count] = self.spot_light(light, transform);
            self.extracted.lights.point.push(entity);
            count += 1;
        }
        count
    }

    /// A spot light as the shaders read it.
    fn spot_light(&self, light: &SpotLight, transform: &GlobalTransform) -> PointLightGpu {
        // glTF's cone: t = cos(angle to the axis) × scale + offset, clamped, squared.
        let (inner, outer) = light.sanitized_cone();
        let scale = 1.0 / (inner.cos() - outer.cos()).max(1e-3);
        PointLightGpu {
            position_range: transform.translation().extend(light.range.max(0.0)).into(),
            radiance: radiance(light.color, light.intensity, self.light_scale),
            spot_direction: transform.forward().extend(0.0).into(),
            spot_cone: [scale, -outer.cos() * scale, 0.0, 0.0],
            ..PointLightGpu::default()
        }
    }
}
