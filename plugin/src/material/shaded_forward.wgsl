// The fragment entry the core writes around a shaded material's `shade` function: the opaque
// phase of the forward path (with or without a depth prepass). The prepass, the shadow maps and
// the visibility pass need no fragment stage of the material's: its surface lies on its polygons.

@fragment
fn fs_main(in: VertexOut, @builtin(front_facing) front_facing: bool) -> @location(0) vec4<f32> {
    let surface = surface_input(in, front_facing, fragment_footprint(in));
    return shade(surface, materials[in.object_index]);
}
