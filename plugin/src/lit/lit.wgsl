// `LitMaterial`: lit, normal-mapped meshes. Composed after the generated enum codes and
// `LitParams` (every declared parameter of the material), the core's frame.wgsl and
// mesh_vertex.wgsl and shadows.wgsl, then tangent_space.wgsl and lighting.wgsl (see lit/mod.rs).

// Pipeline-overridable: masked materials get their own pipelines (discard ends early depth
// writes, so opaque ones must not carry it).
override ALPHA_MASK: bool = false;

@group(0) @binding(2) var<storage, read> materials: array<LitParams>;
@group(1) @binding(0) var base_color_texture: texture_2d<f32>;
@group(1) @binding(1) var normal_map: texture_2d<f32>;
@group(1) @binding(2) var emissive_texture: texture_2d<f32>;
@group(1) @binding(3) var occlusion_texture: texture_2d<f32>;
@group(1) @binding(4) var metallic_roughness_texture: texture_2d<f32>;
@group(1) @binding(5) var material_sampler: sampler;

// Base colour: texture × factor × vertex colour (glTF's product).
fn base_color(in: VertexOut, material: LitParams) -> vec4<f32> {
    return textureSample(base_color_texture, material_sampler, in.uv) * rgba(material.base_color) * in.color;
}

// Whether a masked surface is cut out here.
fn cut_out(alpha: f32, material: LitParams) -> bool {
    return ALPHA_MASK && alpha < material.alpha_cutoff;
}

@fragment
fn fs_main(in: VertexOut, @builtin(front_facing) front_facing: bool) -> @location(0) vec4<f32> {
    let material = materials[in.object_index];
    let base = base_color(in, material);
    if cut_out(base.a, material) {
        discard;
    }
    let emissive = rgba(material.emissive).rgb * material.emissive_strength
        * textureSample(emissive_texture, material_sampler, in.uv).rgb;
    // Opaque and masked surfaces are opaque where drawn (glTF ignores an opaque one's alpha).
    let alpha = select(1.0, base.a, material.alpha_mode == ALPHA_MODE_BLEND);
    if material.unlit != 0u {
        return vec4<f32>(base.rgb + emissive, alpha);
    }
    let surface_frame = facing_tangent_frame(in.world_normal, in.world_tangent, front_facing);
    let normal = perturbed_normal(
        surface_frame,
        textureSample(normal_map, material_sampler, in.uv).xyz,
        material.normal_strength,
    );
    let to_eye = direction_to_eye(in.world_position, normal);
    // glTF: roughness in green, metalness in blue, each times its factor.
    let metallic_roughness = textureSample(metallic_roughness_texture, material_sampler, in.uv);
    let surface = Surface(base.rgb, material.specular_strength, max(material.shininess, 1.0),
        material.roughness * metallic_roughness.g, material.metallic * metallic_roughness.b, material.lighting);

    // glTF's occlusion darkens the indirect (ambient) light only.
    let occlusion = 1.0 + material.occlusion_strength
        * (textureSample(occlusion_texture, material_sampler, in.uv).r - 1.0);
    var color = frame.ambient.rgb * base.rgb * occlusion + emissive;
    let receives_shadows = receives_scene_shadows(in.object_index);
    for (var i = 0u; i < light_count(); i += 1u) {
        let light = light_at(i, in.world_position);
        var visibility = 1.0;
        if receives_shadows && dot(normal, light.to_light) > 0.0 {
            visibility = scene_shadow(i, in.world_position, surface_frame.normal);
        }
        color += light.radiance * visibility * direct_lighting(surface, normal, light.to_light, to_eye);
    }
    return vec4<f32>(color, alpha);
}

// The prepass of a masked surface: its holes write no depth.
@fragment
fn fs_prepass_alpha_mask(in: VertexOut) {
    if cut_out(base_color(in, materials[in.object_index]).a, materials[in.object_index]) {
        discard;
    }
}
