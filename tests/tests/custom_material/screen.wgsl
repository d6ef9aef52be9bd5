// Unlit: the picture, filtered over the pixel's footprint, times the tint and the brightness.
fn shade(surface: SurfaceInput, material: MaterialParams) -> vec4<f32> {
    let color = texture_at(picture, surface).rgb * rgba(material.tint).rgb;
    return vec4<f32>(color * material.brightness, 1.0);
}
