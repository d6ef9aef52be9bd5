// Reading the visibility keys (visibility.wgsl) from compute, where the shader binds them
// read-only as `visibility: array<vec2<u32>>`: each key as (id, depth bits), row by row.

// The visibility id at `pixel` of a target `width` pixels wide (0: no draw there).
fn visible_id(pixel: vec2<u32>, width: u32) -> u32 {
    return visibility[pixel.y * width + pixel.x].x;
}
