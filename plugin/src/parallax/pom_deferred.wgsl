// The parallax material's entry points of the deferred path: its visibility pass where the
// prepass marches for its depth or coverage, and the compute resolve that marches and shades
// each pixel the visibility buffer gives it. Composed after pom.wgsl, visibility.wgsl and
// deferred_resolve.wgsl.

// `depth_offset` (with or without a silhouette) in the visibility pass: the depth of `fs_prepass_marched_depth`,
// which is also the depth the id is merged with, so the pixel keeps whichever surface is really
// nearest, and no id where the view ray left the surface. A fragment already behind what its
// pixel kept is dropped before it marches: with a depth write and the merge's side effect the
// GPU tests depth late, whatever the attribute promises (without this, hidden planes cost far
// more: sandbox/BENCHMARKS.md, "Stacked planes (overdraw) and depth offset"). The footprint's
// derivatives come first, while the whole quad still runs.
@fragment @early_depth_test(greater_equal)
fn fs_visibility_marched_depth(in: VertexOut, @builtin(front_facing) front_facing: bool,
    @builtin(primitive_index) triangle: u32) -> @builtin(frag_depth) f32 {
    let footprint = fragment_footprint(in);
    if behind_kept_depth(in.clip_position) {
        discard;
    }
    let point = covering_surface(in, view_ray(in, front_facing, footprint));
    if point.clipped {
        discard;
    }
    let depth = marched_depth(in, point);
    keep_visible(in.clip_position, depth, visibility_id(in.object_index, triangle));
    return depth;
}

// A silhouette without depth offset in the visibility pass: the polygon's depth, written by the
// rasterizer (as `fs_prepass_clipped`), and no id where the view ray left the surface.
@fragment
fn fs_visibility_clipped(in: VertexOut, @builtin(front_facing) front_facing: bool,
    @builtin(primitive_index) triangle: u32) {
    if covering_surface(in, view_ray(in, front_facing, fragment_footprint(in))).clipped {
        discard;
    }
    keep_visible(in.clip_position, in.clip_position.z, visibility_id(in.object_index, triangle));
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
    // Coverage was the visibility pass's: a pixel it kept is shaded even where this march, from
    // the rebuilt footprint, would clip it by a rounding.
    let point = find_surface(pixel.vertex, pixel.front_facing, pixel.footprint);
    textureStore(scene_output, item.pixel, shade(pixel.vertex, point));
}
