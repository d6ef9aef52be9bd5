// FXAA's bilinear read where the display format filters (rgba8unorm): one sampler tap instead
// of four loads. The edge search reads up to 22 of them a pixel: on finely detailed texture the
// pass takes about half the time it took with loads (sandbox/BENCHMARKS.md, "Anti-aliasing").
// Clamped at the borders, as the loads are.
@group(0) @binding(1) var tonemapped_sampler: sampler;

// `position` is in pixels, a pixel's centre at + 0.5.
fn sample_at(position: vec2<f32>) -> vec4<f32> {
    let size = vec2<f32>(textureDimensions(tonemapped));
    return textureSampleLevel(tonemapped, tonemapped_sampler, position / size, 0.0);
}
