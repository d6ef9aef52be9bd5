// FXAA as a compute pass, one invocation per pixel. `output` is declared by the generated
// prelude with the display target's storage format.

@compute @workgroup_size(8, 8, 1)
fn fxaa_main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = textureDimensions(tonemapped);
    if id.x >= size.x || id.y >= size.y {
        return;
    }
    textureStore(output, id.xy, fxaa(vec2<i32>(id.xy)));
}
