// Forward pass for lit, normal-mapped meshes: Blinn-Phong with directional and point lights
// and an ambient term. Bindings and structs mirror `forward.rs`; change both together.

const MAX_DIRECTIONAL_LIGHTS: u32 = 4u;
const MAX_POINT_LIGHTS: u32 = 16u;

struct DirectionalLight {
    // xyz: unit vector from the surface towards the light.
    direction_to_light: vec4<f32>,
    // rgb: colour × intensity.
    radiance: vec4<f32>,
}

struct PointLight {
    // xyz: world position, w: range.
    position_range: vec4<f32>,
    // rgb: colour × intensity.
    radiance: vec4<f32>,
}

struct Frame {
    view_projection: mat4x4<f32>,
    camera_position: vec4<f32>,
    // rgb: ambient colour × intensity.
    ambient: vec4<f32>,
    // x: directional light count, y: point light count.
    light_counts: vec4<u32>,
    directional_lights: array<DirectionalLight, MAX_DIRECTIONAL_LIGHTS>,
    point_lights: array<PointLight, MAX_POINT_LIGHTS>,
}

struct Object {
    model: mat4x4<f32>,
    // Inverse transpose of the model matrix, for normals under non-uniform scale.
    normal_matrix: mat4x4<f32>,
    base_color: vec4<f32>,
    // x: normal map strength, y: specular strength, z: shininess exponent,
    // w: sign of the model matrix determinant (mirroring flips the bitangent).
    params: vec4<f32>,
}

@group(0) @binding(0) var<uniform> frame: Frame;
@group(0) @binding(1) var<storage, read> objects: array<Object>;
@group(1) @binding(0) var base_color_texture: texture_2d<f32>;
@group(1) @binding(1) var normal_map: texture_2d<f32>;
@group(1) @binding(2) var material_sampler: sampler;

struct VertexIn {
    @location(0) position: vec3<f32>,
    @location(1) normal: vec3<f32>,
    @location(2) uv: vec2<f32>,
    // xyz: dP/du, w: sign so that cross(normal, tangent) * w = dP/dv (MikkTSpace).
    @location(3) tangent: vec4<f32>,
}

struct VertexOut {
    @builtin(position) clip_position: vec4<f32>,
    @location(0) world_position: vec3<f32>,
    @location(1) world_normal: vec3<f32>,
    @location(2) uv: vec2<f32>,
    @location(3) world_tangent: vec4<f32>,
    @location(4) @interpolate(flat) object_index: u32,
}

// normalize() of a zero vector is NaN; degenerate input falls back to `fallback`.
fn safe_normalize(v: vec3<f32>, fallback: vec3<f32>) -> vec3<f32> {
    let length_squared = dot(v, v);
    if length_squared > 1e-20 {
        return v * inverseSqrt(length_squared);
    }
    return fallback;
}

@vertex
fn vs_main(in: VertexIn, @builtin(instance_index) object_index: u32) -> VertexOut {
    let object = objects[object_index];
    let world_position = object.model * vec4<f32>(in.position, 1.0);
    var out: VertexOut;
    out.clip_position = frame.view_projection * world_position;
    out.world_position = world_position.xyz;
    out.world_normal = (object.normal_matrix * vec4<f32>(in.normal, 0.0)).xyz;
    out.world_tangent = vec4<f32>(
        (object.model * vec4<f32>(in.tangent.xyz, 0.0)).xyz,
        in.tangent.w * object.params.w,
    );
    out.uv = in.uv;
    out.object_index = object_index;
    return out;
}

// Blinn-Phong reflection of one light: Lambert diffuse plus a specular lobe around the half
// vector, both scaled by N·L so nothing lights a surface from behind.
fn blinn_phong(
    normal: vec3<f32>,
    to_light: vec3<f32>,
    to_eye: vec3<f32>,
    albedo: vec3<f32>,
    specular_strength: f32,
    shininess: f32,
) -> vec3<f32> {
    let n_dot_l = max(dot(normal, to_light), 0.0);
    let half_vector = safe_normalize(to_light + to_eye, normal);
    let specular = specular_strength * pow(max(dot(normal, half_vector), 0.0), shininess);
    return (albedo + vec3<f32>(specular)) * n_dot_l;
}

// Inverse-square falloff with a smooth window that reaches zero at the light's range.
fn point_light_attenuation(distance: f32, range: f32) -> f32 {
    let ratio = distance / max(range, 1e-4);
    let window = clamp(1.0 - ratio * ratio * ratio * ratio, 0.0, 1.0);
    return window * window / max(distance * distance, 1e-4);
}

@fragment
fn fs_main(in: VertexOut) -> @location(0) vec4<f32> {
    let object = objects[in.object_index];
    let geometric_normal = safe_normalize(in.world_normal, vec3<f32>(0.0, 0.0, 1.0));
    // Gram-Schmidt: interpolation leaves the tangent slightly off perpendicular.
    let tangent = safe_normalize(
        in.world_tangent.xyz - geometric_normal * dot(geometric_normal, in.world_tangent.xyz),
        vec3<f32>(1.0, 0.0, 0.0),
    );
    let bitangent_v = cross(geometric_normal, tangent) * in.world_tangent.w;

    // Normal maps use the OpenGL / glTF convention: green points up the image, which is −v.
    let encoded = textureSample(normal_map, material_sampler, in.uv).xyz * 2.0 - 1.0;
    let tangent_normal = vec3<f32>(encoded.xy * object.params.x, max(encoded.z, 1e-3));
    let normal = safe_normalize(
        tangent * tangent_normal.x - bitangent_v * tangent_normal.y
            + geometric_normal * tangent_normal.z,
        geometric_normal,
    );

    let base = textureSample(base_color_texture, material_sampler, in.uv) * object.base_color;
    let to_eye = safe_normalize(frame.camera_position.xyz - in.world_position, normal);
    let specular_strength = object.params.y;
    let shininess = max(object.params.z, 1.0);

    var color = frame.ambient.rgb * base.rgb;
    let directional_count = min(frame.light_counts.x, MAX_DIRECTIONAL_LIGHTS);
    for (var i = 0u; i < directional_count; i += 1u) {
        let light = frame.directional_lights[i];
        color += light.radiance.rgb * blinn_phong(
            normal, light.direction_to_light.xyz, to_eye, base.rgb, specular_strength, shininess);
    }
    let point_count = min(frame.light_counts.y, MAX_POINT_LIGHTS);
    for (var i = 0u; i < point_count; i += 1u) {
        let light = frame.point_lights[i];
        let offset = light.position_range.xyz - in.world_position;
        let distance = length(offset);
        let to_light = safe_normalize(offset, normal);
        let attenuation = point_light_attenuation(distance, light.position_range.w);
        color += light.radiance.rgb * attenuation * blinn_phong(
            normal, to_light, to_eye, base.rgb, specular_strength, shininess);
    }
    return vec4<f32>(color, base.a);
}
