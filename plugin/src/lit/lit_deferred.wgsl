// The lit material's visibility pass where the prepass has a fragment stage of its own: a
// masked surface's holes keep neither depth nor id. Composed after lit.wgsl and visibility.wgsl.

@fragment
fn fs_visibility_alpha_mask(in: VertexOut, @builtin(primitive_index) triangle: u32) {
    if cut_out(base_color(in, materials[in.object_index]).a, materials[in.object_index]) {
        discard;
    }
    keep_visible(in.clip_position, in.clip_position.z, visibility_id(in.object_index, triangle));
}
