// Reading the visibility keys (visibility.wgsl) from compute, bound as `visibility:
// array<vec2<u32>>`: each key as (id, depth bits), row by row, then the candidate keys alike.

// The visibility id at `pixel` of a target `width` pixels wide (0: no draw there).
fn visible_id(pixel: vec2<u32>, width: u32) -> u32 {
    return visibility[pixel.y * width + pixel.x].x;
}

// The clip depth the visibility pass kept at `pixel` (the far plane where no draw is).
fn visible_depth(pixel: vec2<u32>, width: u32) -> f32 {
    let key = visibility[pixel.y * width + pixel.x];
    if key.x == 0u {
        return 1.0;
    }
    return bitcast<f32>(~key.y);
}

// The index of `pixel`'s candidate key in a target of `size` pixels.
fn candidate_index(pixel: vec2<u32>, size: vec2<u32>) -> u32 {
    return size.x * size.y + pixel.y * size.x + pixel.x;
}
