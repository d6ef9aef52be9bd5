// The parallax material's entry points of the deferred path: its visibility pass where a
// silhouette marches for coverage, and the compute resolves that march and shade each pixel
// the visibility buffer gives them (with depth offset, the candidate keys: see
// `cs_resolve_settling`). Composed after pom.wgsl, visibility.wgsl and
// deferred_resolve.wgsl.

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

// `depth_offset` (with or without a silhouette): the candidate pass kept the nearest polygon
// by its own depth, a bound of every displaced depth on it; the march runs here, once, and the
// relief shows where its displaced depth is nearer than what the visibility pass kept behind
// it and the view ray stays on the surface. Not exact where two depth-offset surfaces overlap
// within one's relief depth: only the nearer polygon is marched.
@compute @workgroup_size(TILE_SIDE, TILE_SIDE)
fn cs_resolve_settling(@builtin(workgroup_id) group: vec3<u32>, @builtin(local_invocation_id) local: vec3<u32>) {
    let item = resolve_item(group.xy, local.xy);
    if !item.resolves {
        return;
    }
    let pixel = resolve_pixel(item);
    let point = covering_surface(pixel.vertex, view_ray(pixel.vertex, pixel.front_facing, pixel.footprint));
    if settle_candidate(item.pixel, marched_depth(pixel.vertex, point), !point.clipped) {
        textureStore(scene_output, item.pixel, shade(pixel.vertex, point));
    }
}
