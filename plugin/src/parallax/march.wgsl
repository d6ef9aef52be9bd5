// Ray / height-field intersection for every parallax method (Tatarchuk 2006 §5.4).
//
// Pure functions: no bindings and no derivative built-ins, so a fragment and a compute entry point
// can share them. Textures, gradients and parameters come in as arguments. The CPU reference in
// reference.rs mirrors this file step by step; change both together.
//
// Heights are in Tatarchuk's convention after `sample_height`: 1 = the polygon's surface (top),
// 0 = the deepest point. A ray is described by its height: the view ray enters at 1 and descends.
//
// The METHOD_* and SHADOWS_* codes are generated from `ParallaxMethod` and `ShadowMode` and
// prepended (see parallax/mod.rs).

// Longest sideways travel of a ray per unit of depth: |V.xy| / V.z is capped here, which is
// reached about 87° from the normal. It keeps grazing rays (V.z → 0, or < 0 on silhouettes of
// smooth meshes) finite and stops a sliver of pixels from marching across the whole texture.
const MAX_PARALLAX_RATIO: f32 = 20.0;

// Hard shadow rays start this far (in height units) above the visible point: the height there
// comes from an 8-bit, bilinearly filtered texture, and without the bias the first steps would
// find the surface's own rounding above the ray and speckle lit slopes with shadow.
const HARD_SHADOW_BIAS: f32 = 0.01;

// Tatarchuk's fShadowSoftening default. His listing multiplies by it (larger = harder); the
// material's shadow_softening divides instead, scaled so that 0.58 gives his result.
const SEED_SHADOW_SOFTENING: f32 = 0.58;

// Set on a layered material's pipelines: every height is the blend of its layers' (`LayerBlend`).
override LAYERED: bool = false;
// Set on a triplanar material's pipelines: every height is the mix of the three axis
// projections' (`TriplanarProjection`; triplanar.wgsl builds it and shades with it).
override TRIPLANAR: bool = false;

struct HeightField {
    // Texture channel holding the height: 0 = red, 3 = alpha.
    channel: u32,
    // 1 when white means deepest (depth maps).
    depth_convention: u32,
    // The mip level every height sample of the march reads (`sampler_level` of the pixel's
    // footprint), taken once outside every loop: nothing in a march uses implicit derivatives
    // (T samples with tex2Dgrad, Luna with SampleGrad, for the same reason). An explicit level
    // rather than the gradients themselves: the same filtering, and on the GPUs we measure a
    // sample at a given level costs less than one the sampler must find the level of
    // (sandbox/BENCHMARKS.md, "History": the explicit sample level).
    level: f32,
    // 1 where the surface ends at `bounds` (min u, min v, max u, max v; the material's
    // uv_bounds silhouette): a sample outside reads as the deepest height, so no ray meets the
    // relief there, and a view ray that gets there has left the surface. The CPU reference
    // samples fields unbounded, as 0 does here.
    bounded: u32,
    bounds: vec4<f32>,
    // The fraction of one step (0..1) by which every linear search starts early: per pixel and
    // frame noise with the material's jitter_march, which TAA averages into the image of many
    // more steps; 0 samples where Tatarchuk does (the CPU reference's march).
    march_jitter: f32,
}

fn inside_bounds(field: HeightField, uv: vec2<f32>) -> bool {
    return all(uv >= field.bounds.xy) && all(uv <= field.bounds.zw);
}

// The level a trilinear sampler without anisotropy picks for a pixel whose texture coordinate
// moves by `ddx_texels` across and `ddy_texels` down (in texels): log2 of the longer of the two
// (the scale factor of the Vulkan and WebGPU specifications), never below level 0.
fn sampler_level(ddx_texels: vec2<f32>, ddy_texels: vec2<f32>) -> f32 {
    let longest_squared = max(dot(ddx_texels, ddx_texels), dot(ddy_texels, ddy_texels));
    return max(0.5 * log2(longest_squared), 0.0);
}

fn sample_height(height_texture: texture_2d<f32>, weight_texture: texture_2d<f32>, height_sampler: sampler,
    field: HeightField, mapping: FieldMapping, uv: vec2<f32>) -> f32 {
    let height = field_height(height_texture, weight_texture, height_sampler, field, mapping, uv, field.level);
    return select(height, 0.0, field.bounded != 0u && !inside_bounds(field, uv));
}

// The height at `uv` (the march's coordinate) read at mip `level` of the first (or only)
// layer's heights: one layer's, the blend of a layered material's, or the mix of the
// triplanar projections'.
fn field_height(height_texture: texture_2d<f32>, weight_texture: texture_2d<f32>, height_sampler: sampler,
    field: HeightField, mapping: FieldMapping, uv: vec2<f32>, level: f32) -> f32 {
    if LAYERED {
        let blend = mapping.layers;
        let heights = layer_heights(height_texture, height_sampler, blend, uv, level);
        return dot(layer_shares(heights, layer_weights(weight_texture, height_sampler, blend, uv), blend.sharpness), heights);
    }
    if TRIPLANAR {
        return triplanar_height(height_texture, height_sampler, field, mapping.triplanar, uv, level);
    }
    let texel = textureSampleLevel(height_texture, height_sampler, uv, level);
    return height_in_channel(texel, field.channel, field.depth_convention);
}

// A layered material's layers (parallax/layers.rs): their heights packed one a channel, each
// tiled its own way and reaching its own share of the relief's depth, mixed by weights with
// height-based blending. `reference::layer_shares` is the CPU reference of `layer_shares`.
struct LayerBlend {
    // Each layer's repeats across the texture coordinates 0..1.
    tiling: vec4<f32>,
    // Each layer's mip level over the first layer's (log2 of its tiling over the first's).
    level_offset: vec4<f32>,
    // Each layer's depth as a share of the height scale.
    depth: vec4<f32>,
    // 1 for each layer the material has, 0 past the last.
    present: vec4<f32>,
    // The weights where the view ray entered (the vertex colours), read when there is no
    // weight map.
    entry_weights: vec4<f32>,
    // contrast / (1 − contrast): how fast a layer standing lower loses its share.
    sharpness: f32,
    weights_from_texture: u32,
    // The weight map's mip level for the pixel's footprint.
    weight_level: f32,
    // Half a texel of the weight map: its coordinates stay this far inside 0..1, so the edges
    // of a terrain do not mix in the weights of the opposite edge.
    weight_inset: vec2<f32>,
    // 1 when every layer tiles as the first: one fetch reads every height.
    shared_tiling: u32,
}

// How the march's coordinate reads the height field beyond one texture: a layered material's
// blend, or the triplanar projections (each unused by other materials).
struct FieldMapping {
    layers: LayerBlend,
    triplanar: TriplanarProjection,
}

// Triplanar mapping as the march reads it: the march moves in the tangent plane where the view
// ray enters, its coordinate (a, b) the point origin + tangent · a + bitangent · b in texture
// units (world units / triplanar_scale), whose height the three axis projections give, mixed by
// the weights of the entry point's normal (fixed along the ray: one field for the ray, its
// shadow rays and relief occlusion).
struct TriplanarProjection {
    // Where the view ray entered, in texture units, moved by whole repeats into 0..1 (the
    // projections repeat, and small numbers keep the march's coordinates exact far from the
    // world's origin).
    origin: vec3<f32>,
    // The tangent plane's axes, in world directions (unit): the march's coordinate axes.
    tangent: vec3<f32>,
    bitangent: vec3<f32>,
    // The projections' shares along X, Y and Z (`triplanar_weights`).
    weights: vec3<f32>,
    // The sign of the normal along each axis: which way each projection faces.
    sides: vec3<f32>,
}

// The texture coordinate of `q` (texture units; a point, or a change of one) in the projection
// along `axis` (0 = X, 1 = Y, 2 = Z): seen from outside along its axis, u runs to the right and
// v down the image (`reference::triplanar_uvs`).
fn projection_uv(q: vec3<f32>, sides: vec3<f32>, axis: u32) -> vec2<f32> {
    if axis == 0u {
        return vec2<f32>(-q.z * sides.x, -q.y);
    }
    if axis == 1u {
        return vec2<f32>(q.x, q.z * sides.y);
    }
    return vec2<f32>(q.x * sides.z, -q.y);
}

// The point (texture units) of the march's coordinate `planar`.
fn projected_point(projection: TriplanarProjection, planar: vec2<f32>) -> vec3<f32> {
    return projection.origin + projection.tangent * planar.x + projection.bitangent * planar.y;
}

// The height at the march's coordinate `planar`, read at mip `level`: the projections' heights
// mixed (one fetch for each projection with a share).
fn triplanar_height(height_texture: texture_2d<f32>, height_sampler: sampler, field: HeightField,
    projection: TriplanarProjection, planar: vec2<f32>, level: f32) -> f32 {
    let q = projected_point(projection, planar);
    var height = 0.0;
    for (var axis = 0u; axis < 3u; axis += 1u) {
        if projection.weights[axis] > 0.0 {
            let texel = textureSampleLevel(height_texture, height_sampler, projection_uv(q, projection.sides, axis), level);
            height += projection.weights[axis] * height_in_channel(texel, field.channel, field.depth_convention);
        }
    }
    return height;
}

// Each layer's height at `uv` (1 the top), the heights fetched once where the layers tile alike.
fn layer_heights(heights: texture_2d<f32>, height_sampler: sampler, blend: LayerBlend, uv: vec2<f32>, level: f32) -> vec4<f32> {
    var packed = textureSampleLevel(heights, height_sampler, uv * blend.tiling.x, level);
    if blend.shared_tiling == 0u {
        packed.y = textureSampleLevel(heights, height_sampler, uv * blend.tiling.y, level + blend.level_offset.y).y;
        packed.z = textureSampleLevel(heights, height_sampler, uv * blend.tiling.z, level + blend.level_offset.z).z;
        packed.w = textureSampleLevel(heights, height_sampler, uv * blend.tiling.w, level + blend.level_offset.w).w;
    }
    return 1.0 - (1.0 - packed) * blend.depth;
}

// Each layer's weight at `uv` (0 past the last layer).
fn layer_weights(weight_texture: texture_2d<f32>, weight_sampler: sampler, blend: LayerBlend, uv: vec2<f32>) -> vec4<f32> {
    var weights = blend.entry_weights;
    if blend.weights_from_texture != 0u {
        let inside = clamp(uv, blend.weight_inset, vec2<f32>(1.0) - blend.weight_inset);
        weights = textureSampleLevel(weight_texture, weight_sampler, inside, blend.weight_level);
    }
    return max(weights, vec4<f32>(0.0)) * blend.present;
}

// Each layer's share of the mix: it scores its height plus its weight, and one d below the best
// score keeps weight × max(1 − sharpness · d, 0). No weight at all: the first layer.
fn layer_shares(heights: vec4<f32>, weights: vec4<f32>, sharpness: f32) -> vec4<f32> {
    if dot(weights, vec4<f32>(1.0)) <= 0.0 {
        return vec4<f32>(1.0, 0.0, 0.0, 0.0);
    }
    let scores = heights + weights;
    let shown = select(vec4<f32>(-3.0e38), scores, weights > vec4<f32>(0.0));
    let best = max(max(shown.x, shown.y), max(shown.z, shown.w));
    let shares = weights * max(vec4<f32>(1.0) - sharpness * (vec4<f32>(best) - scores), vec4<f32>(0.0));
    return shares / dot(shares, vec4<f32>(1.0));
}

// How far, in texture coordinates, a ray along `direction_ts` (tangent space, pointing away from
// the surface) travels sideways while rising by the full height range `height_scale`.
// The view ray descends, so its parallax offset vector P (T's vParallaxOffsetTS) is the negation
// of this for the direction towards the eye.
fn ray_offset(direction_ts: vec3<f32>, height_scale: f32) -> vec2<f32> {
    let sideways = length(direction_ts.xy);
    if sideways < 1e-7 {
        return vec2<f32>(0.0);
    }
    let ratio = min(sideways / max(direction_ts.z, 1e-7), MAX_PARALLAX_RATIO);
    return direction_ts.xy / sideways * (ratio * height_scale);
}

// T eq. 1: n = lerp(n_max, n_min, N·V), more samples at grazing angles; but never more steps than
// texels the ray crosses at the sampled mip level, where more steps add cost and no accuracy.
fn march_steps(min_samples: u32, max_samples: u32, n_dot_v: f32, texels_crossed: f32) -> u32 {
    let wanted = floor(mix(f32(max_samples), f32(min_samples), clamp(n_dot_v, 0.0, 1.0)));
    let needed = ceil(max(texels_crossed, 0.0));
    return u32(clamp(min(wanted, needed), 1.0, f32(max(max_samples, 1u))));
}

// T Listing 2: the mip level from the screen-space derivatives of uv × texture size.
fn mip_level(ddx_texels: vec2<f32>, ddy_texels: vec2<f32>) -> f32 {
    let delta = ddx_texels * ddx_texels + ddy_texels * ddy_texels;
    return max(0.5 * log2(max(delta.x, delta.y)), 0.0);
}

// 0 = full march (mip at or below threshold − band), 1 = normal mapping only (mip past the
// threshold), the fraction through the band in between. With band 1 this is T's fractional mip.
fn lod_fade(mip: f32, threshold: f32, band: f32) -> f32 {
    return clamp((mip - (threshold - band)) / max(band, 1e-4), 0.0, 1.0);
}

// Two consecutive samples of a linear search: `above` has the ray over the surface, `below` has
// the surface at or over the ray (when `found`).
struct Crossing {
    above_uv: vec2<f32>,
    above_ray: f32,
    above_surface: f32,
    below_uv: vec2<f32>,
    below_ray: f32,
    below_surface: f32,
    found: bool,
    samples: u32,
}

// Linear search with early exit (T §5.4.1): from `start_uv` at ray height `start_ray` (surface
// height `start_surface` there), take `steps` equal steps spanning `uv_span` and `ray_span`, and
// stop at the first sample where the surface reaches the ray. `bend` bends the ray by the
// surface's curvature: at the fraction t of the span its height is start_ray + ray_span · t +
// bend · t² (0: straight, as the CPU reference marches every ray).
fn linear_search(
    height_texture: texture_2d<f32>,
    weight_texture: texture_2d<f32>,
    height_sampler: sampler,
    field: HeightField,
    mapping: FieldMapping,
    start_uv: vec2<f32>,
    start_ray: f32,
    start_surface: f32,
    uv_span: vec2<f32>,
    ray_span: f32,
    bend: f32,
    steps: u32,
) -> Crossing {
    var crossing = Crossing(start_uv, start_ray, start_surface, start_uv, start_ray, start_surface, false, 0u);
    let step = 1.0 / f32(steps);
    for (var i = 1u; i <= steps; i += 1u) {
        // From the start each time, not accumulated, and the last step exactly on the end.
        let t = select((f32(i) - field.march_jitter) * step, 1.0, i == steps);
        let uv = start_uv + uv_span * t;
        let ray = start_ray + ray_span * t + bend * t * t;
        let surface = sample_height(height_texture, weight_texture, height_sampler, field, mapping, uv);
        crossing.samples += 1u;
        if surface >= ray {
            crossing.below_uv = uv;
            crossing.below_ray = ray;
            crossing.below_surface = surface;
            crossing.found = true;
            break;
        }
        crossing.above_uv = uv;
        crossing.above_ray = ray;
        crossing.above_surface = surface;
    }
    return crossing;
}

struct RayHit {
    // Texture coordinate of the visible point.
    uv: vec2<f32>,
    // Height of that point (1 = surface, 0 = deepest).
    height: f32,
    // Height samples taken.
    samples: u32,
    // False where a bent ray rose out of the relief's shell without meeting it: it left the
    // surface (the CPU reference's rays are straight and always meet it).
    met: bool,
}

// T / Luna §4: the ray meets the straight line through the two bracketing samples.
fn secant_refinement(crossing: Crossing) -> RayHit {
    let above_gap = crossing.above_ray - crossing.above_surface;
    let below_gap = crossing.below_ray - crossing.below_surface;
    let denominator = above_gap - below_gap;
    let t = select(1.0, clamp(above_gap / denominator, 0.0, 1.0), denominator > 1e-7);
    return RayHit(
        mix(crossing.above_uv, crossing.below_uv, t),
        mix(crossing.above_ray, crossing.below_ray, t),
        crossing.samples,
        true,
    );
}

// `bracket` with the sample at `uv` (ray height `ray`, surface height `surface`) as its new
// end on the side the sample falls: the crossing stays between its two ends. Counts the sample.
fn narrowed(bracket: Crossing, uv: vec2<f32>, ray: f32, surface: f32) -> Crossing {
    var narrower = bracket;
    narrower.samples += 1u;
    if surface >= ray {
        narrower.below_uv = uv;
        narrower.below_ray = ray;
        narrower.below_surface = surface;
    } else {
        narrower.above_uv = uv;
        narrower.above_ray = ray;
        narrower.above_surface = surface;
    }
    return narrower;
}

// Parallax occlusion mapping's refinement: the secant `steps` times, each time sampling the
// height where the last secant met the ray and keeping the bracket that holds the crossing
// (false position). One step is T's; on a curved slope the first secant lands off the surface
// by the curvature across the bracket, and each step shrinks that error.
fn secant_steps_refinement(
    height_texture: texture_2d<f32>,
    weight_texture: texture_2d<f32>,
    height_sampler: sampler,
    field: HeightField,
    mapping: FieldMapping,
    crossing: Crossing,
    steps: u32,
) -> RayHit {
    var bracket = crossing;
    for (var i = 1u; i < steps; i += 1u) {
        let hit = secant_refinement(bracket);
        bracket = narrowed(bracket, hit.uv, hit.height, sample_height(height_texture, weight_texture, height_sampler, field, mapping, hit.uv));
    }
    return secant_refinement(bracket);
}

// Relief mapping (Policarpo et al.): halve the bracket `steps` times, keeping the crossing inside.
fn binary_refinement(
    height_texture: texture_2d<f32>,
    weight_texture: texture_2d<f32>,
    height_sampler: sampler,
    field: HeightField,
    mapping: FieldMapping,
    crossing: Crossing,
    steps: u32,
) -> RayHit {
    var bracket = crossing;
    for (var i = 0u; i < steps; i += 1u) {
        let middle_uv = (bracket.above_uv + bracket.below_uv) * 0.5;
        let middle_ray = (bracket.above_ray + bracket.below_ray) * 0.5;
        bracket = narrowed(bracket, middle_uv, middle_ray, sample_height(height_texture, weight_texture, height_sampler, field, mapping, middle_uv));
    }
    return RayHit((bracket.above_uv + bracket.below_uv) * 0.5, (bracket.above_ray + bracket.below_ray) * 0.5,
        bracket.samples, true);
}

// The fraction of a view ray's straight path (the one that reaches the deepest height at 1) its
// march spans when `bend` bends it (height 1 − t + bend · t²): to where it reaches the deepest
// height, or, bent up by more than ¼, to where it rises back out of the shell's top.
fn bent_span(bend: f32) -> f32 {
    if bend == 0.0 {
        return 1.0;
    }
    if bend > 0.25 {
        return 1.0 / bend;
    }
    // The smaller root of 1 − t + bend · t², in the form that stays exact as bend → 0.
    return 2.0 / (1.0 + sqrt(1.0 - 4.0 * bend));
}

// The visible point for the view ray entering at `uv` with parallax offset vector `offset` (P),
// by `method`, the ray bent by `bend` (`linear_search`; 0: straight), refined by
// `refinement_steps` (relief's bisections, or occlusion's secant steps). `to_eye_ts` is only used
// by parallax offset mapping, `pyramid` (the height's maximum pyramid, max_mip.wgsl) only by
// MaxMip, which walks straight rays: a bent one takes the linear search instead.
fn march_view(
    height_texture: texture_2d<f32>,
    weight_texture: texture_2d<f32>,
    height_sampler: sampler,
    pyramid: texture_2d<f32>,
    field: HeightField,
    mapping: FieldMapping,
    method: u32,
    uv: vec2<f32>,
    offset: vec2<f32>,
    to_eye_ts: vec3<f32>,
    height_scale: f32,
    steps: u32,
    refinement_steps: u32,
    bend: f32,
) -> RayHit {
    if method == METHOD_NORMAL_MAPPING {
        return RayHit(uv, 1.0, 0u, true);
    }
    if method == METHOD_MAX_MIP && bend == 0.0 {
        return march_max_mip(height_texture, height_sampler, pyramid, field, uv, offset);
    }
    let surface = sample_height(height_texture, weight_texture, height_sampler, field, mapping, uv);
    if method == METHOD_PARALLAX_OFFSET {
        // Welsh's offset limiting: shift by the depth along V.xy without dividing by V.z.
        return RayHit(uv - (1.0 - surface) * height_scale * to_eye_ts.xy, surface, 1u, true);
    }
    if surface >= 1.0 {
        return RayHit(uv, 1.0, 1u, true);
    }
    let span = bent_span(bend);
    var crossing = linear_search(height_texture, weight_texture, height_sampler, field, mapping, uv, 1.0, surface, offset * span, -span,
        bend * span * span, steps);
    crossing.samples += 1u;
    if !crossing.found {
        // A straight ray always ends on the deepest height; a bent one ends there only to a
        // rounding (the last sample is kept), or rose out of the shell.
        return RayHit(crossing.above_uv, crossing.above_ray, crossing.samples, bend <= 0.25);
    }
    if method == METHOD_STEEP {
        return RayHit(crossing.below_uv, crossing.below_ray, crossing.samples, true);
    }
    if method == METHOD_RELIEF {
        return binary_refinement(height_texture, weight_texture, height_sampler, field, mapping, crossing, refinement_steps);
    }
    return secant_steps_refinement(height_texture, weight_texture, height_sampler, field, mapping, crossing, refinement_steps);
}

// Hard self-shadow (McGuire): march from the visible point towards the light; 0 if any sample
// of the height field rises above the light ray, else 1. `light_offset` is ray_offset(L_ts, H);
// `texels_per_rise` the texels a ray rising the whole height range crosses. The ray only rises
// from the visible point to the top, so it takes T eq. 1's count for N·L capped by the texels
// that shorter ray crosses: a point near the top needs few steps. `bend` bends the light ray
// by the surface's curvature as `linear_search` does, over the whole rise (0: straight). MaxMip
// walks its `pyramid` instead, exactly and straight (max_mip.wgsl).
fn hard_shadow(
    height_texture: texture_2d<f32>,
    weight_texture: texture_2d<f32>,
    height_sampler: sampler,
    pyramid: texture_2d<f32>,
    field: HeightField,
    mapping: FieldMapping,
    method: u32,
    uv: vec2<f32>,
    light_offset: vec2<f32>,
    min_samples: u32,
    max_samples: u32,
    n_dot_l: f32,
    texels_per_rise: f32,
    bend: f32,
) -> f32 {
    if method == METHOD_MAX_MIP {
        return max_mip_hard_shadow(height_texture, height_sampler, pyramid, field, uv, light_offset);
    }
    let start = sample_height(height_texture, weight_texture, height_sampler, field, mapping, uv) + HARD_SHADOW_BIAS;
    let rise = 1.0 - start;
    if rise <= 0.0 {
        return 1.0;
    }
    let steps = march_steps(min_samples, max_samples, n_dot_l, texels_per_rise * rise);
    let crossing = linear_search(height_texture, weight_texture, height_sampler, field, mapping, uv, start, start, light_offset * rise, rise,
        bend * rise * rise, steps);
    return select(1.0, 0.0, crossing.found);
}

// Tatarchuk's soft self-shadow (§5.4.2, Listing 2): seven height samples along the light ray at
// 0.22 … 0.88 of the height range above the visible point. Each sample's height over the ray is
// weighted more the nearer it is (near blockers cast sharp penumbrae), the strongest one wins.
// `bend` raises the ray by bend · fraction² where the surface curves away (0: straight).
// `tap_shift` (−0.5..0.5) moves every sample that part of their spacing along the ray, its weight
// following its place: per pixel and frame noise under TAA, whose history then holds the
// penumbra of many samples rather than seven steps; 0 samples where Tatarchuk does.
fn soft_shadow(
    height_texture: texture_2d<f32>,
    weight_texture: texture_2d<f32>,
    height_sampler: sampler,
    field: HeightField,
    mapping: FieldMapping,
    uv: vec2<f32>,
    light_offset: vec2<f32>,
    softening: f32,
    bend: f32,
    tap_shift: f32,
) -> f32 {
    let start = sample_height(height_texture, weight_texture, height_sampler, field, mapping, uv);
    var strongest = 0.0;
    for (var k = 0u; k < 7u; k += 1u) {
        // Fractions 0.88, 0.77, …, 0.22 with weights 1, 2, 4, 6, 8, 10, 12, as in the listing.
        let place = f32(k) + tap_shift;
        let fraction = 0.88 - 0.11 * place;
        let weight = max(1.0, 2.0 * place);
        let blocker = sample_height(height_texture, weight_texture, height_sampler, field, mapping, uv + light_offset * fraction);
        strongest = max(strongest, (blocker - start - fraction - bend * fraction * fraction) * weight);
    }
    let sharpness = SEED_SHADOW_SOFTENING * SEED_SHADOW_SOFTENING / max(softening, 1e-4);
    return clamp(1.0 - strongest * sharpness, 0.0, 1.0);
}

// Directions and steps of the relief's horizon search.
const OCCLUSION_DIRECTIONS: u32 = 4u;
const OCCLUSION_STEPS: u32 = 4u;

// How much of the sky the relief leaves open above the point at `uv` of height `height`: in
// each of four directions (turned by `turn`, a fraction of their spacing) the steepest rise of
// the field within `radius` (texture units) is the horizon's slope s, under which a cosine-
// weighted half of the hemisphere sees 1 / (1 + s²) (cos² of the horizon's elevation, GTAO's
// slice integral for a normal along the polygon's). `height_scale` turns heights into texture
// units; each step reads the mip whose texels are about as wide as the step, so a wide search
// costs as little as a narrow one. 1: open sky, 0: buried.
fn relief_occlusion(
    height_texture: texture_2d<f32>,
    weight_texture: texture_2d<f32>,
    height_sampler: sampler,
    field: HeightField,
    mapping: FieldMapping,
    uv: vec2<f32>,
    height: f32,
    height_scale: f32,
    radius: f32,
    texels: f32,
    turn: f32,
) -> f32 {
    var open = 0.0;
    for (var d = 0u; d < OCCLUSION_DIRECTIONS; d += 1u) {
        let angle = (f32(d) + turn) * (2.0 * 3.14159265 / f32(OCCLUSION_DIRECTIONS));
        let direction = vec2<f32>(cos(angle), sin(angle));
        var steepest = 0.0;
        for (var s = 1u; s <= OCCLUSION_STEPS; s += 1u) {
            let fraction = f32(s) / f32(OCCLUSION_STEPS);
            let distance = radius * fraction * fraction;
            let level = max(field.level, log2(max(distance * texels, 1.0)) - 1.0);
            let sample = field_height(height_texture, weight_texture, height_sampler, field, mapping, uv + direction * distance, level);
            let rise = (sample - height) * height_scale;
            steepest = max(steepest, rise / distance);
        }
        open += 1.0 / (1.0 + steepest * steepest);
    }
    return open / f32(OCCLUSION_DIRECTIONS);
}
