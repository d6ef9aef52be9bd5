// Where the plate is: outside the round hole of each cell.
fn covers(surface: SurfaceInput, material: MaterialParams) -> bool {
    return length(fract(surface.uv * material.cells) - 0.5) >= material.hole_radius;
}

// Lambert, as matte.wgsl.
fn shade(surface: SurfaceInput, material: MaterialParams) -> vec4<f32> {
    var light = frame.ambient.rgb;
    for (var i = 0u; i < light_count(); i += 1u) {
        let incoming = light_at(i, surface.position);
        let facing = max(dot(surface.normal, incoming.to_light), 0.0);
        light += incoming.radiance * facing * surface_shadow(i, surface);
    }
    return vec4<f32>(rgba(material.color).rgb * light, 1.0);
}
