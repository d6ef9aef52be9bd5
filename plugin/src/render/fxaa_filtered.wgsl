// FXAA's bilinear read where the display format filters (rgba8unorm): one sampler tap instead
// of four loads. The edge search reads up to 22 of them a pixel: on finely detailed texture at
// 4K, 45°, the pass took 0.19-0.22 ms with loads and takes 0.11-0.12 ms so (sandbox/BENCHMARKS.md).
// Clamped at the borders, as the loads are.
@group(0) @binding(1) var tonemapped_sampler: sampler;

// `position` is in pixels, a pixel's centre at + 0.5.
fn sample_at(position: vec2<f32>) -> vec4<f32> {
    let size = vec2<f32>(textureDimensions(tonemapped));
    return textureSampleLevel(tonemapped, tonemapped_sampler, position / size, 0.0);
}
