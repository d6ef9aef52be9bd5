// The maximum-height pyramid of a height texture, for hierarchical ray marching over the
// height field (Tevs, Ihrke and Seidel 2008). Mirrors `MaxPyramid::new` in
// reference/max_mip.rs. Composed after height_channel.wgsl.
//
// Level 0 holds, per cell (the bilinear patch between texel centres i..i+1, j..j+1, wrapping),
// its highest corner in Tatarchuk's convention (1 = top) after picking the channel and the
// convention; every level above, the maximum of 2 × 2 cells below.

struct PyramidLevel {
    // Size of the level written, in cells.
    size: vec2<u32>,
    // Channel of the source holding the height: 0 = red .. 3 = alpha (level 0 only).
    channel: u32,
    // 1 when white means deepest (level 0 only).
    depth_convention: u32,
}

// Level 0: the height texture (its level 0). Above: the pyramid's level below.
@group(0) @binding(0) var below: texture_2d<f32>;
@group(0) @binding(1) var level: texture_storage_2d<r32float, write>;
@group(0) @binding(2) var<uniform> params: PyramidLevel;

fn source_height(texel: vec2<i32>) -> f32 {
    let size = vec2<i32>(params.size);
    let wrapped = ((texel % size) + size) % size;
    return height_in_channel(textureLoad(below, wrapped, 0), params.channel, params.depth_convention);
}

@compute @workgroup_size(8, 8)
fn cell_maxima(@builtin(global_invocation_id) id: vec3<u32>) {
    if any(id.xy >= params.size) {
        return;
    }
    let cell = vec2<i32>(id.xy);
    let highest = max(max(source_height(cell), source_height(cell + vec2<i32>(1, 0))),
        max(source_height(cell + vec2<i32>(0, 1)), source_height(cell + vec2<i32>(1, 1))));
    textureStore(level, cell, vec4<f32>(highest, 0.0, 0.0, 0.0));
}

@compute @workgroup_size(8, 8)
fn reduce_level(@builtin(global_invocation_id) id: vec3<u32>) {
    if any(id.xy >= params.size) {
        return;
    }
    let first = vec2<i32>(id.xy) * 2;
    let highest = max(max(textureLoad(below, first, 0).r, textureLoad(below, first + vec2<i32>(1, 0), 0).r),
        max(textureLoad(below, first + vec2<i32>(0, 1), 0).r, textureLoad(below, first + vec2<i32>(1, 1), 0).r));
    textureStore(level, vec2<i32>(id.xy), vec4<f32>(highest, 0.0, 0.0, 0.0));
}
