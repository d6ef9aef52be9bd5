// Where the plate is: outside the round hole of each cell.
fn covers(surface: SurfaceInput, material: MaterialParams) -> bool {
    return length(fract(surface.uv * material.cells) - 0.5) >= material.hole_radius;
}

// Unlit: the plate's colour, darkened where the scene's shadow falls on it from the first light.
fn shade(surface: SurfaceInput, material: MaterialParams) -> vec4<f32> {
    let lit = select(1.0, 0.5 + 0.5 * surface_shadow(0u, surface), light_count() > 0u);
    return vec4<f32>(rgba(material.color).rgb * lit, 1.0);
}
