// The environment light as materials read it (pom::render::EnvironmentMaps binds it; the
// environment feature fills it): radiance prefiltered by roughness, the split-sum table and
// the irradiance. Composed after frame.wgsl and spherical_harmonics.wgsl. Values come
// pre-exposed like the lights' (`frame.environment.x` folds in the exposure and intensity).

// Irradiance / π as nine spherical-harmonic coefficients (rgb), convolution included.
struct EnvironmentIrradiance {
    coefficients: array<vec4<f32>, 9>,
}

@group(0) @binding(10) var environment_radiance_map: texture_cube<f32>;
@group(0) @binding(11) var environment_split_sum_table: texture_2d<f32>;
@group(0) @binding(12) var<uniform> environment_irradiance: EnvironmentIrradiance;
@group(0) @binding(13) var environment_sampler: sampler;

// Set by the material seam in pipelines of frames an environment lights: the others are
// compiled without the environment's code (code that is there costs registers unrun).
override ENVIRONMENT: bool = false;

// Whether an environment lights the frame (else materials use the ambient term).
fn has_environment() -> bool {
    return ENVIRONMENT && frame.environment.y > 0.0;
}

// A world direction in the environment's own frame: turned about +Y by its rotation.
fn environment_direction(world: vec3<f32>) -> vec3<f32> {
    let c = frame.environment.z;
    let s = frame.environment.w;
    return vec3<f32>(c * world.x - s * world.z, world.y, s * world.x + c * world.z);
}

// What a white Lambertian surface facing `normal` reflects of the environment.
fn environment_diffuse(normal: vec3<f32>) -> vec3<f32> {
    let basis = spherical_harmonics(environment_direction(normal));
    var sum = vec3<f32>(0.0);
    for (var i = 0u; i < 9u; i += 1u) {
        sum += environment_irradiance.coefficients[i].rgb * basis[i];
    }
    return max(sum, vec3<f32>(0.0)) * frame.environment.x;
}

// The radiance seen looking along `direction`, blurred as a GGX lobe of perceptual `roughness`.
fn environment_specular(direction: vec3<f32>, roughness: f32) -> vec3<f32> {
    let level = clamp(roughness, 0.0, 1.0) * (frame.environment.y - 1.0);
    return textureSampleLevel(environment_radiance_map, environment_sampler, environment_direction(direction), level).rgb
        * frame.environment.x;
}

// The split sum's scale (x) and bias (y) of F0 at `n_dot_v` and perceptual `roughness`.
fn environment_split_sum(n_dot_v: f32, roughness: f32) -> vec2<f32> {
    return textureSampleLevel(environment_split_sum_table, environment_sampler, vec2<f32>(n_dot_v, roughness), 0.0).xy;
}
