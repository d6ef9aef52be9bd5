// The vertex stage of full-screen passes: one triangle, (-1,-1), (3,-1), (-1,3), covering the
// whole target with no vertex buffer. Draw it with `draw(0..3, 0..1)`.

@vertex
fn fullscreen_vertex(@builtin(vertex_index) index: u32) -> @builtin(position) vec4<f32> {
    let corner = vec2<f32>(f32((index << 1u) & 2u), f32(index & 2u));
    return vec4<f32>(corner * 2.0 - 1.0, 0.0, 1.0);
}
