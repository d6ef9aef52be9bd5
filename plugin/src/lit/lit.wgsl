// `LitMaterial`: lit, normal-mapped meshes. Composed after the generated enum codes and
// `LitParams` (every declared parameter of the material), the core's frame.wgsl and
// mesh_vertex.wgsl, then tangent_space.wgsl and lighting.wgsl (see lit/mod.rs).

@group(0) @binding(2) var<storage, read> materials: array<LitParams>;
@group(1) @binding(0) var base_color_texture: texture_2d<f32>;
@group(1) @binding(1) var normal_map: texture_2d<f32>;
@group(1) @binding(2) var material_sampler: sampler;

@fragment
fn fs_main(in: VertexOut, @builtin(front_facing) front_facing: bool) -> @location(0) vec4<f32> {
    let material = materials[in.object_index];
    let surface_frame = facing_tangent_frame(in.world_normal, in.world_tangent, front_facing);
    let normal = perturbed_normal(
        surface_frame,
        textureSample(normal_map, material_sampler, in.uv).xyz,
        material.normal_strength,
    );
    let base = textureSample(base_color_texture, material_sampler, in.uv) * rgba(material.base_color);
    let to_eye = direction_to_eye(in.world_position, normal);
    let surface = Surface(base.rgb, material.specular_strength, max(material.shininess, 1.0), 1.0, 0.0, LIGHTING_BLINN_PHONG);

    var color = frame.ambient.rgb * base.rgb;
    for (var i = 0u; i < light_count(); i += 1u) {
        let light = light_at(i, in.world_position);
        color += light.radiance * direct_lighting(surface, normal, light.to_light, to_eye);
    }
    return vec4<f32>(color, base.a);
}
