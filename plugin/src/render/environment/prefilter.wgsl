// Prefilters the environment (prefilter.rs): `cs_capture` renders the source into the largest
// mip of a cube, `cs_downsample` averages each mip of it into the next, `cs_specular` blurs it
// into the radiance cube's mips by GGX lobes of growing roughness, and `cs_irradiance` projects
// it onto nine spherical harmonics. Composed after sky.wgsl, environment_source.wgsl and
// spherical_harmonics.wgsl.

// Mirrors `PrefilterParams` in prefilter.rs (the layout test checks them).
struct PrefilterParams {
    // Texels along a side of the mip written (cs_capture, cs_downsample, cs_specular) or read
    // (cs_irradiance).
    size: u32,
    // Texels along a side of the cube's largest mip.
    source_size: u32,
    // The cube's mips.
    source_levels: u32,
    // GGX samples per texel (cs_specular).
    samples: u32,
    // The perceptual roughness of the mip written (cs_specular).
    roughness: f32,
    // The image's mip the capture reads.
    image_level: f32,
    // What the capture multiplies the source with, to keep it within half precision.
    radiance_scale: f32,
    _padding: u32,
}

// Storage, not uniform, as the source's parameters (environment_source.wgsl): a sun that moves
// prefilters every frame.
@group(0) @binding(0) var<storage, read> params: PrefilterParams;
@group(0) @binding(1) var output: texture_storage_2d_array<rgba16float, write>;
@group(0) @binding(2) var input_level: texture_2d_array<f32>;
@group(0) @binding(3) var input_cube: texture_cube<f32>;
@group(0) @binding(4) var input_sampler: sampler;
@group(0) @binding(5) var<storage, read_write> irradiance: array<vec4<f32>, 9>;

// Texel `texel` of cube face `face` (+X, −X, +Y, −Y, +Z, −Z) of `size` texels a side, as a unit
// direction: the faces as Vulkan and Direct3D sample them.
fn cube_direction(texel: vec2<u32>, face: u32, size: u32) -> vec3<f32> {
    let uv = (vec2<f32>(texel) + 0.5) / f32(size) * 2.0 - 1.0;
    var direction: vec3<f32>;
    switch face {
        case 0u: { direction = vec3<f32>(1.0, -uv.y, -uv.x); }
        case 1u: { direction = vec3<f32>(-1.0, -uv.y, uv.x); }
        case 2u: { direction = vec3<f32>(uv.x, 1.0, uv.y); }
        case 3u: { direction = vec3<f32>(uv.x, -1.0, -uv.y); }
        case 4u: { direction = vec3<f32>(uv.x, -uv.y, 1.0); }
        default: { direction = vec3<f32>(-uv.x, -uv.y, -1.0); }
    }
    return normalize(direction);
}

@compute @workgroup_size(8, 8, 1)
fn cs_capture(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x >= params.size || id.y >= params.size {
        return;
    }
    let radiance = source_radiance(cube_direction(id.xy, id.z, params.size), params.image_level) * params.radiance_scale;
    textureStore(output, id.xy, id.z, vec4<f32>(min(radiance, vec3<f32>(65504.0)), 1.0));
}

@compute @workgroup_size(8, 8, 1)
fn cs_downsample(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x >= params.size || id.y >= params.size {
        return;
    }
    let corner = id.xy * 2u;
    let sum = textureLoad(input_level, corner, id.z, 0) + textureLoad(input_level, corner + vec2<u32>(1u, 0u), id.z, 0)
        + textureLoad(input_level, corner + vec2<u32>(0u, 1u), id.z, 0) + textureLoad(input_level, corner + vec2<u32>(1u, 1u), id.z, 0);
    textureStore(output, id.xy, id.z, sum * 0.25);
}

// The i-th of `count` points of the Hammersley set.
fn hammersley(i: u32, count: u32) -> vec2<f32> {
    return vec2<f32>((f32(i) + 0.5) / f32(count), f32(reverseBits(i)) * 2.3283064e-10);
}

// GGX-distributed half vector around +Z for width `alpha`, and its cosine.
fn ggx_half_vector(xi: vec2<f32>, alpha: f32) -> vec3<f32> {
    let phi = 2.0 * PI * xi.x;
    let cos_theta = sqrt((1.0 - xi.y) / (1.0 + (alpha * alpha - 1.0) * xi.y));
    let sin_theta = sqrt(max(1.0 - cos_theta * cos_theta, 0.0));
    return vec3<f32>(sin_theta * cos(phi), sin_theta * sin(phi), cos_theta);
}

// The radiance cube's mip for `params.roughness`, with view = normal = the texel's direction
// (the split sum's assumption), by importance sampling with the source mip chosen from each
// sample's solid angle (Colbert & Křivánek, GPU Gems 3 ch. 20: filtered importance sampling).
@compute @workgroup_size(8, 8, 1)
fn cs_specular(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x >= params.size || id.y >= params.size {
        return;
    }
    let normal = cube_direction(id.xy, id.z, params.size);
    let up = select(vec3<f32>(0.0, 1.0, 0.0), vec3<f32>(1.0, 0.0, 0.0), abs(normal.y) > 0.999);
    let tangent = normalize(cross(up, normal));
    let bitangent = cross(normal, tangent);
    let alpha = max(params.roughness * params.roughness, 1e-4);
    let texel_solid_angle = 4.0 * PI / (6.0 * f32(params.source_size * params.source_size));
    var sum = vec3<f32>(0.0);
    var weight = 0.0;
    for (var i = 0u; i < params.samples; i += 1u) {
        let h = ggx_half_vector(hammersley(i, params.samples), alpha);
        let half_vector = tangent * h.x + bitangent * h.y + normal * h.z;
        let light = 2.0 * h.z * half_vector - normal;
        let n_dot_l = dot(normal, light);
        if n_dot_l > 0.0 {
            let d_denominator = h.z * h.z * (alpha * alpha - 1.0) + 1.0;
            let distribution = alpha * alpha / (PI * d_denominator * d_denominator);
            // pdf = D (N·H) / (4 V·H) = D / 4 with V = N.
            let sample_solid_angle = 4.0 / (f32(params.samples) * max(distribution, 1e-8));
            // No coarser than the mip of 1/32 of the source's side: a tail sample reading a
            // face-wide average would carry the sky's light into the ground below the horizon.
            let level = clamp(0.5 * log2(sample_solid_angle / texel_solid_angle) + 1.0, 0.0,
                max(f32(params.source_levels) - 6.0, 0.0));
            sum += textureSampleLevel(input_cube, input_sampler, light, level).rgb * n_dot_l;
            weight += n_dot_l;
        }
    }
    textureStore(output, id.xy, id.z, vec4<f32>(sum / max(weight, 1e-8), 1.0));
}

const IRRADIANCE_THREADS: u32 = 64u;
var<workgroup> partial_sums: array<array<vec4<f32>, 9>, IRRADIANCE_THREADS>;

// Irradiance / π as nine coefficients: the cube's mip of `params.size` texels a side projected
// onto the harmonics, each texel weighted by its solid angle, then convolved with the cosine
// lobe (Ramamoorthi & Hanrahan: Â₀ = π, Â₁ = 2π/3, Â₂ = π/4, over π).
@compute @workgroup_size(IRRADIANCE_THREADS)
fn cs_irradiance(@builtin(local_invocation_index) thread: u32) {
    let face_texels = params.size * params.size;
    var sums: array<vec4<f32>, 9>;
    for (var t = thread; t < 6u * face_texels; t += IRRADIANCE_THREADS) {
        let face = t / face_texels;
        let texel = vec2<u32>(t % face_texels % params.size, t % face_texels / params.size);
        let uv = (vec2<f32>(texel) + 0.5) / f32(params.size) * 2.0 - 1.0;
        let solid_angle = 4.0 / (f32(face_texels) * pow(1.0 + dot(uv, uv), 1.5));
        let radiance = textureLoad(input_level, texel, face, 0).rgb;
        let basis = spherical_harmonics(cube_direction(texel, face, params.size));
        for (var k = 0u; k < 9u; k += 1u) {
            sums[k] += vec4<f32>(radiance * basis[k], 1.0) * solid_angle;
        }
    }
    partial_sums[thread] = sums;
    workgroupBarrier();
    for (var stride = IRRADIANCE_THREADS / 2u; stride > 0u; stride /= 2u) {
        if thread < stride {
            for (var k = 0u; k < 9u; k += 1u) {
                partial_sums[thread][k] += partial_sums[thread + stride][k];
            }
        }
        workgroupBarrier();
    }
    if thread == 0u {
        // The texels' solid angles add up to 4π up to the rule's error: normalize by their sum.
        let normalization = 4.0 * PI / partial_sums[0][0].w;
        let band = array<f32, 9>(1.0, 2.0 / 3.0, 2.0 / 3.0, 2.0 / 3.0, 0.25, 0.25, 0.25, 0.25, 0.25);
        for (var k = 0u; k < 9u; k += 1u) {
            irradiance[k] = vec4<f32>(partial_sums[0][k].rgb * normalization * band[k], 0.0);
        }
    }
}
