// Tatarchuk's listings 1 and 2 (ShaderX5 / SIGGRAPH 2006, the appendix of ../shared/seeds/000)
// transliterated to WGSL, for the bench only: the seed's own shader on the same workload and
// GPU as ours. Composed after frame.wgsl, mesh_vertex.wgsl (its vs_main stands in for listing 1's
// transform) and tangent_space.wgsl. Mirrors `SeedPortUniform` in seed_port/mod.rs.
//
// Two entry points share everything below but the derivatives: `fs_seed_port` (here, the seed as
// written: a material in the opaque raster pass) and `cs_seed_port` (seed_port_compute.wgsl: the
// same listing as one compute dispatch over the target). Both call `seed_port_listing_1` and
// `seed_port_listing_2` with the pixel's texture gradients passed in, so the march, the shadow
// and the lighting are one piece of WGSL.
//
// What it reads, as the listing does: one RGBA8 normal map with the height in its alpha
// (`SeedPortMaterial::packed_normal_height` builds it), its green read unflipped along the
// tangent frame's dP/dv. The listing's maps are Direct3D's: v runs down the image and green
// points down it, along the binormal. Ours (tangent_space.wgsl's perturbed_normal) store green
// up the image, −v, and negate it when decoding; the packed image stores 255 − green, so the
// listing's plain read sees the surface our material sees.
//
// Every remaining deviation from listings 1 and 2:
// - Listing 1's uniforms come from the frame: the light is the first light (a directional one
//   gives parallel rays where vLightPosition − position would converge), the eye the camera (an
//   orthographic one's view direction everywhere); cAmbientColor is the frame's ambient,
//   cDiffuseColor the light's radiance, cSpecularColor its radiance × `specular_strength`.
// - Listing 1's per-vertex tangent-space vectors are formed per pixel from the interpolated
//   frame (the same values on the bench's flat plane, whose frame is constant).
// - ComputeIllumination's tex2D takes the rasterizer's derivatives of the displaced texSample;
//   here every sample takes the gradients of the undisplaced texture coordinate, as the march
//   does (tex2Dgrad with dx, dy): a compute pass has no derivatives, and the two differ only
//   where the displacement jumps, at the relief's steps.
// - ps_main passes `vViewTS` to ComputeIllumination and lerps the sample count by
//   `dot(vViewWS, vNormalWS)`; it declares neither name, only the normalized mViewTS and
//   mViewWS, which are used.
// - ComputeIllumination's `normalize(tex2D(tNormalMap, texCoord) * 2 - 1)` normalizes all four
//   channels, the height in alpha among them, before HLSL's implicit truncation to float3 keeps
//   xyz: a normal shortened by up to 1/√2 where the height is 0 or 1 (visibly darker diffuse on
//   the cobblestones), an artefact of the packing the text never describes. The port
//   normalizes xyz, the normal the text shades with; the cost is the same.
// - pow() gets max(R·L, 0) (HLSL's saturate(pow(negative)) is 0, WGSL's pow of a negative
//   number is undefined); looking straight down the normal, the parallax direction is zero
//   instead of normalize(0) = NaN.
// - The colour's alpha is 1 (the listing's carries the lit alpha channels); bVisualizeLOD and
//   bVisualizeMipLevel are off (debug tints the bench never shows).

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
// RGB: the tangent-space normal (Direct3D's green), A: the height (1 = the polygon's surface).
@group(1) @binding(1) var normal_map: texture_2d<f32>;
@group(1) @binding(2) var material_sampler: sampler;

// Listing 2's PS_INPUT (what listing 1 hands on), the light that lights it, and the pixel's
// gradients of the texture coordinate (listing 2's ddx / ddy of i.texCoord).
struct SeedPortPixel {
    tex_coord: vec2<f32>,
    // Not normalized, as interpolated.
    light_ts: vec3<f32>,
    view_ts: vec3<f32>,
    parallax_offset_ts: vec2<f32>,
    normal_ws: vec3<f32>,
    view_ws: vec3<f32>,
    radiance: vec3<f32>,
    dx: vec2<f32>,
    dy: vec2<f32>,
}

// Listing 1 at one point of the surface, from the vertex stage's interpolated outputs and the
// texture gradients the caller found.
fn seed_port_listing_1(in: VertexOut, dx: vec2<f32>, dy: vec2<f32>) -> SeedPortPixel {
    let params = materials[in.object_index];
    let frame_ts = tangent_frame(in.world_normal, in.world_tangent);
    let view_ws = direction_to_eye(in.world_position, frame_ts.normal);
    let light = light_at(0u, in.world_position);
    let view_ts = to_tangent_space(frame_ts, view_ws);
    let parallax_direction = select(vec2<f32>(0.0), normalize(view_ts.xy), length(view_ts.xy) > 0.0);
    let view_length = length(view_ts);
    let parallax_length = sqrt(view_length * view_length - view_ts.z * view_ts.z) / view_ts.z;
    return SeedPortPixel(
        in.uv,
        to_tangent_space(frame_ts, light.to_light),
        view_ts,
        parallax_direction * parallax_length * params.height_map_range,
        frame_ts.normal,
        view_ws,
        light.radiance,
        dx,
        dy,
    );
}

// Listing 2's ComputeIllumination: Phong (ambient + diffuse) × base + specular, times the shadow.
fn compute_illumination(tex_coord: vec2<f32>, light_ts: vec3<f32>, view_ts: vec3<f32>, occlusion_shadow: f32,
    pixel: SeedPortPixel, params: SeedPortUniform) -> vec4<f32> {
    let texel = textureSampleGrad(normal_map, material_sampler, tex_coord, pixel.dx, pixel.dy);
    let normal_ts = normalize(texel.xyz * 2.0 - 1.0);
    let base_color = textureSampleGrad(base_map, material_sampler, tex_coord, pixel.dx, pixel.dy);
    let diffuse = clamp(dot(normal_ts, light_ts), 0.0, 1.0) * pixel.radiance;
    let reflection_ts = normalize(2.0 * dot(view_ts, normal_ts) * normal_ts - view_ts);
    let r_dot_l = dot(reflection_ts, light_ts);
    let specular = clamp(pow(max(r_dot_l, 0.0), params.specular_exponent), 0.0, 1.0)
        * params.specular_strength * pixel.radiance;
    let color = ((frame.ambient.rgb + diffuse) * base_color.rgb + specular) * occlusion_shadow;
    return vec4<f32>(color, 1.0);
}

// The height (the normal map's alpha), sampled as the listing's tex2Dgrad(tNormalMap, ..., dx, dy).a.
fn height_at(tex_coord: vec2<f32>, pixel: SeedPortPixel) -> f32 {
    return textureSampleGrad(normal_map, material_sampler, tex_coord, pixel.dx, pixel.dy).a;
}

// Listing 2's linear march along the parallax offset and its piecewise-linear intersection:
// the displaced texture coordinate.
fn seed_port_march(pixel: SeedPortPixel, params: SeedPortUniform, num_steps: i32) -> vec2<f32> {
    var curr_height = 0.0;
    let step_size = 1.0 / f32(num_steps);
    var prev_height = 1.0;
    var step_index = 0;
    let tex_offset_per_step = step_size * pixel.parallax_offset_ts;
    var tex_current_offset = pixel.tex_coord;
    var current_bound = 1.0;
    var pt1 = vec2<f32>(0.0);
    var pt2 = vec2<f32>(0.0);
    while step_index < num_steps {
        tex_current_offset -= tex_offset_per_step;
        curr_height = height_at(tex_current_offset, pixel);
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
    return pixel.tex_coord - pixel.parallax_offset_ts * (1.0 - parallax_amount);
}

// Listing 2's soft shadow: seven height samples towards the light, weighted by their distance.
fn seed_port_soft_shadow(tex_sample_base: vec2<f32>, light_ts: vec3<f32>, pixel: SeedPortPixel,
    params: SeedPortUniform) -> f32 {
    let light_ray_ts = light_ts.xy * params.height_map_range;
    let softening = params.shadow_softening;
    let sh0 = height_at(tex_sample_base, pixel);
    let sh_a = (height_at(tex_sample_base + light_ray_ts * 0.88, pixel) - sh0 - 0.88) * 1.0 * softening;
    let sh9 = (height_at(tex_sample_base + light_ray_ts * 0.77, pixel) - sh0 - 0.77) * 2.0 * softening;
    let sh8 = (height_at(tex_sample_base + light_ray_ts * 0.66, pixel) - sh0 - 0.66) * 4.0 * softening;
    let sh7 = (height_at(tex_sample_base + light_ray_ts * 0.55, pixel) - sh0 - 0.55) * 6.0 * softening;
    let sh6 = (height_at(tex_sample_base + light_ray_ts * 0.44, pixel) - sh0 - 0.44) * 8.0 * softening;
    let sh5 = (height_at(tex_sample_base + light_ray_ts * 0.33, pixel) - sh0 - 0.33) * 10.0 * softening;
    let sh4 = (height_at(tex_sample_base + light_ray_ts * 0.22, pixel) - sh0 - 0.22) * 12.0 * softening;
    let occlusion_shadow = 1.0 - max(max(max(max(max(max(sh_a, sh9), sh8), sh7), sh6), sh5), sh4);
    // The listing's correction: the sum over-brightens.
    return occlusion_shadow * 0.6 + 0.4;
}

// Listing 2's ps_main: the mip-level LOD switch, the march, its blend to bump mapping in the
// transition band, the soft shadow and the lighting.
fn seed_port_listing_2(pixel: SeedPortPixel, params: SeedPortUniform) -> vec4<f32> {
    let view_ts = normalize(pixel.view_ts);
    let view_ws = normalize(pixel.view_ws);
    let light_ts = normalize(pixel.light_ts);
    let normal_ws = normalize(pixel.normal_ws);

    // ddx / ddy of texCoord × vTextureDims: the gradients scale with the dimensions.
    let dx_size = pixel.dx * params.texture_dims;
    let dy_size = pixel.dy * params.texture_dims;
    let d_tex_coords = dx_size * dx_size + dy_size * dy_size;
    let min_tex_coord_delta = max(d_tex_coords.x, d_tex_coords.y);
    let mip_level = max(0.5 * log2(min_tex_coord_delta), 0.0);

    var tex_sample = pixel.tex_coord;
    var occlusion_shadow = 1.0;
    if mip_level <= f32(params.lod_threshold) {
        let num_steps = i32(mix(f32(params.max_samples), f32(params.min_samples), dot(view_ws, normal_ws)));
        let tex_sample_base = seed_port_march(pixel, params, num_steps);
        tex_sample = tex_sample_base;
        if mip_level > f32(params.lod_threshold - 1) {
            let mip_level_frac = fract(mip_level);
            tex_sample = mix(tex_sample_base, pixel.tex_coord, mip_level_frac);
        }
        if params.display_shadows != 0u {
            occlusion_shadow = seed_port_soft_shadow(tex_sample_base, light_ts, pixel, params);
        }
    }
    return compute_illumination(tex_sample, light_ts, view_ts, occlusion_shadow, pixel, params);
}

// The seed as written: the rasterizer's derivatives of the interpolated texture coordinate.
@fragment
fn fs_seed_port(in: VertexOut) -> @location(0) vec4<f32> {
    let pixel = seed_port_listing_1(in, dpdx(in.uv), dpdy(in.uv));
    return seed_port_listing_2(pixel, materials[in.object_index]);
}
