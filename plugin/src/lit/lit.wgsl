// `LitMaterial`: lit, normal-mapped meshes. Composed after the core's frame.wgsl and
// mesh_vertex.wgsl, then tangent_space.wgsl and lighting.wgsl (see lit/mod.rs). Mirrors
// `LitUniform` (the layout test checks them against each other).

struct LitUniform {
    base_color: vec4<f32>,
    // Scales the normal map's tilt.
    normal_strength: f32,
    specular_strength: f32,
    // Blinn-Phong exponent.
    shininess: f32,
    _padding: f32,
}

@group(0) @binding(2) var<storage, read> materials: array<LitUniform>;
@group(1) @binding(0) var base_color_texture: texture_2d<f32>;
@group(1) @binding(1) var normal_map: texture_2d<f32>;
@group(1) @binding(2) var material_sampler: sampler;

@fragment
fn fs_main(in: VertexOut) -> @location(0) vec4<f32> {
    let material = materials[in.object_index];
    let surface_frame = tangent_frame(in.world_normal, in.world_tangent);
    let normal = perturbed_normal(
        surface_frame,
        textureSample(normal_map, material_sampler, in.uv).xyz,
        material.normal_strength,
    );
    let base = textureSample(base_color_texture, material_sampler, in.uv) * material.base_color;
    let to_eye = direction_to_eye(in.world_position, normal);
    let surface = Surface(base.rgb, material.specular_strength, max(material.shininess, 1.0), 1.0, 0.0, LIGHTING_BLINN_PHONG);

    var color = frame.ambient.rgb * base.rgb;
    for (var i = 0u; i < light_count(); i += 1u) {
        let light = light_at(i, in.world_position);
        color += light.radiance * direct_lighting(surface, normal, light.to_light, to_eye);
    }
    return vec4<f32>(color, base.a);
}
