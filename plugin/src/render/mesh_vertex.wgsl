// Vertex input, the per-draw transforms and the vertex stage every material shares. Mirrors
// `MeshTransform` in gpu_types.rs (the layout test checks them against each other).

struct MeshTransform {
    model: mat4x4<f32>,
    // Inverse transpose of `model`, for normals under non-uniform scale.
    normal_matrix: mat4x4<f32>,
    // Sign of det(model): mirroring flips the bitangent.
    determinant_sign: f32,
    // 1 where scene shadows fall on the object (0: NotShadowReceiver).
    receives_shadows: u32,
    // Deferred path: the visibility id of the object's first triangle (visibility.wgsl).
    first_visibility_id: u32,
    // Under TAA, the number of the draw's motion since the last frame (object_motion.rs); 0: still.
    motion: u32,
}

@group(0) @binding(1) var<storage, read> transforms: array<MeshTransform>;

struct VertexIn {
    @location(0) position: vec3<f32>,
    @location(1) normal: vec3<f32>,
    @location(2) uv: vec2<f32>,
    // xyz: dP/du, w: sign so that cross(normal, tangent) * w = dP/dv (MikkTSpace).
    @location(3) tangent: vec4<f32>,
    // Linear RGBA, multiplied with the base colour (white when the mesh has none).
    @location(4) color: vec4<f32>,
}

struct VertexOut {
    // Invariant: the prepass and the opaque phase compile this vertex stage into different
    // pipelines, and their depths must agree bit for bit.
    @builtin(position) @invariant clip_position: vec4<f32>,
    @location(0) world_position: vec3<f32>,
    @location(1) world_normal: vec3<f32>,
    @location(2) uv: vec2<f32>,
    @location(3) world_tangent: vec4<f32>,
    @location(4) @interpolate(flat) object_index: u32,
    @location(5) color: vec4<f32>,
}

// `normal_matrix` is the inverse transpose of `model`; `determinant_sign` flips the bitangent of
// mirrored objects.
fn transform_vertex(
    in: VertexIn,
    model: mat4x4<f32>,
    normal_matrix: mat4x4<f32>,
    determinant_sign: f32,
    object_index: u32,
) -> VertexOut {
    let world_position = model * vec4<f32>(in.position, 1.0);
    var out: VertexOut;
    out.clip_position = frame.view_projection * world_position;
    out.world_position = world_position.xyz;
    out.world_normal = (normal_matrix * vec4<f32>(in.normal, 0.0)).xyz;
    out.world_tangent = vec4<f32>((model * vec4<f32>(in.tangent.xyz, 0.0)).xyz, in.tangent.w * determinant_sign);
    out.uv = in.uv;
    out.color = in.color;
    out.object_index = object_index;
    return out;
}

// Draw instances index the per-draw arrays (`transforms`, a material's uniforms).
@vertex
fn vs_main(in: VertexIn, @builtin(instance_index) object_index: u32) -> VertexOut {
    let transform = transforms[object_index];
    return transform_vertex(in, transform.model, transform.normal_matrix, transform.determinant_sign, object_index);
}

// TAA's object motion pass (object_motion.rs): a moving draw marks the pixels it shows with its
// motion's number, tested against the frame's depth; a still draw's triangles collapse outside
// the clip volume. The position is vs_main's (one function computes both), so its depth equals the prepass's bit for bit.
@vertex
fn vs_motion(in: VertexIn, @builtin(instance_index) object_index: u32) -> VertexOut {
    let transform = transforms[object_index];
    var out = transform_vertex(in, transform.model, transform.normal_matrix, transform.determinant_sign, object_index);
    if transform.motion == 0u {
        out.clip_position = vec4<f32>(0.0, 0.0, 2.0, 1.0);
    }
    return out;
}

@fragment
fn fs_motion(in: VertexOut) -> @location(0) u32 {
    return transforms[in.object_index].motion;
}

// What a pixel covers: the change of the texture coordinate and of the world position from one
// pixel to the next, across and down. Materials take it as an argument and use no stage
// built-in, so the deferred resolve (deferred_resolve.wgsl), which knows the pixel's rays, calls
// them as the fragment stage does. The true derivatives: a texture read scales them by
// `texture_gradient_scale()` (anti-aliasing's mip bias), geometry takes them as they are.
struct PixelFootprint {
    ddx_uv: vec2<f32>,
    ddy_uv: vec2<f32>,
    ddx_world: vec3<f32>,
    ddy_world: vec3<f32>,
    // Of the interpolated (not normalized) world normal: with the position's, the surface's
    // curvature.
    ddx_normal: vec3<f32>,
    ddy_normal: vec3<f32>,
}

// The fragment stage's footprint: screen-space derivatives, taken once before any branch.
fn fragment_footprint(in: VertexOut) -> PixelFootprint {
    return PixelFootprint(dpdx(in.uv), dpdy(in.uv), dpdx(in.world_position), dpdy(in.world_position),
        dpdx(in.world_normal), dpdy(in.world_normal));
}

// What texture gradients (and the levels chosen from them) are scaled by: 2 to the mip bias of
// TAA or the post filter, so textures are read finer; 1 without anti-aliasing.
fn texture_gradient_scale() -> f32 {
    return frame.texture_lod.x;
}
