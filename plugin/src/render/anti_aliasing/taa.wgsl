// Temporal anti-aliasing (temporal.rs says what and why), one invocation per pixel: the
// jittered HDR scene and the history reprojected through the depth become the new history,
// which post-processing then writes as it is. Each sample is tonemapped first (display-referred
// ones, alpha < 0, are kept as they are), so an edge between the two kinds blends in display
// values whichever kind the pixel's latest sample was. Mirrors `TaaUniform` in taa.rs (the layout test checks them).

struct TaaUniform {
    // Clip space of this (jittered) frame to world space.
    inverse_view_projection: mat4x4<f32>,
    // World to clip space now and a frame ago, both unjittered.
    view_projection: mat4x4<f32>,
    previous_view_projection: mat4x4<f32>,
    camera_position: vec4<f32>,
    view_direction: vec4<f32>,
    previous_camera_position: vec4<f32>,
    previous_view_direction: vec4<f32>,
    // Frames in the history before this one (0: dropped).
    accumulated: u32,
    // The least share of the new frame in a still pixel, and in one moving half a pixel or more.
    still_weight: f32,
    current_weight: f32,
    clip_gamma: f32,
    depth_tolerance: f32,
    // TONEMAP_* code of the camera's operator: the history holds display values.
    tonemapping: u32,
    // 1 where a draw moved since the last frame: `motion_ids` is then this frame's.
    object_motion: u32,
    _padding: u32,
}

// A moving draw's motion (object_motion.rs): this frame's world to last frame's.
struct ObjectMotion {
    previous_from_current: mat4x4<f32>,
}

@group(0) @binding(0) var scene: texture_2d<f32>;
@group(0) @binding(1) var scene_depth: texture_2d<f32>;
@group(0) @binding(2) var history: texture_2d<f32>;
@group(0) @binding(3) var history_sampler: sampler;
// rgb: the anti-aliased scene; a: the frames it holds at that pixel.
@group(0) @binding(4) var resolved: texture_storage_2d<rgba16float, write>;
@group(0) @binding(5) var<uniform> taa: TaaUniform;
// The same bytes, read where they alone choose a branch: Mesa's lavapipe (22.x) compiles a
// shader again each time its bind group is bound when a uniform alone decides a branch, and
// keeps every copy. Everything else reads the uniform, which is faster on GPUs.
@group(0) @binding(8) var<storage, read> taa_branches: TaaUniform;
// The view depth each pixel showed, for the next frame's disocclusion test: last frame's, this one's.
@group(0) @binding(6) var history_depth: texture_2d<f32>;
@group(0) @binding(7) var resolved_depth: texture_storage_2d<r32float, write>;
// Per pixel, the number of the moving draw it shows (0: none), and the motions they number.
@group(1) @binding(0) var motion_ids: texture_2d<u32>;
@group(1) @binding(1) var<storage, read> object_motions: array<ObjectMotion>;

// Largest finite half float: the history's format.
const HALF_MAX: f32 = 65504.0;

// NaN and infinities never enter the history (tested by bit pattern: a compiler may assume
// x == x); other values are kept within what the history can store.
fn finite_colour(colour: vec3<f32>) -> vec3<f32> {
    let exponent = bitcast<vec3<u32>>(colour) & vec3<u32>(0x7f800000u);
    let bad = exponent == vec3<u32>(0x7f800000u);
    return select(clamp(colour, vec3<f32>(0.0), vec3<f32>(HALF_MAX)), vec3<f32>(0.0), bad);
}

fn luma(colour: vec3<f32>) -> f32 {
    return dot(colour, vec3<f32>(0.2126, 0.7152, 0.0722));
}

// Karis's reversible tonemap: the blend and the clip see colours as the display will, so a
// bright sample cannot outweigh its neighbours (no fireflies at jittered highlights).
fn compress(colour: vec3<f32>) -> vec3<f32> {
    return colour / (1.0 + luma(colour));
}

fn expand(colour: vec3<f32>) -> vec3<f32> {
    return colour / max(1.0 - luma(colour), 1e-4);
}

// YCoCg: the variance box is tighter around colours along luma than in RGB.
fn to_ycocg(c: vec3<f32>) -> vec3<f32> {
    return vec3<f32>(0.25 * c.r + 0.5 * c.g + 0.25 * c.b, 0.5 * c.r - 0.5 * c.b, -0.25 * c.r + 0.5 * c.g - 0.25 * c.b);
}

fn from_ycocg(c: vec3<f32>) -> vec3<f32> {
    return vec3<f32>(c.x + c.y - c.z, c.x + c.z, c.x - c.y - c.z);
}

// A scene sample as the display shows it (before the sRGB curve).
fn display_colour(sample: vec4<f32>) -> vec3<f32> {
    let colour = finite_colour(sample.rgb);
    return select(tonemap(colour, taa_branches.tonemapping), colour, is_display_referred(sample.a));
}

// Every history texel was written through `finite_colour`, so a filtered tap of it is finite.
fn history_colour(uv: vec2<f32>) -> vec3<f32> {
    return textureSampleLevel(history, history_sampler, uv, 0.0).rgb;
}

// The history at `uv` through a Catmull-Rom filter in five bilinear taps (Jimenez 2016): sharp
// where bilinear would blur the image a little more each frame. At a pixel's centre it is
// that pixel exactly.
fn sample_history(uv: vec2<f32>, size: vec2<f32>) -> vec3<f32> {
    let position = uv * size;
    let centre = floor(position - 0.5) + 0.5;
    let f = position - centre;
    let w0 = f * (-0.5 + f * (1.0 - 0.5 * f));
    let w1 = 1.0 + f * f * (-2.5 + 1.5 * f);
    let w2 = f * (0.5 + f * (2.0 - 1.5 * f));
    let w3 = f * f * (-0.5 + 0.5 * f);
    let w12 = w1 + w2;
    let texel = 1.0 / size;
    let uv0 = (centre - 1.0) * texel;
    let uv3 = (centre + 2.0) * texel;
    let uv12 = (centre + w2 / w12) * texel;
    let weights = vec4<f32>(w12.x * w0.y, w0.x * w12.y, w12.x * w12.y, w3.x * w12.y) ;
    var sum = history_colour(vec2<f32>(uv12.x, uv0.y)) * weights.x;
    sum += history_colour(vec2<f32>(uv0.x, uv12.y)) * weights.y;
    sum += history_colour(uv12) * weights.z;
    sum += history_colour(vec2<f32>(uv3.x, uv12.y)) * weights.w;
    sum += history_colour(vec2<f32>(uv12.x, uv3.y)) * (w12.x * w3.y);
    let total = weights.x + weights.y + weights.z + weights.w + w12.x * w3.y;
    return max(sum / total, vec3<f32>(0.0));
}

// `colour` moved towards the box's centre until it lies inside (a clip, not a clamp per
// channel: the hue of the history is kept).
fn clip_to_box(colour: vec3<f32>, low: vec3<f32>, high: vec3<f32>) -> vec3<f32> {
    let centre = 0.5 * (low + high);
    let extent = 0.5 * (high - low) + vec3<f32>(1e-6);
    let offset = colour - centre;
    let units = abs(offset / extent);
    let most = max(units.x, max(units.y, units.z));
    return select(colour, centre + offset / most, most > 1.0);
}

// The least share of the new frame in a pixel whose history moved by `motion` pixels: the
// Catmull-Rom read at a fraction f of a pixel blurs by about f(1 - f), so a pixel that moves
// less keeps its history longer; from half a pixel on, `current_weight`.
fn least_weight(motion: vec2<f32>) -> f32 {
    let f = min(abs(motion), vec2<f32>(0.5));
    let blur = f * (1.0 - f);
    return mix(taa.still_weight, taa.current_weight, saturate(4.0 * (blur.x + blur.y)));
}

// The most frames a pixel's history counts (its weight is then its floor's).
const MOST_FRAMES: f32 = 1024.0;

fn project(view_projection: mat4x4<f32>, world: vec3<f32>) -> vec3<f32> {
    let clip = view_projection * vec4<f32>(world, 1.0);
    return clip.xyz / clip.w;
}

// The workgroup's 16×16 pixels and a border of one: each neighbourhood's colour (compressed,
// in YCoCg; xyz) and depth (w), loaded and tonemapped once per workgroup instead of nine times
// per pixel (1.27 loads a pixel; an 8×8 group's border made it 1.56). One vec4 a pixel, so
// each of the nine taps is one workgroup read, which timed faster than a vec3 and an f32 array
// (sandbox/BENCHMARKS.md, "History").
const GROUP: i32 = 16;
const TILE: i32 = GROUP + 2;
var<workgroup> tile: array<vec4<f32>, TILE * TILE>;

@compute @workgroup_size(GROUP, GROUP, 1)
fn taa_main(
    @builtin(global_invocation_id) id: vec3<u32>,
    @builtin(local_invocation_index) local_index: u32,
    @builtin(workgroup_id) group: vec3<u32>,
) {
    let size = textureDimensions(scene);
    let last = vec2<i32>(size) - 1;
    let origin = vec2<i32>(group.xy) * GROUP - 1;
    for (var index = i32(local_index); index < TILE * TILE; index += GROUP * GROUP) {
        let at = clamp(origin + vec2<i32>(index % TILE, index / TILE), vec2<i32>(0), last);
        tile[index] = vec4<f32>(to_ycocg(compress(display_colour(textureLoad(scene, at, 0)))), textureLoad(scene_depth, at, 0).r);
    }
    workgroupBarrier();
    if id.x >= size.x || id.y >= size.y {
        return;
    }
    let pixel = vec2<i32>(id.xy);
    let in_tile = pixel - origin;

    // The neighbourhood: its mean and spread for the clip, and the nearest depth, whose motion
    // the pixel takes (edges follow the surface in front). The pixel's own sample is the
    // current colour as it is: over a cycle of the jitter the history becomes the mean of
    // samples spread evenly over the pixel, a box filter, where a reconstruction filter
    // (Karis 2014) would blur the still image further.
    var moment1 = vec3<f32>(0.0);
    var moment2 = vec3<f32>(0.0);
    var nearest_depth = 1.0;
    var nearest = pixel;
    for (var dy = -1; dy <= 1; dy += 1) {
        for (var dx = -1; dx <= 1; dx += 1) {
            let texel = tile[(in_tile.y + dy) * TILE + in_tile.x + dx];
            let colour = texel.xyz;
            moment1 += colour;
            moment2 += colour * colour;
            if texel.w < nearest_depth {
                nearest_depth = texel.w;
                nearest = clamp(pixel + vec2<i32>(dx, dy), vec2<i32>(0), last);
            }
        }
    }
    let current = tile[in_tile.y * TILE + in_tile.x].xyz;
    let mean = moment1 / 9.0;
    let deviation = sqrt(max(moment2 / 9.0 - mean * mean, vec3<f32>(0.0)));
    let low = mean - taa.clip_gamma * deviation;
    let high = mean + taa.clip_gamma * deviation;

    // Where the nearest surface was a frame ago. The depth buffer holds the jittered frame's
    // depth at pixel centres: back to the world through this frame's jittered inverse, then
    // its draw's motion (where it moved) and both frames' unjittered projections give the
    // pixel's motion (0 for a still camera and draw: the history is read at the pixel's
    // centre and never blurs).
    let centre = vec2<f32>(nearest) + 0.5;
    let ndc = vec2<f32>(centre.x / f32(size.x) * 2.0 - 1.0, 1.0 - centre.y / f32(size.y) * 2.0);
    let world_h = taa.inverse_view_projection * vec4<f32>(ndc, nearest_depth, 1.0);
    let world = world_h.xyz / world_h.w;
    // A moving draw's point was elsewhere a frame ago: its motion takes it there.
    var world_before = world;
    if taa_branches.object_motion != 0u {
        let motion = textureLoad(motion_ids, nearest, 0).r;
        if motion != 0u {
            let moved = object_motions[motion - 1u].previous_from_current * vec4<f32>(world, 1.0);
            world_before = moved.xyz / moved.w;
        }
    }
    let now = project(taa.view_projection, world).xy;
    let before = project(taa.previous_view_projection, world_before).xy;
    let uv = (vec2<f32>(pixel) + 0.5) / vec2<f32>(size) + (before - now) * vec2<f32>(0.5, -0.5);
    let view_depth = dot(world - taa.camera_position.xyz, taa.view_direction.xyz);

    // The frames the history holds where the point was; none where it was dropped: a reset,
    // off screen, or disoccluded.
    var frames = 0.0;
    let on_screen = all(uv >= vec2<f32>(0.0)) && all(uv <= vec2<f32>(1.0));
    if taa_branches.accumulated != 0u && on_screen && world_h.w != 0.0 {
        // The depth the history kept where the point was: nearer than the point would have
        // been, something hid it then (disocclusion), and the history is another surface's.
        let kept_at = clamp(vec2<i32>(uv * vec2<f32>(size)), vec2<i32>(0), last);
        let kept = textureLoad(history_depth, kept_at, 0).r;
        let expected = dot(world_before - taa.previous_camera_position.xyz, taa.previous_view_direction.xyz);
        if kept >= expected - (taa.depth_tolerance + 1e-5) * abs(expected) {
            frames = textureLoad(history, kept_at, 0).a;
        }
    }
    // A plain mean while the history is short, then at least the floor of the pixel's motion.
    let pixel_motion = uv * vec2<f32>(size) - (vec2<f32>(pixel) + 0.5);
    let weight = max(1.0 / (frames + 1.0), least_weight(pixel_motion));
    var blended = current;
    if weight < 1.0 {
        let remembered = clip_to_box(to_ycocg(compress(sample_history(uv, vec2<f32>(size)))), low, high);
        blended = mix(remembered, current, weight);
    }
    let colour = finite_colour(expand(max(from_ycocg(blended), vec3<f32>(0.0))));
    textureStore(resolved, pixel, vec4<f32>(colour, min(frames + 1.0, MOST_FRAMES)));
    textureStore(resolved_depth, pixel, vec4<f32>(view_depth, 0.0, 0.0, 0.0));
}
