// Forward pass for `LitMaterial`: lit, normal-mapped meshes. Composed after frame.wgsl,
// tangent_space.wgsl, lighting.wgsl and mesh_vertex.wgsl (see shaders.rs).

struct Object {
    model: mat4x4<f32>,
    // Inverse transpose of the model matrix, for normals under non-uniform scale.
    normal_matrix: mat4x4<f32>,
    base_color: vec4<f32>,
    // x: normal map strength, y: specular strength, z: shininess exponent,
    // w: sign of the model matrix determinant (mirroring flips the bitangent).
    params: vec4<f32>,
}

@group(0) @binding(1) var<storage, read> objects: array<Object>;
@group(1) @binding(0) var base_color_texture: texture_2d<f32>;
@group(1) @binding(1) var normal_map: texture_2d<f32>;
@group(1) @binding(2) var material_sampler: sampler;

@vertex
fn vs_main(in: VertexIn, @builtin(instance_index) object_index: u32) -> VertexOut {
    let object = objects[object_index];
    return transform_vertex(in, object.model, object.normal_matrix, object.params.w, object_index);
}

@fragment
fn fs_main(in: VertexOut) -> @location(0) vec4<f32> {
    let object = objects[in.object_index];
    let surface_frame = tangent_frame(in.world_normal, in.world_tangent);
    let normal = perturbed_normal(
        surface_frame,
        textureSample(normal_map, material_sampler, in.uv).xyz,
        object.params.x,
    );
    let base = textureSample(base_color_texture, material_sampler, in.uv) * object.base_color;
    let to_eye = direction_to_eye(in.world_position, normal);
    let surface = Surface(base.rgb, object.params.y, max(object.params.z, 1.0), 1.0, 0.0, LIGHTING_BLINN_PHONG);

    var color = frame.ambient.rgb * base.rgb;
    for (var i = 0u; i < light_count(); i += 1u) {
        let light = light_at(i, in.world_position);
        color += light.radiance * direct_lighting(surface, normal, light.to_light, to_eye);
    }
    return vec4<f32>(color, base.a);
}
