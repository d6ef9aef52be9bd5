// Post-processing, shared by the compute pass and its fragment fallback: tonemapping from the
// HDR scene target (pre-exposed: the lights carry the camera's exposure) to the display target.
// Mirrors `PostSettings` in post_process.rs (the layout test checks them).

struct PostSettings {
    // TONEMAP_* code.
    tonemapping: u32,
    // 1: encode with the sRGB curve (8-bit display target); 0: write linear floats.
    encode_srgb: u32,
    _padding: vec2<u32>,
}

@group(0) @binding(0) var scene: texture_2d<f32>;
// A read-only storage buffer, not a uniform: Mesa's lavapipe (22.x) compiles a shader whose
// uniforms steer its branches again each time its bind group is bound, and keeps every copy.
@group(0) @binding(1) var<storage, read> settings: PostSettings;
// The colour to tonemap: the scene's own, or TAA's history of it (the alpha stays the scene's).
@group(0) @binding(3) var colour_source: texture_2d<f32>;

// The display value of one pixel. A display-referred pixel (the clear colour, a debug view's
// data: render/display_referred.rs) is written as it is.
fn post_process(pixel: vec2<u32>) -> vec4<f32> {
    let hdr = vec4<f32>(textureLoad(colour_source, pixel, 0).rgb, textureLoad(scene, pixel, 0).a);
    var display: vec4<f32>;
    if is_display_referred(hdr.a) {
        display = vec4<f32>(hdr.rgb, displayed_alpha(hdr.a));
    } else {
        display = vec4<f32>(tonemap(hdr.rgb, settings.tonemapping), clamp(hdr.a, 0.0, 1.0));
    }
    if settings.encode_srgb != 0u {
        display = vec4<f32>(encode_srgb(display.rgb), display.a);
    }
    return display;
}
