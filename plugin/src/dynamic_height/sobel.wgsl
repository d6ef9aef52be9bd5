// Normals of a height field by a 3×3 Sobel filter (Tatarchuk 2006 §5.5), on the GPU, for height
// fields that change every frame. Mirrors `normal_map_from_heights` in normal_map.rs: wrapping
// edges, OpenGL convention (green = up the image = −v), slopes scaled by the height range.

struct SobelParams {
    size: vec2<u32>,
    // Height of 1.0 in texture-coordinate units.
    height_scale: f32,
    padding: f32,
}

@group(0) @binding(0) var heights: texture_2d<f32>;
@group(0) @binding(1) var normals: texture_storage_2d<rgba8unorm, write>;
@group(0) @binding(2) var<uniform> params: SobelParams;

fn height_at(x: i32, y: i32) -> f32 {
    let size = vec2<i32>(params.size);
    let wrapped = ((vec2<i32>(x, y) % size) + size) % size;
    return textureLoad(heights, wrapped, 0).r;
}

@compute @workgroup_size(8, 8)
fn derive_normals(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x >= params.size.x || id.y >= params.size.y {
        return;
    }
    let x = i32(id.x);
    let y = i32(id.y);
    // Sobel weights sum to 8 over a 2-texel baseline: divide by 8 for height per texel.
    let per_texel_u = (height_at(x + 1, y - 1) + 2.0 * height_at(x + 1, y) + height_at(x + 1, y + 1)
        - height_at(x - 1, y - 1) - 2.0 * height_at(x - 1, y) - height_at(x - 1, y + 1)) / 8.0;
    let per_texel_v = (height_at(x - 1, y + 1) + 2.0 * height_at(x, y + 1) + height_at(x + 1, y + 1)
        - height_at(x - 1, y - 1) - 2.0 * height_at(x, y - 1) - height_at(x + 1, y - 1)) / 8.0;
    let slope_u = per_texel_u * f32(params.size.x) * params.height_scale;
    let slope_v = per_texel_v * f32(params.size.y) * params.height_scale;
    // Up the image is −v, so the green component is +dh/dv.
    let normal = normalize(vec3<f32>(-slope_u, slope_v, 1.0));
    textureStore(normals, vec2<i32>(x, y), vec4<f32>(normal * 0.5 + 0.5, 1.0));
}
