// The parallax material's entry points of the deferred path: its visibility pass where the
// prepass moves the depth, and the compute resolve that marches and shades each pixel the
// visibility buffer gives it. Composed after pom.wgsl, visibility.wgsl and deferred_resolve.wgsl.

// `depth_offset` in the visibility pass: the displaced depth (as `fs_prepass_depth_offset`),
// which is also the depth the id is merged with, so the pixel keeps whichever surface is really
// nearest.
@fragment @early_depth_test(greater_equal)
fn fs_visibility_depth_offset(in: VertexOut, @builtin(front_facing) front_facing: bool,
    @builtin(primitive_index) triangle: u32) -> @builtin(frag_depth) f32 {
    let depth = displaced_depth(in, find_surface(in, front_facing, fragment_footprint(in)));
    keep_visible(in.clip_position, depth, visibility_id(in.object_index, triangle));
    return depth;
}

// One workgroup per 8 × 8 tile the batch shows in: its pixels march and shade as the fragment
// entry points do; the tile's other pixels return at once.
@compute @workgroup_size(TILE_SIDE, TILE_SIDE)
fn cs_resolve(@builtin(workgroup_id) group: vec3<u32>, @builtin(local_invocation_id) local: vec3<u32>) {
    let item = resolve_item(group.xy, local.xy);
    if !item.resolves {
        return;
    }
    let pixel = resolve_pixel(item);
    let point = find_surface(pixel.vertex, pixel.front_facing, pixel.footprint);
    textureStore(scene_output, item.pixel, shade(pixel.vertex, point));
}
