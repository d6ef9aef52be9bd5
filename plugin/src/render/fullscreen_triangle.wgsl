// The vertex stage of full-screen passes: one triangle, (-1,-1), (3,-1), (-1,3), covering the
// whole target (or the viewport) with no vertex buffer. Draw it with `draw(0..3, 0..1)`.

struct FullscreenVertex {
    @builtin(position) position: vec4<f32>,
    // 0..1 across the viewport, from its top-left corner (passes drawn into part of an image).
    @location(0) viewport_uv: vec2<f32>,
}

@vertex
fn fullscreen_vertex(@builtin(vertex_index) index: u32) -> FullscreenVertex {
    let corner = vec2<f32>(f32((index << 1u) & 2u), f32(index & 2u));
    return FullscreenVertex(vec4<f32>(corner * 2.0 - 1.0, 0.0, 1.0), vec2<f32>(corner.x, 1.0 - corner.y));
}
