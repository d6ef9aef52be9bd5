// The lights that reach a point (render/lights/): its light cluster's, found the way the lights
// feature culled them (clusters.rs), and the brightest few of them. Composed after frame.wgsl.

// The most lights `brightest_lights_floor` ranks.
const MAX_RANKED_LIGHTS: u32 = 8u;
// Words before the clusters (LIGHT_CLUSTER_HEADER in extract.rs): the grid (0..2) and how many
// entries the lists hold (3), the depth slicing (4..7: scale, bias, 1 for a logarithmic
// slicing, the nearest depth), the camera's view-projection (8..23, by columns), position
// (24..26) and forward direction (28..30), as bits. Read from storage, not the frame uniform: a condition on uniform values alone makes
// some drivers (Mesa 22's lavapipe) keep a new copy of the shader at every bind.
const LIGHT_CLUSTER_HEADER: u32 = 32u;

// The header, then per cluster (x fastest, then y, then z) its first entry and count, then the
// lists, which hold indices into point_lights in ascending order.
@group(0) @binding(15) var<storage, read> light_clusters: array<u32>;

fn cluster_word(index: u32) -> f32 {
    return bitcast<f32>(light_clusters[index]);
}

fn cluster_vector(first: u32) -> vec4<f32> {
    return vec4<f32>(cluster_word(first), cluster_word(first + 1u), cluster_word(first + 2u),
        cluster_word(first + 3u));
}

// The lights that may reach a point: every directional light, then the point lights of its
// cluster; `light_in(list, k)` for k < count is each one's number as `light_at` takes it.
struct LightList {
    // Where the cluster's point lights start in light_clusters.
    first: u32,
    count: u32,
    directional_count: u32,
}

// The cluster of `world_position`: the image tile it projects to and its view depth's slice
// (the grid's last slice holds everything farther).
fn light_cluster(world_position: vec3<f32>) -> u32 {
    let grid = max(vec3<u32>(light_clusters[0], light_clusters[1], light_clusters[2]), vec3<u32>(1u));
    let slicing = cluster_vector(4u);
    let view_projection = mat4x4<f32>(cluster_vector(8u), cluster_vector(12u), cluster_vector(16u),
        cluster_vector(20u));
    let clip = view_projection * vec4<f32>(world_position, 1.0);
    let ndc = clip.xy / select(clip.w, 1e-6, abs(clip.w) < 1e-6);
    let tile = vec2<u32>(clamp(floor((ndc * 0.5 + 0.5) * vec2<f32>(grid.xy)), vec2<f32>(0.0),
        vec2<f32>(grid.xy - 1u)));
    let depth = max(dot(world_position - cluster_vector(24u).xyz, cluster_vector(28u).xyz), slicing.w);
    let along = mix(depth, log2(max(depth, 1e-30)), slicing.z);
    let slice = u32(clamp(floor(along * slicing.x + slicing.y), 0.0, f32(grid.z - 1u)));
    return (slice * grid.y + tile.y) * grid.x + tile.x;
}

fn lights_near(world_position: vec3<f32>) -> LightList {
    let directional_count = min(frame.light_counts.x, MAX_DIRECTIONAL_LIGHTS);
    // No point light reaches any cluster: none to find (a frame's lights often are the sun).
    if light_clusters[3] == 0u {
        return LightList(0u, directional_count, directional_count);
    }
    let at = LIGHT_CLUSTER_HEADER + 2u * light_cluster(world_position);
    return LightList(light_clusters[at], directional_count + light_clusters[at + 1u], directional_count);
}

fn light_in(list: LightList, k: u32) -> u32 {
    let point = light_clusters[select(0u, list.first + k - list.directional_count, k >= list.directional_count)];
    return select(k, list.directional_count + point, k >= list.directional_count);
}

// How bright a light's arriving radiance is, for ranking lights (Rec. 709 luminance).
fn light_brightness(radiance: vec3<f32>) -> f32 {
    return dot(radiance, vec3<f32>(0.2126, 0.7152, 0.0722));
}

// The brightness (`light_brightness`) of the `n`-th brightest of `lights` at `world_position`
// (n ≤ MAX_RANKED_LIGHTS): the lights at least this bright are the `n` that matter most
// there. 0 when the list has no more than `n` lights (every one is among them); above every
// light when n is 0.
fn brightest_lights_floor(lights: LightList, world_position: vec3<f32>, n: u32) -> f32 {
    let ranked = min(n, MAX_RANKED_LIGHTS);
    if lights.count <= ranked {
        return 0.0;
    }
    if ranked == 0u {
        return 3.0e38;
    }
    // The eight brightest so far, in descending order (first.x the brightest), in registers:
    // each light passes down the eight slots, leaving the larger value in each.
    var first = vec4<f32>(0.0);
    var second = vec4<f32>(0.0);
    for (var k = 0u; k < lights.count; k += 1u) {
        let value = light_brightness(light_at(light_in(lights, k), world_position).radiance);
        let carried = min(first.w, value);
        first = keep_brightest(first, value);
        second = keep_brightest(second, carried);
    }
    let floors = select(second, first, ranked <= 4u);
    return floors[(ranked - 1u) % 4u];
}

// `slots` (descending) with `value` passed down them: each keeps the larger of itself and what
// reaches it, and hands the smaller on.
fn keep_brightest(slots: vec4<f32>, value: f32) -> vec4<f32> {
    let after_x = min(slots.x, value);
    let after_y = min(slots.y, after_x);
    let after_z = min(slots.z, after_y);
    return vec4<f32>(max(slots.x, value), max(slots.y, after_x), max(slots.z, after_y), max(slots.w, after_z));
}
