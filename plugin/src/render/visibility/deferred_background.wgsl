// The deferred path's background: where no opaque draw covers a pixel (visibility id 0), the
// clear colour, written from compute. On a deferred frame whose opaque phase has nothing to draw
// this replaces that phase's render pass, which would only clear the scene (a full-screen
// fragment pass: sandbox/BENCHMARKS.md, "What the numbers mean").

// Mirrors `BackgroundParams` in deferred_background.rs (the layout test checks them).
struct BackgroundParams {
    // The clear colour as the opaque pass would have cleared to (alpha marks it
    // display-referred).
    clear_color: vec4<f32>,
    width: u32,
    height: u32,
    _padding: vec2<u32>,
}

// The visibility keys (visibility_read.wgsl).
@group(0) @binding(0) var<storage, read> visibility: array<vec2<u32>>;
@group(0) @binding(1) var scene_output: SceneOutput;
@group(0) @binding(2) var<uniform> params: BackgroundParams;

@compute @workgroup_size(TILE_SIDE, TILE_SIDE)
fn cs_background(@builtin(global_invocation_id) pixel: vec3<u32>) {
    if pixel.x >= params.width || pixel.y >= params.height {
        return;
    }
    if visible_id(pixel.xy, params.width) == 0u {
        textureStore(scene_output, pixel.xy, params.clear_color);
    }
}
