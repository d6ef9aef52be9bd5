// The visibility pass, the deferred path's prepass: with its depth, each pixel keeps one 32-bit
// id that names the draw and the triangle it shows. Each draw owns a run of ids, one per
// triangle, starting at its `first_visibility_id` (mesh_vertex.wgsl); 0 marks a pixel no
// opaque draw covers (the pass clears to it). Composed after a material's files (with
// `enable primitive_index;`) where the adapter can run the deferred path.

// The id a pixel of draw `object_index`, triangle `triangle`, keeps.
fn visibility_id(object_index: u32, triangle: u32) -> u32 {
    return transforms[object_index].first_visibility_id + triangle;
}

// The visibility pass of a material whose prepass has no fragment stage of its own. No depth
// written and no side effects: the depth test runs before it.
@fragment @early_depth_test(force)
fn fs_visibility(in: VertexOut, @builtin(primitive_index) triangle: u32) -> @location(0) u32 {
    return visibility_id(in.object_index, triangle);
}
