// The deferred path's background: where no opaque draw covers a pixel (visibility id 0), the
// clear colour, written from compute. On a deferred frame whose opaque phase has nothing to draw
// this replaces that phase's render pass, which would only clear the scene (a full-screen
// fragment pass: measured in sandbox/BENCHMARKS.md).

@group(0) @binding(0) var visibility: texture_2d<u32>;
@group(0) @binding(1) var scene_output: SceneOutput;
// The clear colour as the opaque pass would have cleared to (alpha marks it display-referred).
@group(0) @binding(2) var<uniform> clear_color: vec4<f32>;

@compute @workgroup_size(8, 8)
fn cs_background(@builtin(global_invocation_id) id: vec3<u32>) {
    if any(id.xy >= textureDimensions(visibility)) {
        return;
    }
    if textureLoad(visibility, id.xy, 0).x == 0u {
        textureStore(scene_output, id.xy, clear_color);
    }
}
