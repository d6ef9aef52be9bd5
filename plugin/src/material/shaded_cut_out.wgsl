// The entry points the core writes around a shaded material that cuts holes in its surface
// (ShadedMaterial::CUTS_OUT): its `covers` function decides, where the surface is, whether it is
// there at all. The prepass and the shadow maps leave the holes out of the depth, the visibility
// pass out of the visibility buffer, and the forward path's opaque phase out of the image (after
// a prepass, a hole's own fragment would pass the depth test over what the prepass saw through
// it). The deferred resolve needs no twin: it shades only pixels the visibility pass kept.

@fragment
fn fs_main_cut_out(in: VertexOut, @builtin(front_facing) front_facing: bool) -> @location(0) vec4<f32> {
    let surface = surface_input(in, front_facing, fragment_footprint(in));
    let material = materials[in.object_index];
    if !covers(surface, material) {
        discard;
    }
    return shade(surface, material);
}

// The depth prepass and every shadow map.
@fragment
fn fs_prepass_cut_out(in: VertexOut, @builtin(front_facing) front_facing: bool) {
    if !covers(surface_input(in, front_facing, fragment_footprint(in)), materials[in.object_index]) {
        discard;
    }
}
