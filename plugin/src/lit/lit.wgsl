// `LitMaterial`: lit, normal-mapped meshes, written as a shading function over the core's
// `SurfaceInput` (material/surface_input.wgsl), so the seam's entry points (shaded_forward.wgsl,
// shaded_cut_out*.wgsl, shaded_resolve.wgsl) run it on both paths: on the deferred one an opaque
// or masked surface shades in the compute resolve. Composed after the generated enum codes and
// `LitParams` (every declared parameter of the material), the core's frame.wgsl, mesh_vertex.wgsl,
// shadows.wgsl, tangent_space.wgsl, lighting.wgsl and surface_input.wgsl (see lit/mod.rs).

@group(0) @binding(2) var<storage, read> materials: array<LitParams>;
@group(1) @binding(0) var base_color_texture: texture_2d<f32>;
@group(1) @binding(1) var normal_map: texture_2d<f32>;
@group(1) @binding(2) var emissive_texture: texture_2d<f32>;
@group(1) @binding(3) var occlusion_texture: texture_2d<f32>;
@group(1) @binding(4) var metallic_roughness_texture: texture_2d<f32>;
@group(1) @binding(5) var material_sampler: sampler;

// Base colour: texture × factor × vertex colour (glTF's product).
fn base_color(surface: SurfaceInput, material: LitParams) -> vec4<f32> {
    return texture_at(base_color_texture, surface) * rgba(material.base_color) * surface.color;
}

// Whether the surface is there: a masked one is cut out where its alpha is below the cutoff
// (only masked draws' pipelines ask, see LitPipelineKey).
fn covers(surface: SurfaceInput, material: LitParams) -> bool {
    return base_color(surface, material).a >= material.alpha_cutoff;
}

fn shade(surface: SurfaceInput, material: LitParams) -> vec4<f32> {
    let base = base_color(surface, material);
    let emissive = rgba(material.emissive).rgb * material.emissive_strength
        * texture_at(emissive_texture, surface).rgb;
    // Opaque and masked surfaces are opaque where drawn (glTF ignores an opaque one's alpha).
    let alpha = select(1.0, base.a, material.alpha_mode == ALPHA_MODE_BLEND);
    if material.unlit != 0u {
        return vec4<f32>(base.rgb + emissive, alpha);
    }
    let normal = perturbed_normal(surface.tangent_frame, texture_at(normal_map, surface).xyz,
        material.normal_strength);
    let to_eye = direction_to_eye(surface.position, normal);
    // glTF: roughness in green, metalness in blue, each times its factor.
    let metallic_roughness = texture_at(metallic_roughness_texture, surface);
    let reflecting = Surface(base.rgb, material.specular_strength, max(material.shininess, 1.0),
        material.roughness * metallic_roughness.g, material.metallic * metallic_roughness.b, material.lighting);

    // glTF's occlusion darkens the indirect light (ambient or environment) only.
    let occlusion = 1.0 + material.occlusion_strength * (texture_at(occlusion_texture, surface).r - 1.0);
    var color = ambient_lighting(reflecting, normal, to_eye, vec2<f32>(occlusion)) + emissive;
    let lights = lights_near(surface.position);
    for (var k = 0u; k < lights.count; k += 1u) {
        let i = light_in(lights, k);
        let light = light_at(i, surface.position);
        // A light behind the perturbed normal reflects nothing: no shadow lookup for it.
        var visibility = 1.0;
        if dot(normal, light.to_light) > 0.0 {
            visibility = surface_shadow(i, surface);
        }
        color += light.radiance * visibility * direct_lighting(reflecting, normal, light.to_light, to_eye);
    }
    return vec4<f32>(color, alpha);
}
