// The environment behind the scene (background.rs): where the scene's depth is still the
// cleared far plane, the source's radiance along the pixel's view ray, pre-exposed like the
// lights, from compute. Composed after sky.wgsl and environment_source.wgsl.

// Mirrors `BackgroundParams` in background.rs (the layout test checks them).
struct BackgroundParams {
    // Clip space to the environment's own frame (the inverse view-projection, then its turn
    // about +Y): a pixel's view ray is the difference of its far and near points.
    environment_from_clip: mat4x4<f32>,
    // x: what the source's radiance is multiplied with (intensity × exposure).
    scale: vec4<f32>,
    // xy: the target's size in pixels.
    size: vec4<u32>,
}

// A storage buffer, not a uniform: the matrix changes every frame under TAA's jitter, and
// lavapipe keeps a new copy of a shader specialized on a small uniform buffer's values each time
// they change (memory grows frame after frame).
@group(0) @binding(0) var<storage, read> params: BackgroundParams;
@group(0) @binding(1) var scene_depth: texture_2d<f32>;
@group(0) @binding(2) var scene_output: SceneOutput;

@compute @workgroup_size(8, 8)
fn cs_background(@builtin(global_invocation_id) pixel: vec3<u32>) {
    if pixel.x >= params.size.x || pixel.y >= params.size.y {
        return;
    }
    if textureLoad(scene_depth, pixel.xy, 0).r < 1.0 {
        return;
    }
    let ndc = vec2<f32>((f32(pixel.x) + 0.5) / f32(params.size.x) * 2.0 - 1.0,
        1.0 - (f32(pixel.y) + 0.5) / f32(params.size.y) * 2.0);
    let far = params.environment_from_clip * vec4<f32>(ndc, 1.0, 1.0);
    let near = params.environment_from_clip * vec4<f32>(ndc, 0.0, 1.0);
    let direction = normalize(far.xyz / far.w - near.xyz / near.w);
    textureStore(scene_output, pixel.xy, vec4<f32>(source_radiance(direction, 0.0) * params.scale.x, 1.0));
}
