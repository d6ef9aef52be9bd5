// What the environment is made from, as the prefilter's capture and the background read it
// (source.rs): a constant radiance, the sky, or an equirectangular image, in group 1. Composed
// after sky.wgsl.

const SOURCE_UNIFORM: u32 = 0u;
const SOURCE_SKY: u32 = 1u;
const SOURCE_EQUIRECT: u32 = 2u;

// Mirrors `SourceParams` in source.rs (the layout test checks them).
struct SourceParams {
    // rgb: the constant radiance.
    uniform_radiance: vec4<f32>,
    // x: SOURCE_*.
    kind: vec4<u32>,
}

// Storage buffers, not uniforms: a branch decided by a uniform alone makes lavapipe keep a
// new copy of the shader at each bind (memory grows every frame the background draws).
@group(1) @binding(0) var<storage, read> source: SourceParams;
@group(1) @binding(1) var<storage, read> sky: SkyParams;
@group(1) @binding(2) var source_image: texture_2d<f32>;
@group(1) @binding(3) var source_sampler: sampler;

const PI: f32 = 3.14159265;

// Where an equirectangular image holds the unit `direction`: longitude across, with −Z at the
// centre and +X to its right; the zenith at the top.
fn equirect_coordinate(direction: vec3<f32>) -> vec2<f32> {
    return vec2<f32>(0.5 + atan2(direction.x, -direction.z) / (2.0 * PI), acos(clamp(direction.y, -1.0, 1.0)) / PI);
}

// The radiance seen looking along the unit `direction`; an image is read at mip `level`.
fn source_radiance(direction: vec3<f32>, level: f32) -> vec3<f32> {
    switch source.kind.x {
        case SOURCE_SKY: {
            return sky_radiance(sky, direction);
        }
        case SOURCE_EQUIRECT: {
            return textureSampleLevel(source_image, source_sampler, equirect_coordinate(direction), level).rgb;
        }
        default: {
            return source.uniform_radiance.rgb;
        }
    }
}
