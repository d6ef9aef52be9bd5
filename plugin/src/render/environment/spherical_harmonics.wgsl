// The nine real spherical harmonics of bands 0 to 2 at a unit direction (Ramamoorthi & Hanrahan
// 2001, "An Efficient Representation for Irradiance Environment Maps", eq. 3), in the order
// the environment's irradiance coefficients are stored: projecting (prefilter) and evaluating
// (environment.wgsl) read the same basis.
fn spherical_harmonics(d: vec3<f32>) -> array<f32, 9> {
    return array<f32, 9>(
        0.282095,
        0.488603 * d.y,
        0.488603 * d.z,
        0.488603 * d.x,
        1.092548 * d.x * d.y,
        1.092548 * d.y * d.z,
        0.315392 * (3.0 * d.z * d.z - 1.0),
        1.092548 * d.x * d.z,
        0.546274 * (d.x * d.x - d.y * d.y),
    );
}
