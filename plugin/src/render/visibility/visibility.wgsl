// The visibility pass, the deferred path's prepass: with its depth, each pixel keeps one 32-bit
// id that names the draw and the triangle it shows. Each draw owns a run of ids, one per
// triangle, starting at its `first_visibility_id` (mesh_vertex.wgsl); 0 marks a pixel no
// opaque draw covers. Composed after a material's files (with `enable primitive_index;`) where
// the adapter can run the deferred path.

// One 64-bit key per pixel, row by row: the depth's bits inverted above the id, so that
// atomicMax keeps the nearest fragment whatever the order fragments arrive in (ties: the larger
// id). Cleared to 0 before the pass; outside it a one-key stand-in is bound. As many candidate
// keys follow (material/candidates.wgsl).
@group(0) @binding(8) var<storage, read_write> visibility_keys: array<atomic<u64>>;
// The same keys as 32-bit words (little-endian: a key's depth is its odd word), for reading a
// key: WGSL's 64-bit atomics offer only min and max.
@group(0) @binding(9) var<storage, read_write> visibility_words: array<atomic<u32>>;

// The id a pixel of draw `object_index`, triangle `triangle`, keeps: 0 for a draw the frame
// had no ids left for (it then shows the background rather than another draw's triangle).
fn visibility_id(object_index: u32, triangle: u32) -> u32 {
    let first = transforms[object_index].first_visibility_id;
    return select(first + triangle, 0u, first == 0u);
}

// Merges `id`, seen at framebuffer position `position` at clip depth `depth`, into the pixel's
// key (and counts the merge where a test counts fragments: FragmentInvocationCounter).
fn keep_visible(position: vec4<f32>, depth: f32, id: u32) {
    count_fragment_invocation();
    atomicMax(&visibility_keys[visibility_key_index(position)], visibility_key(depth, id));
}

// The index of the key of framebuffer position `position`.
fn visibility_key_index(position: vec4<f32>) -> u32 {
    let pixel = vec2<u32>(position.xy);
    return pixel.y * frame.target_size.x + pixel.x;
}

// The key of `id` at clip depth `depth`: nearer depths compare larger.
fn visibility_key(depth: f32, id: u32) -> u64 {
    return (u64(~bitcast<u32>(depth)) << 32u) | u64(id);
}

// The visibility pass of a material whose prepass has no fragment stage of its own. The depth
// test runs first (forced: the atomic is the only side effect, and a fragment it rejects could
// only have lost the merge).
@fragment @early_depth_test(force)
fn fs_visibility(in: VertexOut, @builtin(primitive_index) triangle: u32) {
    keep_visible(in.clip_position, in.clip_position.z, visibility_id(in.object_index, triangle));
}
