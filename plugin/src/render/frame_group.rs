//! Group 0 of every material pipeline, the frame's group: what the core binds at each binding.
//! A material's shader declares its own per-draw array at [`MATERIAL_UNIFORMS`]; the rest are
//! declared by the core's WGSL files (frame.wgsl, mesh_vertex.wgsl, prepass_depth.wgsl,
//! shadows.wgsl, environment.wgsl, lights.wgsl, visibility.wgsl) and the composer (the test counter), under the names in
//! [`DECLARED`].

/// `frame`: the camera and lights (frame.wgsl).
pub const FRAME: u32 = 0;
/// `transforms`: each draw's transform and flags (mesh_vertex.wgsl).
pub const TRANSFORMS: u32 = 1;
/// The material's own `array<Uniform>`, one element per draw, indexed by `object_index`.
pub const MATERIAL_UNIFORMS: u32 = 2;
/// `prepass_depth`: the depth prepass, for materials that test their own depth.
pub const PREPASS_DEPTH: u32 = 3;
/// `fragment_invocations`: the test counter of fragment invocations.
pub const FRAGMENT_COUNTER: u32 = 4;
/// `shadow_views`: what receivers read of each shadow map (shadows.wgsl).
pub const SHADOW_VIEWS: u32 = 5;
/// `shadow_maps`: every light's shadow maps, one array (shadows.wgsl).
pub const SHADOW_MAPS: u32 = 6;
/// `shadow_sampler`: the maps' comparison sampler (shadows.wgsl).
pub const SHADOW_SAMPLER: u32 = 7;
/// `visibility_keys`: the deferred path's visibility buffer (visibility.wgsl).
pub const VISIBILITY_KEYS: u32 = 8;
/// `visibility_words`: the same buffer as 32-bit words, for the depth a pixel has kept so far
/// (WGSL's 64-bit atomics offer only min and max).
pub const VISIBILITY_WORDS: u32 = 9;
/// `environment_radiance_map`: the environment prefiltered by roughness, a cube (environment.wgsl).
pub const ENVIRONMENT_RADIANCE: u32 = 10;
/// `environment_split_sum_table`: the split-sum table (environment.wgsl).
pub const ENVIRONMENT_SPLIT_SUM: u32 = 11;
/// `environment_irradiance`: the environment's irradiance as spherical harmonics (environment.wgsl).
pub const ENVIRONMENT_IRRADIANCE: u32 = 12;
/// `environment_sampler`: the environment maps' trilinear sampler (environment.wgsl).
pub const ENVIRONMENT_SAMPLER: u32 = 13;

/// `point_lights`: every point and spot light (frame.wgsl).
pub const POINT_LIGHTS: u32 = 14;
/// `light_clusters`: each light cluster's point lights (lights/lights.wgsl).
pub const LIGHT_CLUSTERS: u32 = 15;

/// The WGSL name the core's files declare at each binding it owns.
pub const DECLARED: &[(&str, u32)] = &[
    ("frame", FRAME),
    ("transforms", TRANSFORMS),
    ("prepass_depth", PREPASS_DEPTH),
    ("fragment_invocations", FRAGMENT_COUNTER),
    ("shadow_views", SHADOW_VIEWS),
    ("shadow_maps", SHADOW_MAPS),
    ("shadow_sampler", SHADOW_SAMPLER),
    ("visibility_keys", VISIBILITY_KEYS),
    ("visibility_words", VISIBILITY_WORDS),
    ("environment_radiance_map", ENVIRONMENT_RADIANCE),
    ("environment_split_sum_table", ENVIRONMENT_SPLIT_SUM),
    ("environment_irradiance", ENVIRONMENT_IRRADIANCE),
    ("environment_sampler", ENVIRONMENT_SAMPLER),
    ("point_lights", POINT_LIGHTS),
    ("light_clusters", LIGHT_CLUSTERS),
];

#[cfg(test)]
mod tests {
    use super::*;
    use crate::render::shaders;

    #[test]
    fn the_core_files_declare_each_binding_where_the_constants_say() {
        let shader = shaders::ComposedShader {
            name: "core",
            constants: &[],
            files: &[
                shaders::FRAME,
                crate::render::lights::LIGHTS_WGSL,
                shaders::MESH_VERTEX,
                shaders::PREPASS_DEPTH,
                shaders::SHADOWS,
                crate::render::environment::SPHERICAL_HARMONICS,
                crate::render::environment::ENVIRONMENT,
                shaders::VISIBILITY,
            ],
        };
        let source = shader.counting_source(&Default::default());
        for (name, binding) in DECLARED {
            let declaration = format!("@group(0) @binding({binding}) var");
            let found = source
                .lines()
                .any(|line| line.starts_with(&declaration) && line.contains(&format!(" {name}:")));
            assert!(found, "{name} is not declared at group 0 binding {binding}");
        }
    }
}
