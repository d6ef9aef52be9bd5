// Per-frame camera and lights, shared by every pass that draws into the main target.
// Mirrors `FrameUniform` in gpu_types.rs; change both together.

const MAX_DIRECTIONAL_LIGHTS: u32 = 4u;

struct DirectionalLight {
    // xyz: unit vector from the surface towards the light.
    direction_to_light: vec4<f32>,
    // rgb: colour × intensity.
    radiance: vec4<f32>,
    // Its shadow maps: shadow_views[first_shadow_view ..][.. shadow_view_count] (shadows.wgsl).
    first_shadow_view: u32,
    shadow_view_count: u32,
    _padding: vec2<u32>,
}

struct PointLight {
    // xyz: world position, w: range.
    position_range: vec4<f32>,
    // rgb: colour × intensity.
    radiance: vec4<f32>,
    // xyz: the direction a spot shines.
    spot_direction: vec4<f32>,
    // x: angle scale, y: angle offset (0 and 1 for a point light).
    spot_cone: vec4<f32>,
    // A spot's one shadow map, a point light's six cube faces (+X, −X, +Y, −Y, +Z, −Z).
    first_shadow_view: u32,
    shadow_view_count: u32,
    _padding: vec2<u32>,
}

struct Frame {
    view_projection: mat4x4<f32>,
    camera_position: vec4<f32>,
    // xyz: the direction the camera looks; w: 1 for orthographic (parallel view rays).
    view_direction: vec4<f32>,
    // rgb: ambient colour × intensity.
    ambient: vec4<f32>,
    // x: directional light count, y: point and spot light count (`point_lights`).
    light_counts: vec4<u32>,
    // xy: the target's width and height in pixels (the visibility buffer's rows); z: the seed of
    // per-frame noise (counts TAA frames; 0 without TAA); w: 1 under TAA, whose history averages
    // per-frame noise away (the soft shadow's samples move only then).
    target_size: vec4<u32>,
    // x: the scale of every texture read's gradients, 2 to the mip bias of TAA or the post
    // filter (1 without anti-aliasing): textures are sampled finer, and the jitter averages them
    // over the pixel (TAA) or FXAA softens their edges.
    texture_lod: vec4<f32>,
    // x: what the environment's values are multiplied with (its intensity × the exposure), y:
    // the radiance cube's mips (0: no environment, the ambient term lights instead; the last is
    // roughness 1), zw: cosine and sine of its turn about +Y (environment.wgsl).
    environment: vec4<f32>,
    // x: 1 where the environment's specular gets back the energy a single scattering loses on
    // rough surfaces (multiple-scattering compensation), else 0.
    environment_options: vec4<f32>,
    directional_lights: array<DirectionalLight, MAX_DIRECTIONAL_LIGHTS>,
}

@group(0) @binding(0) var<uniform> frame: Frame;
// The point lights, then the spot lights (light_counts.y of them).
@group(0) @binding(14) var<storage, read> point_lights: array<PointLight>;

// Unit vector from a surface point towards the eye: along the view ray through that point,
// which for an orthographic camera is the same everywhere.
// A select, not a branch: a shadow map binds the frame at its own slot, and a branch on a
// uniform makes some drivers (Mesa 22's lavapipe) compile the shader again at every bind.
fn direction_to_eye(world_position: vec3<f32>, fallback: vec3<f32>) -> vec3<f32> {
    let offset = frame.camera_position.xyz - world_position;
    let length_squared = dot(offset, offset);
    let perspective = select(fallback, offset * inverseSqrt(length_squared), length_squared > 1e-20);
    return select(perspective, -frame.view_direction.xyz, frame.view_direction.w > 0.5);
}

struct LightSample {
    // Unit vector from the surface towards the light.
    to_light: vec3<f32>,
    // Radiance arriving at the surface (falloff included).
    radiance: vec3<f32>,
}

// Every light: directional lights first, then point lights (`light_at` numbers them so).
fn light_count() -> u32 {
    return min(frame.light_counts.x, MAX_DIRECTIONAL_LIGHTS) + frame.light_counts.y;
}

// Inverse-square falloff with a smooth window that reaches zero at the light's range.
fn point_light_attenuation(distance: f32, range: f32) -> f32 {
    let ratio = distance / max(range, 1e-4);
    let window = clamp(1.0 - ratio * ratio * ratio * ratio, 0.0, 1.0);
    return window * window / max(distance * distance, 1e-4);
}

// The light `index` (0..light_count()) as seen from `world_position`.
fn light_at(index: u32, world_position: vec3<f32>) -> LightSample {
    let directional_count = min(frame.light_counts.x, MAX_DIRECTIONAL_LIGHTS);
    if index < directional_count {
        let light = frame.directional_lights[index];
        return LightSample(light.direction_to_light.xyz, light.radiance.rgb);
    }
    let light = point_lights[index - directional_count];
    let offset = light.position_range.xyz - world_position;
    let distance = length(offset);
    // At the light's own position any direction will do; the window makes it dark anyway.
    let to_light = select(vec3<f32>(0.0, 0.0, 1.0), offset / distance, distance > 1e-6);
    // A spot's cone (KHR_lights_punctual): full inside the inner angle, squared fade to the outer.
    let cone = clamp(dot(light.spot_direction.xyz, -to_light) * light.spot_cone.x + light.spot_cone.y, 0.0, 1.0);
    let radiance = light.radiance.rgb * point_light_attenuation(distance, light.position_range.w) * cone * cone;
    return LightSample(to_light, radiance);
}

