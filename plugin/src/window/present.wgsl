// Presenting: the display target (sRGB-encoded bytes in a plain Unorm texture, see target.rs)
// drawn texel for texel into a window's swapchain image, or into the viewport of the part of it
// where the scene goes. A swapchain that encodes itself (an
// sRGB format) or holds linear floats gets the decoded colour, any other the bytes as they
// are: either way the screen shows what a capture of the target shows, gamma applied once.

@group(0) @binding(0) var display: texture_2d<f32>;

fn display_texel(viewport_uv: vec2<f32>) -> vec3<f32> {
    // The target follows the viewport's size; for the frame in which they differ, the nearest
    // texel (clamped: the edge).
    let size = textureDimensions(display);
    let texel = vec2<u32>(viewport_uv * vec2<f32>(size));
    return textureLoad(display, min(texel, size - vec2<u32>(1u)), 0).rgb;
}

// For swapchains that take the bytes as they are (`Bgra8Unorm`, say).
@fragment
fn present_encoded(@location(0) viewport_uv: vec2<f32>) -> @location(0) vec4<f32> {
    return vec4<f32>(display_texel(viewport_uv), 1.0);
}

// For swapchains that encode themselves (sRGB formats) or hold linear floats.
@fragment
fn present_decoded(@location(0) viewport_uv: vec2<f32>) -> @location(0) vec4<f32> {
    return vec4<f32>(decode_srgb(display_texel(viewport_uv)), 1.0);
}
