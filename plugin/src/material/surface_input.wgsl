// What a shaded material's `shade` function is given (pom::material::ShadedMaterial): one point
// of its surface as the fragment stage or the deferred resolve sees it, and the helpers it
// samples textures and scene shadows with. Composed after the core's frame.wgsl,
// mesh_vertex.wgsl, shadows.wgsl and tangent_space.wgsl, and the material's generated
// declarations (`MaterialParams`, `materials`, its textures and `material_sampler`).

struct SurfaceInput {
    // The point, in world space.
    position: vec3<f32>,
    // Unit normal of the side the eye sees, interpolated from the vertices.
    normal: vec3<f32>,
    // That side's tangent frame (normal, unit dP/du and dP/dv), for `perturbed_normal`.
    tangent_frame: TangentFrame,
    // Texture coordinate.
    uv: vec2<f32>,
    // Vertex colour, linear (white where the mesh has none).
    color: vec4<f32>,
    // Unit vector from the point towards the eye.
    to_eye: vec3<f32>,
    // What the pixel covers: `texture_at` samples with it, on both paths alike.
    footprint: PixelFootprint,
    // The draw's index into the per-draw arrays (`materials`, `transforms`).
    object_index: u32,
    // Whether the eye sees the front (counter-clockwise) side.
    front_facing: bool,
}

// The surface input at a rasterized or resolved point.
fn surface_input(vertex: VertexOut, front_facing: bool, footprint: PixelFootprint) -> SurfaceInput {
    let tangent_frame = facing_tangent_frame(vertex.world_normal, vertex.world_tangent, front_facing);
    return SurfaceInput(vertex.world_position, tangent_frame.normal, tangent_frame, vertex.uv, vertex.color,
        direction_to_eye(vertex.world_position, tangent_frame.normal), footprint, vertex.object_index, front_facing);
}

// `texture` at the surface's texture coordinate, filtered over the pixel's footprint (trilinear,
// repeating; finer under anti-aliasing's mip bias). Explicit gradients, because the deferred
// resolve is a compute pass.
fn texture_at(texture: texture_2d<f32>, surface: SurfaceInput) -> vec4<f32> {
    let scale = texture_gradient_scale();
    return textureSampleGrad(texture, material_sampler, surface.uv, surface.footprint.ddx_uv * scale,
        surface.footprint.ddy_uv * scale);
}

// How much of light `light_index` (as `light_at` numbers them) reaches the surface past the
// scene's shadows: 1 = all, 0 = none; 1 where the draw receives no scene shadows.
fn surface_shadow(light_index: u32, surface: SurfaceInput) -> f32 {
    if !receives_scene_shadows(surface.object_index) {
        return 1.0;
    }
    return scene_shadow(light_index, surface.position, surface.normal);
}
