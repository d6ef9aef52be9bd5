// The post filter: FXAA (Lottes 2009, the 3.11 quality algorithm), on the tonemapped image, for
// frames without a history. Each pixel on a contrasting edge finds the edge's direction and
// ends and is blended across it by how far along it lies; a lone bright pixel is blended by
// its contrast with the neighbourhood. The generated prelude declares `output` (the display
// format) and `LINEAR_INPUT` (true where the display holds linear floats, not sRGB bytes);
// `sample_at`, the bilinear read of the edge search and of the final blend, comes from
// fxaa_filtered.wgsl or fxaa_loads.wgsl, composed after this file.

@group(0) @binding(0) var tonemapped: texture_2d<f32>;

// The camera's FastApproximateAntiAliasing, within its limits (Lottes's "quality" defaults:
// 0.0312, 0.125 and his 0.75). Edges of less contrast than either threshold stay as they are;
// a lone bright pixel gets `subpixel_blending` of the sub-pixel blend.
struct FxaaSettings {
    contrast_threshold: f32,
    relative_threshold: f32,
    subpixel_blending: f32,
    _padding: f32,
}

// A read-only storage buffer, not a uniform: the thresholds steer branches, and Mesa's
// lavapipe compiles a shader whose uniforms steer its branches again at each bind.
@group(0) @binding(3) var<storage, read> settings: FxaaSettings;
// The search along the edge: ten steps of growing length, at most 25 pixels each way.
const EDGE_STEPS: u32 = 10u;

// The length of search step `i`: 1, 1, 1, 1, 1.5, 2, 2, 2, 4, 8.5 pixels.
fn edge_step(i: u32) -> f32 {
    if i < 4u {
        return 1.0;
    }
    if i == 4u {
        return 1.5;
    }
    if i < 8u {
        return 2.0;
    }
    return select(8.5, 4.0, i == 8u);
}

fn load_clamped(pixel: vec2<i32>) -> vec4<f32> {
    let last = vec2<i32>(textureDimensions(tonemapped)) - 1;
    return textureLoad(tonemapped, clamp(pixel, vec2<i32>(0), last), 0);
}

// Perceived brightness: of the encoded values, as the eye sees steps (linear floats are
// brought near that with a square root).
fn luma_of(colour: vec4<f32>) -> f32 {
    let value = dot(clamp(colour.rgb, vec3<f32>(0.0), vec3<f32>(1.0)), vec3<f32>(0.299, 0.587, 0.114));
    return select(value, sqrt(value), LINEAR_INPUT);
}

fn luma_at(pixel: vec2<i32>) -> f32 {
    return luma_of(load_clamped(pixel));
}

fn fxaa(pixel: vec2<i32>) -> vec4<f32> {
    let centre_colour = load_clamped(pixel);
    let m = luma_of(centre_colour);
    // y grows downwards: "north" is the row above.
    let n = luma_at(pixel + vec2<i32>(0, -1));
    let s = luma_at(pixel + vec2<i32>(0, 1));
    let e = luma_at(pixel + vec2<i32>(1, 0));
    let w = luma_at(pixel + vec2<i32>(-1, 0));
    let highest = max(max(max(n, s), max(e, w)), m);
    let lowest = min(min(min(n, s), min(e, w)), m);
    let contrast = highest - lowest;
    if contrast < max(settings.contrast_threshold, settings.relative_threshold * highest) {
        return centre_colour;
    }
    let ne = luma_at(pixel + vec2<i32>(1, -1));
    let nw = luma_at(pixel + vec2<i32>(-1, -1));
    let se = luma_at(pixel + vec2<i32>(1, 1));
    let sw = luma_at(pixel + vec2<i32>(-1, 1));

    // The sub-pixel blend: how far the pixel stands out of its neighbourhood's low-pass.
    let neighbourhood = (2.0 * (n + s + e + w) + ne + nw + se + sw) / 12.0;
    let standing_out = clamp(abs(neighbourhood - m) / contrast, 0.0, 1.0);
    let smooth_out = smoothstep(0.0, 1.0, standing_out);
    let subpixel_blend = smooth_out * smooth_out * settings.subpixel_blending;

    // The edge runs along rows where luma changes most from row to row.
    let horizontal = 2.0 * abs(n + s - 2.0 * m) + abs(ne + se - 2.0 * e) + abs(nw + sw - 2.0 * w);
    let vertical = 2.0 * abs(e + w - 2.0 * m) + abs(ne + nw - 2.0 * n) + abs(se + sw - 2.0 * s);
    let along_rows = horizontal >= vertical;
    // Across the edge: towards the neighbour that differs more.
    let positive = select(e, s, along_rows);
    let negative = select(w, n, along_rows);
    let positive_gradient = abs(positive - m);
    let negative_gradient = abs(negative - m);
    var across = select(vec2<f32>(1.0, 0.0), vec2<f32>(0.0, 1.0), along_rows);
    var opposite = positive;
    var gradient = positive_gradient;
    if positive_gradient < negative_gradient {
        across = -across;
        opposite = negative;
        gradient = negative_gradient;
    }

    // Walk both ways along the edge, half a pixel across it, to where its luma changes.
    let centre = vec2<f32>(pixel) + 0.5;
    let on_edge = centre + across * 0.5;
    let along = select(vec2<f32>(0.0, 1.0), vec2<f32>(1.0, 0.0), along_rows);
    let edge_luma = 0.5 * (m + opposite);
    let threshold = 0.25 * gradient;
    var forward = on_edge + along;
    var forward_delta = luma_of(sample_at(forward)) - edge_luma;
    var forward_end = abs(forward_delta) >= threshold;
    for (var i = 0u; i < EDGE_STEPS && !forward_end; i += 1u) {
        forward += along * edge_step(i);
        forward_delta = luma_of(sample_at(forward)) - edge_luma;
        forward_end = abs(forward_delta) >= threshold;
    }
    var backward = on_edge - along;
    var backward_delta = luma_of(sample_at(backward)) - edge_luma;
    var backward_end = abs(backward_delta) >= threshold;
    for (var i = 0u; i < EDGE_STEPS && !backward_end; i += 1u) {
        backward -= along * edge_step(i);
        backward_delta = luma_of(sample_at(backward)) - edge_luma;
        backward_end = abs(backward_delta) >= threshold;
    }
    let forward_distance = dot(forward - centre, along);
    let backward_distance = dot(centre - backward, along);
    let nearer_forward = forward_distance <= backward_distance;
    let shortest = min(forward_distance, backward_distance);
    let end_delta = select(backward_delta, forward_delta, nearer_forward);
    // Blend only on the side of the edge whose end turns towards this pixel's luma.
    var edge_blend = 0.5 - shortest / (forward_distance + backward_distance);
    if (end_delta >= 0.0) == (m - edge_luma >= 0.0) {
        edge_blend = 0.0;
    }
    let blend = max(subpixel_blend, edge_blend);
    return sample_at(centre + across * blend);
}
