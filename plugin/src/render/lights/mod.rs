//! Point, spot and directional lights: [`LightsPlugin`]'s Extract system copies every
//! [`DirectionalLight`] (up to four), [`PointLight`] and [`SpotLight`] of the world, in
//! physical units times the camera's exposure, into the frame (frame.wgsl's `light_at` reads
//! them), with each slot's entity in the frame's `lights` for the features that follow (the
//! shadows plan each casting light's maps; the environment's sky takes its sun from the first
//! directional light). It runs right after the core's extract, before every other feature's.
//!
//! Point and spot lights are culled into clusters (clusters.rs): the image is cut into tiles
//! and the view depth into slices, and each cluster lists the lights whose range reaches into
//! it, so a pixel loops over its cluster's lights only (`lights_near` in frame.wgsl) on both
//! paths, with hundreds or thousands of lights in view.

mod clusters;

use crate::shader::WgslFile;

/// Finding the lights that reach a point (`lights_near`, `light_in`) and ranking the brightest
/// (`brightest_lights_floor`); composed after the core's frame.wgsl by every lit material.
pub const LIGHTS_WGSL: WgslFile = crate::wgsl_file!(nested "render/lights/lights.wgsl");

/// The most lights lights.wgsl's `brightest_lights_floor` ranks (`MAX_RANKED_LIGHTS` there).
pub const MAX_RANKED_LIGHTS: u32 = 8;

use hecs::World;

use crate::render::gpu_types::{DirectionalLightGpu, MAX_DIRECTIONAL_LIGHTS, PointLightGpu};
use crate::render::{ExtractedFrame, RenderTarget, extract::radiance};
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
        dropped_point_lights: false,
    };
    let directional_count = lights.directional_lights(world);
    let point_count = lights.point_and_spot_lights(world);
    let dropped = lights.dropped_point_lights;
    lights.extracted.frame.light_counts = [directional_count as u32, point_count as u32, 0, 0];
    let overflow = resources.get_or_default::<PointLightOverflow>();
    if dropped && !overflow.0 {
        log::warn!(
            "more than {MAX_POINT_LIGHTS} point and spot lights (MAX_POINT_LIGHTS): the rest are ignored"
        );
    }
    overflow.0 = dropped;
    let target = resources.require::<RenderTarget>()?;
    let (aspect, size) = (target.aspect(), target.size());
    let extracted = resources.require_mut::<ExtractedFrame>()?;
    if let Some(camera) = extracted.camera {
        let lights = &extracted.point_lights;
        clusters::cull(&camera, aspect, size, lights, &mut extracted.light_clusters);
    }
    Ok(())
}

/// Most point and spot lights one frame shades with: the rest are ignored, with a warning
/// (their buffer alone would take 5 MB of the GPU's memory).
pub const MAX_POINT_LIGHTS: usize = 65_536;

/// Whether the last frame had more point and spot lights than [`MAX_POINT_LIGHTS`] (warned
/// once per episode).
#[derive(Clone, Copy, Debug, Default)]
struct PointLightOverflow(bool);

/// The frame's lights being filled in, with their entities.
struct LightExtraction<'a> {
    extracted: &'a mut ExtractedFrame,
    light_scale: f32,
    /// Whether point or spot lights past [`MAX_POINT_LIGHTS`] were left out.
    dropped_point_lights: bool,
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
                self.dropped_point_lights = true;
                break;
            }
            self.extracted.point_lights.push(PointLightGpu {
                position_range: transform.translation().extend(light.range.max(0.0)).into(),
                radiance: radiance(light.color, light.intensity, self.light_scale),
                spot_direction: [0.0, 0.0, -1.0, 0.0],
                // Scale 0, offset 1: full strength in every direction.
                spot_cone: [0.0, 1.0, 0.0, 0.0],
                ..PointLightGpu::default()
            });
            self.extracted.lights.point.push(entity);
            count += 1;
        }
        for (entity, light, transform) in world
            .query::<(hecs::Entity, &SpotLight, &GlobalTransform)>()
            .iter()
        {
            if count == MAX_POINT_LIGHTS {
                self.dropped_point_lights = true;
                break;
            }
            let spot = self.spot_light(light, transform);
            self.extracted.point_lights.push(spot);
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

#[cfg(test)]
mod tests {
    #[test]
    fn the_shader_reads_the_cluster_header_the_renderer_writes() {
        let declaration = format!(
            "const LIGHT_CLUSTER_HEADER: u32 = {}u;",
            crate::render::extract::LIGHT_CLUSTER_HEADER
        );
        assert!(super::LIGHTS_WGSL.source.contains(&declaration));
    }

    #[test]
    fn the_shader_ranks_as_many_lights_as_the_renderer_says() {
        let declaration = format!(
            "const MAX_RANKED_LIGHTS: u32 = {}u;",
            super::MAX_RANKED_LIGHTS
        );
        assert!(super::LIGHTS_WGSL.source.contains(&declaration));
    }
}
