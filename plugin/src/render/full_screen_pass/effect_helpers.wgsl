// What a post effect's WGSL may call besides its own code (full_screen_pass.rs composes it):
// the colour its images hold to linear colour and back. 8-bit display images hold the sRGB
// curve's values (`ENCODED_SRGB`, generated); HDR and float images hold linear colour already.

fn to_linear(stored: vec3<f32>) -> vec3<f32> {
    return select(stored, decode_srgb(stored), ENCODED_SRGB);
}

fn from_linear(linear: vec3<f32>) -> vec3<f32> {
    return select(linear, encode_srgb(linear), ENCODED_SRGB);
}
