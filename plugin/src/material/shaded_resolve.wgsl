// The compute entry the core writes around a shaded material's `shade` function: the deferred
// resolve, one workgroup per 8 × 8 tile its batch shows in, each pixel rebuilt from its
// visibility id and shaded as the fragment entry shades it. Composed after
// deferred_resolve.wgsl.

@compute @workgroup_size(TILE_SIDE, TILE_SIDE)
fn cs_resolve(@builtin(workgroup_id) group: vec3<u32>, @builtin(local_invocation_id) local: vec3<u32>) {
    let item = resolve_item(group.xy, local.xy);
    if !item.resolves {
        return;
    }
    let pixel = resolve_pixel(item);
    let surface = surface_input(pixel.vertex, pixel.front_facing, pixel.footprint);
    textureStore(scene_output, item.pixel, shade(surface, materials[item.object_index]));
}
