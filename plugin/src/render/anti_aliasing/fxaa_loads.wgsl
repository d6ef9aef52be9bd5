// FXAA's bilinear read where the display format cannot be filtered (rgba32float): four loads.
// `position` is in pixels, a pixel's centre at + 0.5.
fn sample_at(position: vec2<f32>) -> vec4<f32> {
    let corner = position - 0.5;
    let base = floor(corner);
    let f = corner - base;
    let pixel = vec2<i32>(base);
    let top = mix(load_clamped(pixel), load_clamped(pixel + vec2<i32>(1, 0)), f.x);
    let bottom = mix(load_clamped(pixel + vec2<i32>(0, 1)), load_clamped(pixel + vec2<i32>(1, 1)), f.x);
    return mix(top, bottom, f.y);
}
