// The texel-rate probe: every pixel takes `taps` bilinear samples of a 1024² texture along a
// short diagonal walk, as a parallax march does, and writes their mean so none is optimised out.

struct ProbeParams {
    // x: taps per pixel; yz: UV step per tap; w: unused.
    taps_and_step: vec4<f32>,
}

@group(0) @binding(0) var probe_texture: texture_2d<f32>;
@group(0) @binding(1) var probe_sampler: sampler;
@group(0) @binding(2) var<uniform> params: ProbeParams;

@vertex
fn vs_main(@builtin(vertex_index) index: u32) -> @builtin(position) vec4<f32> {
    // One triangle covering the whole target.
    let corner = vec2<f32>(f32((index << 1u) & 2u), f32(index & 2u));
    return vec4<f32>(corner * 2.0 - 1.0, 0.0, 1.0);
}

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
