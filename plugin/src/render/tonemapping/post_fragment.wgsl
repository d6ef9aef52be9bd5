// Post-processing as a full-screen triangle (fullscreen_triangle.wgsl), for adapters that
// cannot write the display format from compute.

@fragment
fn post_fragment(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {
    return post_process(vec2<u32>(position.xy));
}
