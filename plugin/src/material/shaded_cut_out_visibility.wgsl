// The visibility pass of a shaded material that cuts holes (shaded_cut_out.wgsl): a hole keeps
// neither depth nor id. Composed after visibility.wgsl.

@fragment
fn fs_visibility_cut_out(in: VertexOut, @builtin(front_facing) front_facing: bool,
    @builtin(primitive_index) triangle: u32) {
    if !covers(surface_input(in, front_facing, fragment_footprint(in)), materials[in.object_index]) {
        discard;
    }
    keep_visible(in.clip_position, in.clip_position.z, visibility_id(in.object_index, triangle));
}
