// The texel-rate probe: every pixel takes `taps` bilinear samples of a 1024² texture along a
// short diagonal walk, as a parallax march does, and writes their mean so none is optimised out.
// Composed after fullscreen_triangle.wgsl.

struct ProbeParams {
    // x: taps per pixel; yz: UV step per tap; w: unused.
    taps_and_step: vec4<f32>,
}

@group(0) @binding(0) var probe_texture: texture_2d<f32>;
@group(0) @binding(1) var probe_sampler: sampler;
@group(0) @binding(2) var<uniform> params: ProbeParams;

@fragment
fn fs_main(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {
    let taps = u32(params.taps_and_step.x);
    let step = params.taps_and_step.yz;
    // One texel per pixel, as a magnified parallax surface reads its height map.
    var uv = position.xy / vec2<f32>(textureDimensions(probe_texture));
    var sum = vec4<f32>(0.0);
    for (var tap = 0u; tap < taps; tap += 1u) {
        sum += textureSampleLevel(probe_texture, probe_sampler, uv, 0.0);
        uv += step;
    }
    return sum / f32(max(taps, 1u));
}
