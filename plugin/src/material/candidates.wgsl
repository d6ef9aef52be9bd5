// The candidate pass and the settled depth (`MeshPass::Candidate`, `MeshPass::SettledDepth`) of
// a material whose resolve settles its depth (`Material::settles_depth_in_resolve`: parallax
// depth offset). After the visibility keys the buffer holds as many candidate keys, keyed
// alike: per pixel the nearest such polygon by its own depth. The resolve settles each against
// the visibility key (its march finds the real depth) and leaves the winner or 0. Composed
// after visibility.wgsl.

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
