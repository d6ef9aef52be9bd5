// Preetham's daylight sky (sky.rs computes its coefficients and holds the same evaluation on
// the CPU, which the tests compare with this one).

// Mirrors `SkyParams` in sky.rs (the layout test checks them).
struct SkyParams {
    // The Perez coefficients A to E, each for Y, x, y.
    perez: array<vec4<f32>, 5>,
    // Zenith Y, x, y over the Perez function at the zenith; w: the night fade.
    zenith: vec4<f32>,
    // xyz: unit vector towards the sun.
    sun: vec4<f32>,
    // rgb: the ground's radiance.
    ground: vec4<f32>,
}

// Luminance Y and chromaticity x, y (CIE xyY, in Perez's order) to linear sRGB (Rec. 709
// primaries, D65).
fn yxy_to_linear_srgb(yxy: vec3<f32>) -> vec3<f32> {
    let y = max(yxy.z, 1e-4);
    let big = vec3<f32>(yxy.y * yxy.x / y, yxy.x, (1.0 - yxy.y - yxy.z) * yxy.x / y);
    let rgb = vec3<f32>(
        dot(vec3<f32>(3.240454, -1.537139, -0.498531), big),
        dot(vec3<f32>(-0.969266, 1.876011, 0.041556), big),
        dot(vec3<f32>(0.055643, -0.204026, 1.057225), big),
    );
    return max(rgb, vec3<f32>(0.0));
}

// The radiance (cd/m²) seen looking along the unit vector `direction`.
fn sky_radiance(sky: SkyParams, direction: vec3<f32>) -> vec3<f32> {
    if direction.y < 0.0 {
        return sky.ground.rgb;
    }
    let cos_gamma = clamp(dot(direction, sky.sun.xyz), -1.0, 1.0);
    let gamma = acos(cos_gamma);
    let perez = (1.0 + sky.perez[0].xyz * exp(sky.perez[1].xyz / max(direction.y, 0.01)))
        * (1.0 + sky.perez[2].xyz * exp(sky.perez[3].xyz * gamma) + sky.perez[4].xyz * cos_gamma * cos_gamma);
    return yxy_to_linear_srgb(sky.zenith.xyz * perez) * sky.zenith.w;
}
