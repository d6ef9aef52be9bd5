// The seed port (seed_port.wgsl) as one compute dispatch over the target, 8 × 8 pixels per
// workgroup: the like-for-like figure beside our compute resolve. Composed after seed_port.wgsl
// (and what it is composed after); mirrors `SeedPortView` in seed_port/compute.rs.
//
// Each invocation derives what the rasterizer hands fs_seed_port for its pixel centre, from the
// same inputs the raster pass has: the plane's mesh triangle, its transform and the frame's camera.
// - The vertex stage: `transform_vertex` (mesh_vertex.wgsl) on the triangle's three vertices,
//   as vs_main runs it.
// - Interpolation: the pixel's view ray (the inverse view-projection of its centre at depths 0
//   and 1) meets the triangle's plane; the barycentrics of that point in world space weight the
//   vertex outputs. That is perspective-correct interpolation, what the rasterizer does. The
//   plane's attributes are affine across both of its triangles (one flat quad, uniform UVs), so
//   the first triangle's barycentrics, negative outside it, give every pixel's values.
// - The texture gradients (dpdx / dpdy of uv): the difference of the interpolated uv from this
//   pixel centre to the next one across and down. On the bench's orthographic view uv is affine
//   in the pixel position, so that is exactly the rasterizer's difference within a 2 × 2 quad,
//   fine or coarse alike; under a perspective camera it differs from it by the second derivative
//   over one pixel.

struct SeedPortView {
    inverse_view_projection: mat4x4<f32>,
    // The plane's first triangle as its mesh stores it (object space); w unused, uvs in xy.
    corner_positions: array<vec4<f32>, 3>,
    corner_normals: array<vec4<f32>, 3>,
    // xyz: dP/du, w: the MikkTSpace sign.
    corner_tangents: array<vec4<f32>, 3>,
    corner_uvs: array<vec4<f32>, 3>,
    // xy: the target's width and height in pixels.
    target_size: vec4<u32>,
    // The same plane solved once on the CPU, in world space, for `cs_seed_port_analytic`: a
    // point of it and its normal (what the view ray meets), each uv as an affine function of
    // the world point (dot with xyz, plus w), and the surface's normal and tangent.
    plane_point: vec4<f32>,
    plane_normal: vec4<f32>,
    uv_from_world: array<vec4<f32>, 2>,
    surface_normal: vec4<f32>,
    surface_tangent: vec4<f32>,
}

@group(2) @binding(0) var<uniform> view: SeedPortView;
// `SceneOutput` is generated: the target's HDR scene format, where the raster pass draws.
@group(2) @binding(1) var scene_output: SceneOutput;

// The vertex stage's outputs at the three corners of the plane's first triangle: a struct of
// three rather than an array, which a GPU compiler may keep in memory, not registers, where it is
// indexed by a loop or passed by value.
struct SeedPortCorners {
    a: VertexOut,
    b: VertexOut,
    c: VertexOut,
}

fn seed_port_corner(i: u32) -> VertexOut {
    let transform = transforms[0];
    let vertex = VertexIn(view.corner_positions[i].xyz, view.corner_normals[i].xyz, view.corner_uvs[i].xy,
        view.corner_tangents[i], vec4<f32>(1.0));
    return transform_vertex(vertex, transform.model, transform.normal_matrix, transform.determinant_sign, 0u);
}

fn seed_port_corners() -> SeedPortCorners {
    return SeedPortCorners(seed_port_corner(0u), seed_port_corner(1u), seed_port_corner(2u));
}

// The world point at `ndc` (x, y) and depth `depth` in wgpu's 0..1 clip depth.
fn unproject(ndc: vec2<f32>, depth: f32) -> vec3<f32> {
    let point = view.inverse_view_projection * vec4<f32>(ndc, depth, 1.0);
    return point.xyz / point.w;
}

// The point of the plane through `point` with `normal` that `pixel` (a position in pixels, y
// down, as the rasterizer counts them) sees.
fn seed_port_plane_point(pixel: vec2<f32>, point: vec3<f32>, normal: vec3<f32>) -> vec3<f32> {
    let size = vec2<f32>(view.target_size.xy);
    let ndc = vec2<f32>(pixel.x / size.x * 2.0 - 1.0, 1.0 - pixel.y / size.y * 2.0);
    let near = unproject(ndc, 0.0);
    let far = unproject(ndc, 1.0);
    let along = dot(normal, far - near);
    let t = select(0.0, dot(normal, point - near) / along, abs(along) > 1e-20);
    return near + (far - near) * t;
}

// Barycentric weights of the corners at the point of their plane that `pixel` sees.
fn seed_port_weights(corners: SeedPortCorners, pixel: vec2<f32>) -> vec3<f32> {
    let p0 = corners.a.world_position;
    let edge1 = corners.b.world_position - p0;
    let edge2 = corners.c.world_position - p0;
    let offset = seed_port_plane_point(pixel, p0, cross(edge1, edge2)) - p0;
    // Solve offset = b1 · edge1 + b2 · edge2 in the plane (Cramer's rule on the Gram matrix).
    let d11 = dot(edge1, edge1);
    let d12 = dot(edge1, edge2);
    let d22 = dot(edge2, edge2);
    let o1 = dot(offset, edge1);
    let o2 = dot(offset, edge2);
    let determinant = d11 * d22 - d12 * d12;
    let b1 = (d22 * o1 - d12 * o2) / determinant;
    let b2 = (d11 * o2 - d12 * o1) / determinant;
    return vec3<f32>(1.0 - b1 - b2, b1, b2);
}

// The corners' outputs weighted by `weights`, as the rasterizer interpolates them.
fn seed_port_interpolate(corners: SeedPortCorners, weights: vec3<f32>) -> VertexOut {
    var out = corners.a;
    out.world_position = corners.a.world_position * weights.x + corners.b.world_position * weights.y
        + corners.c.world_position * weights.z;
    out.world_normal = corners.a.world_normal * weights.x + corners.b.world_normal * weights.y
        + corners.c.world_normal * weights.z;
    out.uv = corners.a.uv * weights.x + corners.b.uv * weights.y + corners.c.uv * weights.z;
    out.world_tangent = corners.a.world_tangent * weights.x + corners.b.world_tangent * weights.y
        + corners.c.world_tangent * weights.z;
    return out;
}

fn seed_port_uv(corners: SeedPortCorners, pixel: vec2<f32>) -> vec2<f32> {
    let weights = seed_port_weights(corners, pixel);
    return corners.a.uv * weights.x + corners.b.uv * weights.y + corners.c.uv * weights.z;
}

@compute @workgroup_size(8, 8, 1)
fn cs_seed_port(@builtin(global_invocation_id) id: vec3<u32>) {
    if any(id.xy >= view.target_size.xy) {
        return;
    }
    let corners = seed_port_corners();
    let centre = vec2<f32>(id.xy) + 0.5;
    let in = seed_port_interpolate(corners, seed_port_weights(corners, centre));
    let dx = seed_port_uv(corners, centre + vec2<f32>(1.0, 0.0)) - in.uv;
    let dy = seed_port_uv(corners, centre + vec2<f32>(0.0, 1.0)) - in.uv;
    let pixel = seed_port_listing_1(in, dx, dy);
    textureStore(scene_output, vec2<i32>(id.xy), seed_port_listing_2(pixel, materials[0]));
}

// The analytic plane's uv at world point `point`.
fn analytic_uv(point: vec3<f32>) -> vec2<f32> {
    let p = vec4<f32>(point, 1.0);
    return vec2<f32>(dot(view.uv_from_world[0], p), dot(view.uv_from_world[1], p));
}

// The analytic plane's point that `pixel` sees.
fn analytic_point(pixel: vec2<f32>) -> vec3<f32> {
    return seed_port_plane_point(pixel, view.plane_point.xyz, view.plane_normal.xyz);
}

// The floor of a compute pass of listing 2: the plane is known, so a pixel costs one ray–plane
// intersection (three with the gradients' neighbours) and no vertex to rebuild.
@compute @workgroup_size(8, 8, 1)
fn cs_seed_port_analytic(@builtin(global_invocation_id) id: vec3<u32>) {
    if any(id.xy >= view.target_size.xy) {
        return;
    }
    let centre = vec2<f32>(id.xy) + 0.5;
    var in: VertexOut;
    in.world_position = analytic_point(centre);
    in.world_normal = view.surface_normal.xyz;
    in.world_tangent = view.surface_tangent;
    in.uv = analytic_uv(in.world_position);
    in.color = vec4<f32>(1.0);
    let dx = analytic_uv(analytic_point(centre + vec2<f32>(1.0, 0.0))) - in.uv;
    let dy = analytic_uv(analytic_point(centre + vec2<f32>(0.0, 1.0))) - in.uv;
    let pixel = seed_port_listing_1(in, dx, dy);
    textureStore(scene_output, vec2<i32>(id.xy), seed_port_listing_2(pixel, materials[0]));
}
