// Post-processing as a full-screen triangle, for adapters that cannot write the display
// format from compute.

@vertex
fn post_vertex(@builtin(vertex_index) index: u32) -> @builtin(position) vec4<f32> {
    // (-1,-1), (3,-1), (-1,3): one triangle covering the target.
    let uv = vec2<f32>(f32((index << 1u) & 2u), f32(index & 2u));
    return vec4<f32>(uv * 2.0 - 1.0, 0.0, 1.0);
}

@fragment
fn post_fragment(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {
    return post_process(vec2<u32>(position.xy));
}
