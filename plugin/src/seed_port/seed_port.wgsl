// Tatarchuk's listings 1 and 2 (ShaderX5 / SIGGRAPH 2006, the appendix of ../shared/seeds/000)
// transliterated to WGSL, for the bench only: the seed's own shader on the same workload and
// GPU as ours. Composed after frame.wgsl, mesh_vertex.wgsl (its vs_main stands in for listing 1's
// transform) and tangent_space.wgsl. Mirrors `SeedPortUniform` in seed_port/mod.rs.
//
// Deviations, each needed to run at all: the height is read from its own texture (red) instead
// of the normal map's alpha; the light and view come from the frame (the first light, the
// camera, parallel rays for an orthographic view) instead of listing 1's uniforms; listing 1's
// per-vertex tangent-space vectors are formed per pixel from the interpolated frame (the same
// values on the bench's plane); pow() gets max(R·L, 0) (HLSL's saturate(pow(negative)) is 0,
// WGSL's pow of a negative number is undefined); looking straight down the normal, the parallax
// direction is zero instead of normalize(0) = NaN.

struct SeedPortUniform {
    height_map_range: f32,
    shadow_softening: f32,
    specular_exponent: f32,
    specular_strength: f32,
    lod_threshold: i32,
    min_samples: i32,
    max_samples: i32,
    display_shadows: u32,
    texture_dims: vec2<f32>,
    _padding: vec2<f32>,
}

@group(0) @binding(2) var<storage, read> materials: array<SeedPortUniform>;
@group(1) @binding(0) var base_map: texture_2d<f32>;
@group(1) @binding(1) var normal_map: texture_2d<f32>;
@group(1) @binding(2) var height_map: texture_2d<f32>;
@group(1) @binding(3) var material_sampler: sampler;

// Listing 2's ComputeIllumination: Phong (ambient + diffuse) × base + specular, times the shadow.
fn compute_illumination(tex_coord: vec2<f32>, light_ts: vec3<f32>, view_ts: vec3<f32>, occlusion_shadow: f32,
    light: LightSample, params: SeedPortUniform, dx: vec2<f32>, dy: vec2<f32>) -> vec4<f32> {
    let normal_ts = normalize(textureSampleGrad(normal_map, material_sampler, tex_coord, dx, dy).xyz * 2.0 - 1.0);
    let base_color = textureSampleGrad(base_map, material_sampler, tex_coord, dx, dy);
    let diffuse = clamp(dot(normal_ts, light_ts), 0.0, 1.0) * light.radiance;
    let reflection_ts = normalize(2.0 * dot(view_ts, normal_ts) * normal_ts - view_ts);
    let r_dot_l = dot(reflection_ts, light_ts);
    let specular = clamp(pow(max(r_dot_l, 0.0), params.specular_exponent), 0.0, 1.0)
        * params.specular_strength * light.radiance;
    let color = ((frame.ambient.rgb + diffuse) * base_color.rgb + specular) * occlusion_shadow;
    return vec4<f32>(color, 1.0);
}

fn height_at(tex_coord: vec2<f32>, dx: vec2<f32>, dy: vec2<f32>) -> f32 {
    return textureSampleGrad(height_map, material_sampler, tex_coord, dx, dy).r;
}

@fragment
fn fs_seed_port(in: VertexOut) -> @location(0) vec4<f32> {
    let params = materials[in.object_index];
    // Listing 1, per pixel.
    let frame_ts = tangent_frame(in.world_normal, in.world_tangent);
    let view_ws = direction_to_eye(in.world_position, frame_ts.normal);
    let light = light_at(0u, in.world_position);
    let view_ts_raw = to_tangent_space(frame_ts, view_ws);
    let parallax_direction = select(vec2<f32>(0.0), normalize(view_ts_raw.xy), length(view_ts_raw.xy) > 0.0);
    let view_length = length(view_ts_raw);
    let parallax_length = sqrt(view_length * view_length - view_ts_raw.z * view_ts_raw.z) / view_ts_raw.z;
    let parallax_offset_ts = parallax_direction * parallax_length * params.height_map_range;

    // Listing 2.
    let view_ts = normalize(view_ts_raw);
    let light_ts = normalize(to_tangent_space(frame_ts, light.to_light));
    let normal_ws = frame_ts.normal;

    let tex_coords_per_size = in.uv * params.texture_dims;
    let dx_size = dpdx(tex_coords_per_size);
    let dy_size = dpdy(tex_coords_per_size);
    let dx = dpdx(in.uv);
    let dy = dpdy(in.uv);
    let d_tex_coords = dx_size * dx_size + dy_size * dy_size;
    let min_tex_coord_delta = max(d_tex_coords.x, d_tex_coords.y);
    let mip_level = max(0.5 * log2(min_tex_coord_delta), 0.0);

    var tex_sample = in.uv;
    var occlusion_shadow = 1.0;
    if mip_level <= f32(params.lod_threshold) {
        let num_steps = i32(mix(f32(params.max_samples), f32(params.min_samples), dot(view_ws, normal_ws)));
        var curr_height = 0.0;
        let step_size = 1.0 / f32(num_steps);
        var prev_height = 1.0;
        var step_index = 0;
        let tex_offset_per_step = step_size * parallax_offset_ts;
        var tex_current_offset = in.uv;
        var current_bound = 1.0;
        var pt1 = vec2<f32>(0.0);
        var pt2 = vec2<f32>(0.0);
        while step_index < num_steps {
            tex_current_offset -= tex_offset_per_step;
            curr_height = height_at(tex_current_offset, dx, dy);
            current_bound -= step_size;
            if curr_height > current_bound {
                pt1 = vec2<f32>(current_bound, curr_height);
                pt2 = vec2<f32>(current_bound + step_size, prev_height);
                step_index = num_steps + 1;
            } else {
                step_index += 1;
                prev_height = curr_height;
            }
        }
        let delta2 = pt2.x - pt2.y;
        let delta1 = pt1.x - pt1.y;
        let parallax_amount = (pt1.x * delta2 - pt2.x * delta1) / (delta2 - delta1);
        let parallax_offset = parallax_offset_ts * (1.0 - parallax_amount);
        let tex_sample_base = in.uv - parallax_offset;
        tex_sample = tex_sample_base;
        if mip_level > f32(params.lod_threshold - 1) {
            let mip_level_frac = fract(mip_level);
            tex_sample = mix(tex_sample_base, in.uv, mip_level_frac);
        }
        if params.display_shadows != 0u {
            let light_ray_ts = light_ts.xy * params.height_map_range;
            let softening = params.shadow_softening;
            let sh0 = height_at(tex_sample_base, dx, dy);
            let sh_a = (height_at(tex_sample_base + light_ray_ts * 0.88, dx, dy) - sh0 - 0.88) * 1.0 * softening;
            let sh9 = (height_at(tex_sample_base + light_ray_ts * 0.77, dx, dy) - sh0 - 0.77) * 2.0 * softening;
            let sh8 = (height_at(tex_sample_base + light_ray_ts * 0.66, dx, dy) - sh0 - 0.66) * 4.0 * softening;
            let sh7 = (height_at(tex_sample_base + light_ray_ts * 0.55, dx, dy) - sh0 - 0.55) * 6.0 * softening;
            let sh6 = (height_at(tex_sample_base + light_ray_ts * 0.44, dx, dy) - sh0 - 0.44) * 8.0 * softening;
            let sh5 = (height_at(tex_sample_base + light_ray_ts * 0.33, dx, dy) - sh0 - 0.33) * 10.0 * softening;
            let sh4 = (height_at(tex_sample_base + light_ray_ts * 0.22, dx, dy) - sh0 - 0.22) * 12.0 * softening;
            occlusion_shadow = 1.0 - max(max(max(max(max(max(sh_a, sh9), sh8), sh7), sh6), sh5), sh4);
            occlusion_shadow = occlusion_shadow * 0.6 + 0.4;
        }
    }
    return compute_illumination(tex_sample, light_ts, view_ts, occlusion_shadow, light, params, dx, dy);
}
