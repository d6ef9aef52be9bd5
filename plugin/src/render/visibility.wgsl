// The visibility pass, the deferred path's prepass: with its depth, each pixel keeps one 32-bit
// id that names the draw and the triangle it shows. Each draw owns a run of ids, one per
// triangle, starting at its `first_visibility_id` (mesh_vertex.wgsl); 0 marks a pixel no
// opaque draw covers. Composed after a material's files (with `enable primitive_index;`) where
// the adapter can run the deferred path.

// One 64-bit key per pixel, row by row: the depth's bits inverted above the id, so that
// atomicMax keeps the nearest fragment whatever the order fragments arrive in (ties: the larger
// id). Cleared to 0 before the pass; outside it a one-key stand-in is bound. After the
// visibility keys, as many candidate keys, keyed alike: per pixel the nearest polygon, by its
// own depth, of a draw whose visible depth lies behind its polygon (parallax depth offset,
// `MeshPass::Candidate`), merged in the candidate pass; the resolve settles each against the
// visibility key (the candidate's march finds its real depth) and leaves the winner or 0.
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

// The index of the candidate key of framebuffer position `position`.
fn candidate_key_index(position: vec4<f32>) -> u32 {
    return frame.target_size.x * frame.target_size.y + visibility_key_index(position);
}

// Key `index` read: x 1 where it names a draw (0: cleared), y its clip depth.
fn kept_key_depth(index: u32) -> vec2<f32> {
    let id = atomicLoad(&visibility_words[2u * index]);
    let depth = bitcast<f32>(~atomicLoad(&visibility_words[2u * index + 1u]));
    return vec2<f32>(select(0.0, 1.0, id != 0u), depth);
}

// The visibility pass of a material whose prepass has no fragment stage of its own. The depth
// test runs first (forced: the atomic is the only side effect, and a fragment it rejects could
// only have lost the merge).
@fragment @early_depth_test(force)
fn fs_visibility(in: VertexOut, @builtin(primitive_index) triangle: u32) {
    keep_visible(in.clip_position, in.clip_position.z, visibility_id(in.object_index, triangle));
}

// The candidate pass: a polygon whose visible depth lies behind it merges into the candidate
// keys at its own depth, tested and written early (depth compare `Less` against the visibility
// pass), so a polygon behind a nearer one never runs; the march waits for the resolve.
@fragment @early_depth_test(force)
fn fs_visibility_candidate(in: VertexOut, @builtin(primitive_index) triangle: u32) {
    count_fragment_invocation();
    atomicMax(&visibility_keys[candidate_key_index(in.clip_position)], visibility_key(in.clip_position.z, visibility_id(in.object_index, triangle)));
}

// After the resolve, the candidates' polygons again, depth compare `Always`: the depth buffer
// gets each pixel's settled depth (a winning candidate's marched depth, else the visibility
// pass's, or the far plane where neither shows).
@fragment
fn fs_settled_depth(in: VertexOut) -> @builtin(frag_depth) f32 {
    let candidate = kept_key_depth(candidate_key_index(in.clip_position));
    if candidate.x != 0.0 {
        return candidate.y;
    }
    let visible = kept_key_depth(visibility_key_index(in.clip_position));
    return select(1.0, visible.y, visible.x != 0.0);
}
