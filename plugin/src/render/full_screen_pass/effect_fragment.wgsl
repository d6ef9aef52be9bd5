// A post effect as a full-screen triangle (fullscreen_triangle.wgsl), where the adapter cannot
// write the image's format from compute.

@fragment
fn effect_fragment(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {
    return effect(vec2<u32>(position.xy));
}
