// Heights in Tatarchuk's convention (1 = the top, 0 = the deepest point) from a texture that
// holds them in one channel, white meaning either the top or (depth maps) the deepest point.
// Shared by the parallax march and the core's maximum pyramid build.

// The values of one channel in Tatarchuk's convention.
fn heights_in_convention(values: vec4<f32>, depth_convention: u32) -> vec4<f32> {
    return select(values, 1.0 - values, depth_convention != 0u);
}

// The height a texel holds in `channel` (0 = red .. 3 = alpha).
fn height_in_channel(texel: vec4<f32>, channel: u32, depth_convention: u32) -> f32 {
    return heights_in_convention(vec4<f32>(texel[min(channel, 3u)]), depth_convention).x;
}
