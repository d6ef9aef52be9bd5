// Entry points of `ParallaxOcclusionMaterial`. Composed after the generated enum codes,
// frame.wgsl, mesh_vertex.wgsl, tangent_space.wgsl, lighting.wgsl and march.wgsl (see
// parallax/mod.rs). Mirrors `PomUniform` in gpu.rs (the layout test checks them).

// Pipeline-overridable constants: every pipeline is compiled for one combination (see
// parallax/pipelines.rs), so the GPU compiler drops every other path and its registers.
override METHOD: u32 = METHOD_OCCLUSION;
override SHADOW_MODE: u32 = SHADOWS_SOFT;
override LIGHTING_MODEL: u32 = LIGHTING_PHONG;
override DEBUG_VIEW: u32 = DEBUG_NONE;

// `PomParams` (every declared parameter, in declaration order) is generated from the Rust
// declarations and prepended, like the enum codes.
struct PomUniform {
    params: PomParams,
    // The height texture as bound, in texels (1 × 1 without one), and its mip levels.
    height_texture_width: f32,
    height_texture_height: f32,
    height_mip_levels: f32,
    // 1 when the material has a height map.
    has_height_map: u32,
    // Channel of the height texture holding the height: 0 = red .. 3 = alpha.
    height_channel: u32,
}

@group(0) @binding(2) var<storage, read> materials: array<PomUniform>;
@group(1) @binding(0) var base_color_texture: texture_2d<f32>;
@group(1) @binding(1) var normal_map: texture_2d<f32>;
@group(1) @binding(2) var height_texture: texture_2d<f32>;
@group(1) @binding(3) var material_sampler: sampler;

struct Shaded {
    color: vec4<f32>,
    // Depth of the displaced point in clip space (0..1).
    depth: f32,
}

// Black → red → yellow → white as `t` goes 0 → 1.
fn heat(t: f32) -> vec3<f32> {
    let x = clamp(t, 0.0, 1.0) * 3.0;
    return clamp(vec3<f32>(x, x - 1.0, x - 2.0), vec3<f32>(0.0), vec3<f32>(1.0));
}

fn shade(in: VertexOut) -> Shaded {
    let material = materials[in.object_index];
    let params = material.params;
    let surface_frame = tangent_frame(in.world_normal, in.world_tangent);
    let to_eye = direction_to_eye(in.world_position, surface_frame.normal);
    let to_eye_ts = to_tangent_space(surface_frame, to_eye);

    // Everything derived from screen-space derivatives happens here, once, before any branch.
    let ddx_uv = dpdx(in.uv);
    let ddy_uv = dpdy(in.uv);
    let texture_size = vec2<f32>(material.height_texture_width, material.height_texture_height);
    let mip = mip_level(ddx_uv * texture_size, ddy_uv * texture_size);
    // Texture units per world unit (Luna §3), from the areas a pixel covers in both spaces.
    let world_area = length(cross(dpdx(in.world_position), dpdy(in.world_position)));
    let uv_area = abs(ddx_uv.x * ddy_uv.y - ddx_uv.y * ddy_uv.x);
    let uv_per_world = sqrt(uv_area / max(world_area, 1e-30));
    let scale = select(0.0, params.height_scale, material.has_height_map != 0u);
    let height_scale = select(scale, scale * uv_per_world, params.height_units == UNITS_WORLD);

    let field = HeightField(material.height_channel, u32(params.height_convention == CONVENTION_DEPTH), ddx_uv, ddy_uv);
    let method = METHOD;
    let min_samples = params.min_samples;
    let max_samples = params.max_samples;
    let fade = lod_fade(mip, params.lod_threshold, params.lod_band);
    // Past the LOD threshold (fade 1) nothing below runs but normal mapping.
    let march = fade < 1.0 && method != METHOD_NORMAL_MAPPING && height_scale > 0.0;

    var uv = in.uv;
    var height = 1.0;
    var samples = 0u;
    if march {
        let offset = -ray_offset(to_eye_ts, height_scale);
        let texels = length(offset * texture_size) / exp2(mip);
        let steps = march_steps(min_samples, max_samples, dot(surface_frame.normal, to_eye), texels);
        let hit = march_view(height_texture, material_sampler, field, method, in.uv, offset, to_eye_ts,
            height_scale, steps, params.relief_binary_steps);
        // In the LOD band, fade from the parallax coordinate to the plain one (T §5.4.3).
        uv = mix(hit.uv, in.uv, fade);
        height = mix(hit.height, 1.0, fade);
        samples = hit.samples;
    }

    let base = textureSampleGrad(base_color_texture, material_sampler, uv, ddx_uv, ddy_uv) * rgba(params.base_color);
    let encoded_normal = textureSampleGrad(normal_map, material_sampler, uv, ddx_uv, ddy_uv).xyz;
    let normal = perturbed_normal(surface_frame, encoded_normal, params.normal_strength);
    let surface = Surface(base.rgb, params.specular_strength, max(params.shininess, 1.0), params.roughness,
        params.metallic, LIGHTING_MODEL);

    var color = frame.ambient.rgb * base.rgb;
    var first_visibility = 1.0;
    for (var i = 0u; i < light_count(); i += 1u) {
        let light = light_at(i, in.world_position);
        var visibility = 1.0;
        // Shadow rays only where the light faces the polygon (T §5.4.2) and the march ran.
        if march && SHADOW_MODE != SHADOWS_OFF && dot(surface_frame.normal, light.to_light) > 0.0 {
            let to_light_ts = to_tangent_space(surface_frame, light.to_light);
            let light_offset = ray_offset(to_light_ts, height_scale);
            if SHADOW_MODE == SHADOWS_SOFT {
                visibility = soft_shadow(height_texture, material_sampler, field, uv, light_offset, params.shadow_softening);
            } else {
                let texels_per_rise = length(light_offset * texture_size) / exp2(mip);
                visibility = hard_shadow(height_texture, material_sampler, field, uv, light_offset,
                    min_samples, max_samples, dot(surface_frame.normal, light.to_light), texels_per_rise);
            }
            visibility = mix(visibility, 1.0, fade);
        }
        if i == 0u {
            first_visibility = visibility;
        }
        color += light.radiance * visibility * direct_lighting(surface, normal, light.to_light, to_eye);
    }

    var out = vec4<f32>(color, base.a);
    switch DEBUG_VIEW {
        case DEBUG_LOD: {
            // T's tint: blue grows through the band; deepest blue where only normal mapping runs.
            let tint = select(max(1.0, 2.0 * fade), 3.0, fade >= 1.0);
            out = vec4<f32>(color * vec3<f32>(1.0, 1.0, tint), base.a);
        }
        case DEBUG_MIP: {
            out = vec4<f32>(vec3<f32>(mip / max(material.height_mip_levels - 1.0, 1.0)), 1.0);
        }
        case DEBUG_SAMPLES: {
            out = vec4<f32>(heat(f32(samples) / max(f32(max_samples), 1.0)), 1.0);
        }
        case DEBUG_UV: {
            let region = select(select(0.5, 1.0, fade <= 0.0), 0.0, !march);
            out = vec4<f32>(fract(uv), region, 1.0);
        }
        case DEBUG_SHADOW: {
            out = vec4<f32>(vec3<f32>(first_visibility), 1.0);
        }
        case DEBUG_NORMAL: {
            out = vec4<f32>(to_tangent_space(surface_frame, normal) * 0.5 + 0.5, 1.0);
        }
        default: {}
    }

    // The visible point lies (1 − height) × H below the polygon and offset sideways by the
    // change of texture coordinate: place it in the world and project it.
    let du = (uv - in.uv) / max(uv_per_world, 1e-30);
    let depth_below = (1.0 - height) * height_scale / max(uv_per_world, 1e-30);
    let displaced = in.world_position + surface_frame.tangent * du.x + surface_frame.bitangent_v * du.y
        - surface_frame.normal * depth_below;
    let clip = frame.view_projection * vec4<f32>(select(in.world_position, displaced, uv_per_world > 0.0), 1.0);
    let depth = clamp(clip.z / max(clip.w, 1e-30), 0.0, 1.0);
    return Shaded(out, depth);
}

@fragment
fn fs_main(in: VertexOut) -> @location(0) vec4<f32> {
    return shade(in).color;
}

struct ColorAndDepth {
    @location(0) color: vec4<f32>,
    @builtin(frag_depth) depth: f32,
}

// For `depth_offset`: the depth buffer gets the displaced point, so other geometry meets the
// relief where it really is.
@fragment
fn fs_main_depth_offset(in: VertexOut) -> ColorAndDepth {
    let shaded = shade(in);
    return ColorAndDepth(shaded.color, shaded.depth);
}
