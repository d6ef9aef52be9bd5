// The visibility pass, the deferred path's prepass: with its depth, each pixel keeps one 32-bit
// id that names the draw and the triangle it shows. Each draw owns a run of ids, one per
// triangle, starting at its `first_visibility_id` (mesh_vertex.wgsl); 0 marks a pixel no
// opaque draw covers. Composed after a material's files (with `enable primitive_index;`) where
// the adapter can run the deferred path. Also the view ray through a pixel and where it meets a
// triangle, for finding a pixel's surface in compute (the resolve, the polygon pass).

// One 64-bit key per pixel, row by row: the depth's bits inverted above the id, so that
// atomicMax keeps the nearest fragment whatever the order fragments arrive in (ties: the larger
// id). Cleared to 0 before the pass; outside it a one-key stand-in is bound. As many candidate
// keys follow (material/candidates.wgsl).
@group(0) @binding(8) var<storage, read_write> visibility_keys: array<atomic<u64>>;
// The same keys as 32-bit words (little-endian: a key's depth is its odd word), for reading a
// key: WGSL's 64-bit atomics offer only min and max.
@group(0) @binding(9) var<storage, read_write> visibility_words: array<atomic<u32>>;

// The id a pixel of draw `object_index`, triangle `triangle`, keeps: 0 for a draw the frame
// had no ids left for (it then shows the background rather than another draw's triangle).
fn visibility_id(object_index: u32, triangle: u32) -> u32 {
    let first = transforms[object_index].first_visibility_id;
    return select(first + triangle, 0u, first == 0u);
}

// Merges `id`, seen at framebuffer position `position` at clip depth `depth`, into the pixel's
// key (and counts the merge where a test counts fragments: FragmentInvocationCounter).
fn keep_visible(position: vec4<f32>, depth: f32, id: u32) {
    count_fragment_invocation();
    atomicMax(&visibility_keys[visibility_key_index(position)], visibility_key(depth, id));
}

// The index of the key of framebuffer position `position`.
fn visibility_key_index(position: vec4<f32>) -> u32 {
    let pixel = vec2<u32>(position.xy);
    return pixel.y * frame.target_size.x + pixel.x;
}

// The key of `id` at clip depth `depth`: nearer depths compare larger.
fn visibility_key(depth: f32, id: u32) -> u64 {
    return (u64(~bitcast<u32>(depth)) << 32u) | u64(id);
}

// The visibility pass of a material whose prepass has no fragment stage of its own. The depth
// test runs first (forced: the atomic is the only side effect, and a fragment it rejects could
// only have lost the merge).
@fragment @early_depth_test(force)
fn fs_visibility(in: VertexOut, @builtin(primitive_index) triangle: u32) {
    keep_visible(in.clip_position, in.clip_position.z, visibility_id(in.object_index, triangle));
}

// The world point on the view ray through framebuffer position `pixel` of a target `size`
// pixels large at clip depth `depth`, by the `inverse` view-projection.
fn unproject_pixel(inverse: mat4x4<f32>, size: vec2<f32>, pixel: vec2<f32>, depth: f32) -> vec3<f32> {
    let ndc = vec2<f32>(pixel.x / size.x * 2.0 - 1.0, 1.0 - pixel.y / size.y * 2.0);
    let world = inverse * vec4<f32>(ndc, depth, 1.0);
    return world.xyz / world.w;
}

struct Ray {
    origin: vec3<f32>,
    direction: vec3<f32>,
}

// The view ray through framebuffer position `pixel` of a camera at `eye` looking along
// `view_direction` (w: 1 for orthographic): from the eye (perspective), or from the near plane
// along the view (orthographic).
fn ray_through_pixel(inverse: mat4x4<f32>, size: vec2<f32>, pixel: vec2<f32>, eye: vec3<f32>, view_direction: vec4<f32>) -> Ray {
    if view_direction.w > 0.5 {
        return Ray(unproject_pixel(inverse, size, pixel, 0.0), view_direction.xyz);
    }
    // Depth ½ stays finite under an infinite far plane.
    return Ray(eye, unproject_pixel(inverse, size, pixel, 0.5) - eye);
}

// The barycentric weights of the point where `ray` meets the plane of triangle p0 p1 p2
// (Möller–Trumbore without the inside test: off the triangle they extrapolate, as the
// rasterizer does for the helper pixels derivatives come from).
fn ray_barycentrics(ray: Ray, p0: vec3<f32>, p1: vec3<f32>, p2: vec3<f32>) -> vec3<f32> {
    let edge1 = p1 - p0;
    let edge2 = p2 - p0;
    let p = cross(ray.direction, edge2);
    let determinant = dot(edge1, p);
    // Edge-on (no pixel of it is rasterized anyway): the first vertex.
    if abs(determinant) < 1e-30 {
        return vec3<f32>(1.0, 0.0, 0.0);
    }
    let t = ray.origin - p0;
    let q = cross(t, edge1);
    let u = dot(t, p) / determinant;
    let v = dot(ray.direction, q) / determinant;
    return vec3<f32>(1.0 - u - v, u, v);
}
