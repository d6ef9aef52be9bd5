// The settled depth as an image, for compute passes that read the scene's depth after a
// deferred resolve settled depth-offset candidates (material/candidates.wgsl) or where the
// polygon pass found surfaces the depth attachment lacks (polygons.wgsl): a pixel whose
// candidate key the resolve settled holds its depth there (the candidate's marched depth where
// it won, else the visibility pass's behind it); else a pixel with a visibility id holds it in
// its visibility key (which the rasterized draws also wrote into the depth attachment); else
// no draw is there: the far plane (every visibility fragment that writes depth keeps a key, and
// the attachment is not even cleared where the visibility pass had nothing to rasterize). One
// compute pass instead of drawing polygons with `frag_depth`.

@group(0) @binding(0) var<storage, read> visibility: array<vec2<u32>>;
@group(0) @binding(1) var settled_depth: texture_storage_2d<r32float, write>;

@compute @workgroup_size(8, 8)
fn cs_settle_depth(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = textureDimensions(settled_depth);
    if id.x >= size.x || id.y >= size.y {
        return;
    }
    // The visibility key read only where the candidate key is empty.
    let candidate = visibility[candidate_index(id.xy, size)];
    var depth: f32;
    if (candidate.x | candidate.y) != 0u {
        depth = bitcast<f32>(~candidate.y);
    } else {
        depth = visible_depth(id.xy, size.x);
    }
    textureStore(settled_depth, id.xy, vec4<f32>(depth, 0.0, 0.0, 0.0));
}
