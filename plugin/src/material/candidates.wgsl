// The candidate pass and the settled depth (`MeshPass::Candidate`, `MeshPass::SettledDepth`) of
// a material whose resolve settles its depth (`Material::settles_depth_in_resolve`: parallax
// depth offset). After the visibility keys the buffer holds as many candidate keys, keyed
// alike: per pixel the nearest such polygon by its own depth. The resolve settles each against
// the visibility key (its march finds the real depth) and leaves the winner's id or 0, with
// the pixel's settled depth either way. Composed after visibility.wgsl.

// The index of the candidate key of framebuffer position `position`.
fn candidate_key_index(position: vec4<f32>) -> u32 {
    return frame.target_size.x * frame.target_size.y + visibility_key_index(position);
}

// The candidate pass: a polygon whose visible depth lies behind it merges into the candidate
// keys at its own depth, tested and written early (depth compare `Less` against the visibility
// pass), so a polygon behind a nearer one never runs; the march waits for the resolve.
@fragment @early_depth_test(force)
fn fs_visibility_candidate(in: VertexOut, @builtin(primitive_index) triangle: u32) {
    count_fragment_invocation();
    atomicMax(&visibility_keys[candidate_key_index(in.clip_position)], visibility_key(in.clip_position.z, visibility_id(in.object_index, triangle)));
}

// After the resolve, where a later pass tests against the depth, the candidates' polygons
// again, depth compare `Always`: a candidate key the resolve settled holds the pixel's settled
// depth (the candidate's marched depth where it won, else the visibility pass's behind it);
// elsewhere the polygon lost the depth test and the depth buffer is already right (as
// render/visibility/settled_depth.wgsl reads it for compute passes).
@fragment
fn fs_settled_depth(in: VertexOut) -> @builtin(frag_depth) f32 {
    let index = candidate_key_index(in.clip_position);
    let depth_bits = atomicLoad(&visibility_words[2u * index + 1u]);
    if (atomicLoad(&visibility_words[2u * index]) | depth_bits) == 0u {
        discard;
    }
    return bitcast<f32>(~depth_bits);
}
