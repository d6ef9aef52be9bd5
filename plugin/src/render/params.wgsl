// Helpers for the parameter structs `material_parameters!` generates: a colour is uploaded as
// `array<f32, 4>` (4-byte aligned, so the struct has no padding), read as a vec4 here.

fn rgba(color: array<f32, 4>) -> vec4<f32> {
    return vec4<f32>(color[0], color[1], color[2], color[3]);
}
