// FXAA as a full-screen triangle (fullscreen_triangle.wgsl), for adapters that cannot write the
// display format from compute.

@fragment
fn fxaa_fragment(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {
    return fxaa(vec2<i32>(position.xy));
}
