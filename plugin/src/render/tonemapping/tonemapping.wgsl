// Tonemapping operators: exposed scene-linear colour in, display-linear colour (0..1) out.
// The operator codes (`TONEMAP_*`) are generated from `Tonemapping` in tonemapping.rs.

// ACES filmic: Stephen Hill's fit of the RRT + ODT (BakingLab, MIT), in its own primaries.
fn tonemap_aces(color: vec3<f32>) -> vec3<f32> {
    // sRGB → RRT_SAT (rows of Hill's ACESInputMat, written as columns).
    let input = mat3x3<f32>(
        vec3<f32>(0.59719, 0.07600, 0.02840),
        vec3<f32>(0.35458, 0.90834, 0.13383),
        vec3<f32>(0.04823, 0.01566, 0.83777),
    );
    // ODT_SAT → sRGB.
    let output = mat3x3<f32>(
        vec3<f32>(1.60475, -0.10208, -0.00327),
        vec3<f32>(-0.53108, 1.10813, -0.07276),
        vec3<f32>(-0.07367, -0.00605, 1.07602),
    );
    let v = input * color;
    let a = v * (v + 0.0245786) - 0.000090537;
    let b = v * (0.983729 * v + 0.4329510) + 0.238081;
    return clamp(output * (a / b), vec3<f32>(0.0), vec3<f32>(1.0));
}

// Sobotka's AgX with its default look, as Wrensch's minimal fit (MIT): inset into the AgX
// primaries, a log2 encoding over [-12.47, 4.03] EV, a polynomial sigmoid, outset, then the
// 2.2 display curve undone.
fn tonemap_agx(color: vec3<f32>) -> vec3<f32> {
    let inset = mat3x3<f32>(
        vec3<f32>(0.842479062253094, 0.0423282422610123, 0.0423756549057051),
        vec3<f32>(0.0784335999999992, 0.878468636469772, 0.0784336),
        vec3<f32>(0.0792237451477643, 0.0791661274605434, 0.879142973793104),
    );
    let outset = mat3x3<f32>(
        vec3<f32>(1.19687900512017, -0.0528968517574562, -0.0529716355144438),
        vec3<f32>(-0.0980208811401368, 1.15190312990417, -0.0980434501171241),
        vec3<f32>(-0.0990297440797205, -0.0989611768448433, 1.15107367264116),
    );
    let min_ev = -12.47393;
    let max_ev = 4.026069;
    let encoded = (clamp(log2(max(inset * color, vec3<f32>(1e-10))), vec3<f32>(min_ev), vec3<f32>(max_ev)) - min_ev)
        / (max_ev - min_ev);
    let x2 = encoded * encoded;
    let x4 = x2 * x2;
    let sigmoid = 15.5 * x4 * x2 - 40.14 * x4 * encoded + 31.96 * x4 - 6.868 * x2 * encoded
        + 0.4298 * x2 + 0.1191 * encoded - 0.00232;
    return clamp(pow(max(outset * sigmoid, vec3<f32>(0.0)), vec3<f32>(2.2)), vec3<f32>(0.0), vec3<f32>(1.0));
}

// Khronos PBR Neutral (the reference GLSL of the Khronos 3D Commerce group): takes off the
// 0.04 Fresnel floor, keeps colours whose peak is below 0.76 as they are, and compresses the
// peak above it while blending towards white (same hue, less saturation).
fn tonemap_neutral(color_in: vec3<f32>) -> vec3<f32> {
    let start_compression = 0.8 - 0.04;
    let desaturation = 0.15;
    let x = min(color_in.r, min(color_in.g, color_in.b));
    let offset = select(0.04, x - 6.25 * x * x, x < 0.08);
    var color = color_in - offset;
    let peak = max(color.r, max(color.g, color.b));
    if peak < start_compression {
        return color;
    }
    let d = 1.0 - start_compression;
    let new_peak = 1.0 - d * d / (peak + d - start_compression);
    color *= new_peak / peak;
    let g = 1.0 - 1.0 / (desaturation * (peak - new_peak) + 1.0);
    return mix(color, vec3<f32>(new_peak), g);
}

fn tonemap(color_in: vec3<f32>, curve: u32) -> vec3<f32> {
    // Negative light has no meaning here and NaN must not reach the display.
    let color = select(vec3<f32>(0.0), max(color_in, vec3<f32>(0.0)), color_in == color_in);
    switch curve {
        case TONEMAP_ACES: { return tonemap_aces(color); }
        case TONEMAP_AGX: { return tonemap_agx(color); }
        case TONEMAP_NEUTRAL: { return clamp(tonemap_neutral(color), vec3<f32>(0.0), vec3<f32>(1.0)); }
        default: { return clamp(color, vec3<f32>(0.0), vec3<f32>(1.0)); }
    }
}
