// The polygon pass: the visibility keys of a deferred frame's large few-triangle draws, found in
// compute rather than rasterized. Each pixel tests every listed triangle whose screen rectangle
// holds it and merges the nearest into its key with the id the visibility pass would have
// merged. Coverage is the rasterizer's: edge functions over the corners snapped as it snaps
// them, with its top-left rule for a pixel centre on an edge; so is the depth, affine in the
// framebuffer. A triangle the rasterizer would clip first (a corner behind the eye) is tested
// by the view ray alone, its depth where the ray meets its plane.
// Composed after frame.wgsl, mesh_vertex.wgsl and visibility.wgsl. Mirrors `VisiblePolygon`
// (listed_triangle.rs) and `PolygonPass` in polygons.rs (the layout test checks them).

// One triangle of a listed draw, in world space.
struct VisiblePolygon {
    a: vec4<f32>,
    b: vec4<f32>,
    c: vec4<f32>,
    // Where snapped_x.w is 1: the corners in the framebuffer in 1/2^SUB_PIXEL_BITS pixels,
    // ordered so that the inside is where every edge function is positive (the culling is done).
    snapped_x: vec4<i32>,
    snapped_y: vec4<i32>,
    // Where snapped: its clip depth as the rasterizer interpolates it, the first corner's (z)
    // and its rise per 1/2^SUB_PIXEL_BITS pixel across (x) and down (y) from that corner; and
    // the nearest clip depth it reaches (w: 0 where not snapped). The list is sorted by w.
    depth_plane: vec4<f32>,
    // The pixels it may cover: x, y from (inclusive) and to (exclusive).
    rect: vec4<u32>,
    id: u32,
    // The face the draw's pipeline culls: CULL_NONE, CULL_FRONT or CULL_BACK.
    culled_face: u32,
    _padding: vec2<u32>,
}

// The pass: the camera (as the frame's uniform holds it) and target, the listed triangles'
// screen rectangle from `origin` on; `candidates` 1 where they are depth-offset polygons,
// merged into the candidate keys (material/candidates.wgsl) where they lie in front of what
// the visibility pass kept.
struct PolygonPass {
    view_projection: mat4x4<f32>,
    inverse_view_projection: mat4x4<f32>,
    camera_position: vec4<f32>,
    view_direction: vec4<f32>,
    target_size: vec2<u32>,
    origin: vec2<u32>,
    count: u32,
    candidates: u32,
    _padding: vec2<u32>,
}

const SUB_PIXEL_BITS: u32 = 8u;
const CULL_NONE: u32 = 0u;
const CULL_FRONT: u32 = 1u;
const CULL_BACK: u32 = 2u;

// Storage, not uniform, and the frame's uniform unread: lavapipe compiles a shader again for
// each value of a uniform it branches on, and keeps every one (the camera moves each frame).
@group(1) @binding(0) var<storage, read> polygon_pass: PolygonPass;
@group(1) @binding(1) var<storage, read> polygons: array<VisiblePolygon>;

// Whether the edge from `start` to `end` (snapped) holds the pixel centre `centre` on its
// inside: in front of it, or on it where it is a top or left edge (the rasterizer's rule, so a
// centre on an edge two triangles share is covered once). The differences are exact in i32
// (corners lie within `SNAP_RANGE` of listed_triangle.rs); their products need 64 bits.
fn edge_holds(start: vec2<i32>, end: vec2<i32>, centre: vec2<i32>) -> bool {
    let along = end - start;
    let to_centre = centre - start;
    let side = i64(along.x) * i64(to_centre.y) - i64(along.y) * i64(to_centre.x);
    let top_left = along.y < 0 || (along.y == 0 && along.x > 0);
    return side > i64(0) || (side == i64(0) && top_left);
}

// Whether `polygon`, which has no snapped corners, covers the pixel centre on view ray `ray`
// (culling its draw's culled face there).
fn ray_covers(polygon: VisiblePolygon, ray: Ray) -> bool {
    let a = polygon.a.xyz;
    let b = polygon.b.xyz;
    let c = polygon.c.xyz;
    // Counter-clockwise seen from the eye is the front (wgpu's default winding); edge-on shows
    // nothing, as the rasterizer draws no pixel of it.
    let facing = dot(cross(b - a, c - a), ray.direction);
    let culled = facing == 0.0 || (polygon.culled_face == CULL_FRONT && facing < 0.0)
        || (polygon.culled_face == CULL_BACK && facing > 0.0);
    return !culled && all(ray_barycentrics(ray, a, b, c) >= vec3<f32>(0.0));
}

// The clip depth of `polygon` at `pixel`'s centre where it covers it as the rasterizer would,
// else a depth outside 0..1. Snapped, by its edge functions and its depth in the framebuffer;
// else by the view ray `ray` (the depth where the ray meets its plane).
fn polygon_depth(polygon: VisiblePolygon, pixel: vec2<u32>, ray: Ray) -> f32 {
    if polygon.snapped_x.w == 1 {
        let one = 1 << SUB_PIXEL_BITS;
        let centre = vec2<i32>(pixel) * one + one / 2;
        let a = vec2<i32>(polygon.snapped_x.x, polygon.snapped_y.x);
        let b = vec2<i32>(polygon.snapped_x.y, polygon.snapped_y.y);
        let c = vec2<i32>(polygon.snapped_x.z, polygon.snapped_y.z);
        if !(edge_holds(a, b, centre) && edge_holds(b, c, centre) && edge_holds(c, a, centre)) {
            return -1.0;
        }
        return polygon.depth_plane.z + dot(polygon.depth_plane.xy, vec2<f32>(centre - a));
    }
    if !ray_covers(polygon, ray) {
        return -1.0;
    }
    let a = polygon.a.xyz;
    let b = polygon.b.xyz;
    let c = polygon.c.xyz;
    // Off the triangle by a rounding (a covered centre on its edge) the plane still holds.
    let w = ray_barycentrics(ray, a, b, c);
    let clip = polygon_pass.view_projection * vec4<f32>(a * w.x + b * w.y + c * w.z, 1.0);
    return select(-1.0, clip.z / clip.w, clip.w > 0.0);
}

@compute @workgroup_size(8, 8)
fn cs_visible_polygons(@builtin(global_invocation_id) id: vec3<u32>) {
    let pixel = polygon_pass.origin + id.xy;
    let size = polygon_pass.target_size;
    if any(pixel >= size) {
        return;
    }
    let ray = ray_through_pixel(polygon_pass.inverse_view_projection, vec2<f32>(size), vec2<f32>(pixel) + 0.5,
        polygon_pass.camera_position.xyz, polygon_pass.view_direction);
    let visible = pixel.y * size.x + pixel.x;
    var key_index = visible;
    var behind = 1.0;
    if polygon_pass.candidates != 0u {
        key_index += size.x * size.y;
        // The visibility pass is done: a polygon behind what it kept hides its relief too.
        if atomicLoad(&visibility_words[visible * 2u]) != 0u {
            behind = bitcast<f32>(~atomicLoad(&visibility_words[visible * 2u + 1u]));
        }
    }
    // The nearest key (ties to the larger id, as the visibility pass's atomic max) in front of
    // `behind` and the clip volume's far plane.
    var nearest = u64(0u);
    var nearest_depth = behind;
    for (var index = 0u; index < polygon_pass.count; index++) {
        let polygon = polygons[index];
        // Nearest first: no triangle from here on comes nearer than what the pixel found.
        if polygon.depth_plane.w > nearest_depth {
            break;
        }
        if any(pixel < polygon.rect.xy) || any(pixel >= polygon.rect.zw) {
            continue;
        }
        let depth = polygon_depth(polygon, pixel, ray);
        if depth >= 0.0 && depth <= nearest_depth {
            let key = visibility_key(depth, polygon.id);
            if key > nearest {
                nearest = key;
                nearest_depth = depth;
            }
        }
    }
    if nearest == u64(0u) {
        return;
    }
    if polygon_pass.candidates != 0u {
        // The candidate pass may have rasterized other candidates here already.
        atomicMax(&visibility_keys[key_index], nearest);
    } else {
        // The keys were just cleared and each pixel is one invocation's: a plain store.
        atomicStore(&visibility_keys[key_index], nearest);
    }
}
