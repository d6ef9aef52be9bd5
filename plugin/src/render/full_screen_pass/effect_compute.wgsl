// A post effect in compute (full_screen_pass.rs): one invocation per pixel, writing `output`,
// which the generated prelude declares with the image's storage format.

@compute @workgroup_size(8, 8, 1)
fn effect_compute(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = textureDimensions(input);
    if id.x >= size.x || id.y >= size.y {
        return;
    }
    textureStore(output, id.xy, effect(id.xy));
}
