// The deferred path's background: where no opaque draw covers a pixel (visibility id 0), the
// clear colour, written from compute. On a deferred frame whose opaque phase has nothing to draw
// this replaces that phase's render pass, which would only clear the scene (a full-screen
// fragment pass: measured in sandbox/BENCHMARKS.md).

// Mirrors `BackgroundParams` in deferred_background.rs (the layout test checks them).
struct BackgroundParams {
    // The clear colour as the opaque pass would have cleared to (alpha marks it
    // display-referred).
    clear_color: vec4<f32>,
    width: u32,
    height: u32,
    _padding: vec2<u32>,
}

// The visibility keys (visibility.wgsl), each read as (id, depth bits).
@group(0) @binding(0) var<storage, read> visibility: array<vec2<u32>>;
@group(0) @binding(1) var scene_output: SceneOutput;
@group(0) @binding(2) var<uniform> params: BackgroundParams;

@compute @workgroup_size(8, 8)
fn cs_background(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x >= params.width || id.y >= params.height {
        return;
    }
    if visibility[id.y * params.width + id.x].x == 0u {
        textureStore(scene_output, id.xy, params.clear_color);
    }
}
