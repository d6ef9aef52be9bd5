// The deferred resolve's inputs and the rebuilding of a pixel: from its visibility id, the
// vertex output and footprint the rasterizer would have given the fragment stage, so a
// material's compute entry calls the same march and shading functions its fragment entries do.
// Composed after visibility.wgsl. Mirrors `ResolveBatch` and `Vertex` in Rust (the layout test
// checks them against each other).

// What one dispatch resolves: the pixels of one batch of draws (objects from `first_object`
// on, one mesh of `triangles` triangles), whose visibility ids are first_id..end_id.
struct ResolveBatch {
    // Framebuffer → world, to cast each pixel's view ray.
    inverse_view_projection: mat4x4<f32>,
    target_width: f32,
    target_height: f32,
    first_id: u32,
    end_id: u32,
    first_object: u32,
    triangles: u32,
    // The batch's place in the tile lists of deferred_classify.wgsl; UNCLASSIFIED where the
    // dispatch covers the whole target (one workgroup per tile, in rows and columns).
    batch: u32,
    tiles_across: u32,
    tile_count: u32,
    // 1 where this dispatch writes `background` where neither key holds a draw: a dispatch
    // over the whole target, which reads every key anyway (else the classification does).
    writes_background: u32,
    // (Uniform arrays need a 16-byte stride: no array here.)
    _padding: vec2<u32>,
    // The clear colour as the opaque pass would have cleared to (alpha marks it
    // display-referred).
    background: vec4<f32>,
}

// One vertex of a mesh's vertex buffer, read as storage (arrays, not vectors: no padding).
struct StoredVertex {
    position: array<f32, 3>,
    normal: array<f32, 3>,
    uv: array<f32, 2>,
    tangent: array<f32, 4>,
    color: array<f32, 4>,
}

@group(2) @binding(0) var<uniform> resolve_batch: ResolveBatch;
// The visibility keys then the candidate keys (visibility_read.wgsl): a settling resolve
// leaves each of its candidates' id where it won, 0 where it lost (`settle_candidate`); a pixel
// whose candidate id is not 0 shows the candidate, whatever its visibility key says.
@group(2) @binding(1) var<storage, read_write> visibility: array<vec2<u32>>;
@group(2) @binding(2) var<storage, read> mesh_vertices: array<StoredVertex>;
@group(2) @binding(3) var<storage, read> mesh_indices: array<u32>;
// `SceneOutput` is generated: the target's HDR scene format as a write-only storage texture.
@group(2) @binding(4) var scene_output: SceneOutput;
// The tiles each batch shows in, and how many (deferred_classify.wgsl).
@group(2) @binding(5) var<storage, read> batch_tiles: array<u32>;
@group(2) @binding(6) var<storage, read> tile_counts: array<u32>;

// A pixel a resolve invocation shades.
struct ResolveItem {
    pixel: vec2<u32>,
    object_index: u32,
    triangle: u32,
    // False where the pixel is outside the target or shows another batch.
    resolves: bool,
}

const UNCLASSIFIED: u32 = 0xffffffffu;

// The 8 × 8 tile workgroup `group` resolves: the group itself on a whole-target dispatch, else
// the batch's tile at `group`'s place in its list (TILES_PER_ROW tiles a row), if there is one.
fn resolve_tile(group: vec2<u32>) -> vec3<u32> {
    if resolve_batch.batch == UNCLASSIFIED {
        return vec3<u32>(group, 1u);
    }
    let index = group.y * TILES_PER_ROW + group.x;
    if index >= tile_counts[resolve_batch.batch] {
        return vec3<u32>(0u);
    }
    let tile = batch_tiles[resolve_batch.batch * resolve_batch.tile_count + index];
    return vec3<u32>(tile % resolve_batch.tiles_across, tile / resolve_batch.tiles_across, 1u);
}

// Which pixel lane `local` of workgroup `group` resolves, and whether the batch shows there.
// (Composed after visibility_read.wgsl.)
fn resolve_item(group: vec2<u32>, local: vec2<u32>) -> ResolveItem {
    var item: ResolveItem;
    item.resolves = false;
    let tile = resolve_tile(group);
    if tile.z == 0u {
        return item;
    }
    let pixel = tile.xy * TILE_SIDE + local;
    item.pixel = pixel;
    if f32(pixel.x) >= resolve_batch.target_width || f32(pixel.y) >= resolve_batch.target_height {
        return item;
    }
    let candidate = visibility[candidate_index(pixel, frame.target_size.xy)].x;
    let visible = select(visible_id(pixel, frame.target_size.x), candidate, candidate != 0u);
    if visible == 0u && resolve_batch.writes_background != 0u {
        textureStore(scene_output, pixel, resolve_batch.background);
    }
    item.resolves = visible >= resolve_batch.first_id && visible < resolve_batch.end_id;
    let within = visible - resolve_batch.first_id;
    let triangles = max(resolve_batch.triangles, 1u);
    item.object_index = resolve_batch.first_object + within / triangles;
    item.triangle = within % triangles;
    return item;
}

// A settling resolve's verdict on its candidate at `pixel`: its surface at clip depth `depth`
// shows where it is nearer than what the visibility pass kept (and `covers`: the view ray did
// not leave the surface); else the pixel is the visibility pass's again, or the background
// where that kept no draw (written here: the classification and the resolves write it only
// where neither key holds a draw). Either way the key keeps the pixel's settled depth
// (settled_depth.wgsl), a lost candidate without its id. Whether it shows.
fn settle_candidate(pixel: vec2<u32>, depth: f32, covers: bool) -> bool {
    let index = candidate_index(pixel, frame.target_size.xy);
    let behind = visible_depth(pixel, frame.target_size.x);
    let shows = covers && depth < behind;
    if !shows && visible_id(pixel, frame.target_size.x) == 0u {
        textureStore(scene_output, pixel, resolve_batch.background);
    }
    let id = select(0u, visibility[index].x, shows);
    visibility[index] = vec2<u32>(id, ~bitcast<u32>(select(behind, depth, shows)));
    return shows;
}

// The view ray through framebuffer position `pixel` (visibility.wgsl's `ray_through_pixel`).
fn pixel_ray(pixel: vec2<f32>) -> Ray {
    return ray_through_pixel(resolve_batch.inverse_view_projection, resolve_target_size(), pixel, frame.camera_position.xyz, frame.view_direction);
}

// The view ray through the framebuffer position `offset` pixels from `ray`'s: the unprojection
// is affine in the framebuffer at a fixed depth for perspective and orthographic cameras alike
// (the inverse's w does not depend on the pixel), so a quad neighbour's ray is the pixel's own
// moved by a step, with no matrix product of its own.
fn offset_ray(ray: Ray, offset: vec2<f32>) -> Ray {
    let inverse = resolve_batch.inverse_view_projection;
    let ndc = offset * vec2<f32>(2.0 / resolve_batch.target_width, -2.0 / resolve_batch.target_height);
    let along = inverse[0].xyz * ndc.x + inverse[1].xyz * ndc.y;
    // As `ray_through_pixel`: from the near plane along the view (orthographic), or from the
    // eye through depth ½ (perspective).
    if frame.view_direction.w > 0.5 {
        return Ray(ray.origin + along / inverse[3].w, ray.direction);
    }
    return Ray(ray.origin, ray.direction + along / (0.5 * inverse[2].w + inverse[3].w));
}

fn resolve_target_size() -> vec2<f32> {
    return vec2<f32>(resolve_batch.target_width, resolve_batch.target_height);
}

fn stored_vertex_in(index: u32) -> VertexIn {
    let v = mesh_vertices[index];
    return VertexIn(
        vec3<f32>(v.position[0], v.position[1], v.position[2]),
        vec3<f32>(v.normal[0], v.normal[1], v.normal[2]),
        vec2<f32>(v.uv[0], v.uv[1]),
        vec4<f32>(v.tangent[0], v.tangent[1], v.tangent[2], v.tangent[3]),
        vec4<f32>(v.color[0], v.color[1], v.color[2], v.color[3]),
    );
}

// The three vertices of a triangle through the shared vertex stage.
struct TriangleVertices {
    a: VertexOut,
    b: VertexOut,
    c: VertexOut,
}

// The attributes at barycentric weights `w`, as the rasterizer interpolates them (perspective-
// correct: the weights come from the world-space ray).
fn interpolate_vertex(t: TriangleVertices, w: vec3<f32>) -> VertexOut {
    var out = t.a;
    out.world_position = t.a.world_position * w.x + t.b.world_position * w.y + t.c.world_position * w.z;
    out.world_normal = t.a.world_normal * w.x + t.b.world_normal * w.y + t.c.world_normal * w.z;
    out.uv = t.a.uv * w.x + t.b.uv * w.y + t.c.uv * w.z;
    out.world_tangent = t.a.world_tangent * w.x + t.b.world_tangent * w.y + t.c.world_tangent * w.z;
    out.color = t.a.color * w.x + t.b.color * w.y + t.c.color * w.z;
    return out;
}

// What the fragment stage would have received at `item`'s pixel.
struct ResolvedPixel {
    vertex: VertexOut,
    footprint: PixelFootprint,
    front_facing: bool,
}

// Rebuilds `item`'s pixel from its triangle: the vertex output at the pixel centre, the
// footprint from the rays through its quad neighbours across and down (where the fragment
// stage's derivatives look), and which side of the triangle the eye sees.
fn resolve_pixel(item: ResolveItem) -> ResolvedPixel {
    let transform = transforms[item.object_index];
    var t: TriangleVertices;
    let first = item.triangle * 3u;
    t.a = transform_vertex(stored_vertex_in(mesh_indices[first]), transform.model, transform.normal_matrix, transform.determinant_sign, item.object_index);
    t.b = transform_vertex(stored_vertex_in(mesh_indices[first + 1u]), transform.model, transform.normal_matrix, transform.determinant_sign, item.object_index);
    t.c = transform_vertex(stored_vertex_in(mesh_indices[first + 2u]), transform.model, transform.normal_matrix, transform.determinant_sign, item.object_index);
    let p0 = t.a.world_position;
    let p1 = t.b.world_position;
    let p2 = t.c.world_position;

    let centre = vec2<f32>(item.pixel) + 0.5;
    let ray = pixel_ray(centre);
    var resolved: ResolvedPixel;
    resolved.vertex = interpolate_vertex(t, ray_barycentrics(ray, p0, p1, p2));
    // The fragment stage differences a 2 × 2 quad's pixels: the neighbour across is to the
    // right in the quad's left column and to the left in its right one (likewise down).
    let step = 1.0 - 2.0 * vec2<f32>(item.pixel % vec2<u32>(2u));
    let across = interpolate_vertex(t, ray_barycentrics(offset_ray(ray, vec2<f32>(step.x, 0.0)), p0, p1, p2));
    let down = interpolate_vertex(t, ray_barycentrics(offset_ray(ray, vec2<f32>(0.0, step.y)), p0, p1, p2));
    resolved.footprint = PixelFootprint((across.uv - resolved.vertex.uv) * step.x, (down.uv - resolved.vertex.uv) * step.y,
        (across.world_position - resolved.vertex.world_position) * step.x,
        (down.world_position - resolved.vertex.world_position) * step.y,
        (across.world_normal - resolved.vertex.world_normal) * step.x,
        (down.world_normal - resolved.vertex.world_normal) * step.y);
    let clip = frame.view_projection * vec4<f32>(resolved.vertex.world_position, 1.0);
    resolved.vertex.clip_position = vec4<f32>(centre, clip.z / clip.w, 1.0);
    // Counter-clockwise seen from the eye is the front (wgpu's default winding).
    resolved.front_facing = dot(cross(p1 - p0, p2 - p0), ray.direction) < 0.0;
    return resolved;
}
