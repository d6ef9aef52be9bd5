// The MaxMip method: the exact ray / height-field intersection by hierarchical traversal of a
// pyramid of maximum heights (Tevs, Ihrke and Seidel, I3D 2008). The CPU reference
// (reference/max_mip.rs) mirrors this file step by step; change both together.
//
// The surface is the bilinear field at level 0, repeating (whatever the sampler's address mode:
// the pyramid wraps). Between four neighbouring texel centres it is one bilinear patch, never
// higher than its highest corner: pyramid level 0 holds that maximum per *cell* (cell (i, j)
// spans texel centres i..i+1, j..j+1), each level above the maximum of 2 × 2 cells, in
// Tatarchuk's convention (1 = top) whatever the channel and convention (the core builds it:
// parallax/max_pyramid.wgsl). Positions are in level-0 cells.

// Most traversal steps (skip, climb or descend) one ray takes: a bound on the GPU's time per
// pixel. A ray that runs out stops where it is known to be free (the reference's tests count how
// often: never on 2,000-texel grazing rays over 1024² maps).
const MAX_MIP_STEPS: u32 = 2048u;

// `cell` wrapped into [0, size). Rays start in the first repetition, so most cells are within
// one repetition of it: a shift by one size does; the integer remainder (slow on GPUs, and
// measurably so when every gather paid it) only for the rest.
fn wrapped_cell(cell: vec2<i32>, size: vec2<i32>) -> vec2<i32> {
    let shifted = select(select(cell, cell - size, cell >= size), cell + size, cell < vec2<i32>(0));
    if all(shifted >= vec2<i32>(0)) && all(shifted < size) {
        return shifted;
    }
    let remainder = cell % size;
    return select(remainder, remainder + size, remainder < vec2<i32>(0));
}

// The pyramid's maximum for `cell` of `level`, wrapping (every level repeats with the map).
fn pyramid_maximum(pyramid: texture_2d<f32>, level: u32, cell: vec2<i32>) -> f32 {
    // Levels halve exactly. (Not textureDimensions(pyramid, level): lavapipe answers a size
    // query with a level that differs between invocations with one invocation's level.)
    let size = vec2<i32>(textureDimensions(pyramid) >> vec2<u32>(level));
    return textureLoad(pyramid, wrapped_cell(cell, size), level).r;
}

// The height of texel `texel` (inside the texture) at level 0.
fn texel_height(height_texture: texture_2d<f32>, field: HeightField, texel: vec2<i32>) -> f32 {
    return height_in_channel(textureLoad(height_texture, texel, 0), field.channel, field.depth_convention);
}

// The four corner heights of the patch of level-0 cell `cell`, as (h00, h10, h01, h11), wrapping
// whatever the sampler's address mode. One gather (the texel fetch of a patch), except on the
// map's last column or row: that patch spans the seam, where a gather follows the sampler, which
// may clamp or mirror (a glTF sampler can), so four loads of the wrapped texels (one fetch still).
fn patch_corners(height_texture: texture_2d<f32>, height_sampler: sampler, field: HeightField, cell: vec2<i32>) -> vec4<f32> {
    let size = vec2<i32>(textureDimensions(height_texture));
    let first = wrapped_cell(cell, size);
    if any(first == size - 1) {
        let next = select(first + 1, vec2<i32>(0), first == size - 1);
        return vec4<f32>(
            texel_height(height_texture, field, first),
            texel_height(height_texture, field, vec2<i32>(next.x, first.y)),
            texel_height(height_texture, field, vec2<i32>(first.x, next.y)),
            texel_height(height_texture, field, next),
        );
    }
    // The shared corner of the four texels: gather returns (i, j+1), (i+1, j+1), (i+1, j), (i, j).
    let uv = (vec2<f32>(first) + 1.0) / vec2<f32>(size);
    var gathered: vec4<f32>;
    switch field.channel {
        case 0u: { gathered = textureGather(0, height_texture, height_sampler, uv); }
        case 1u: { gathered = textureGather(1, height_texture, height_sampler, uv); }
        case 2u: { gathered = textureGather(2, height_texture, height_sampler, uv); }
        default: { gathered = textureGather(3, height_texture, height_sampler, uv); }
    }
    return heights_in_convention(gathered, field.depth_convention).wzxy;
}

// The bilinear surface at level 0 (the one the patches form) at `uv`.
fn bilinear_height(height_texture: texture_2d<f32>, height_sampler: sampler, field: HeightField, uv: vec2<f32>) -> f32 {
    let position = uv * vec2<f32>(textureDimensions(height_texture)) - 0.5;
    let cell = floor(position);
    let along = position - cell;
    let corners = patch_corners(height_texture, height_sampler, field, vec2<i32>(cell));
    return mix(mix(corners.x, corners.y, along.x), mix(corners.z, corners.w, along.x), along.y);
}

// Where a ray along `axis_travel` (cells per unit of t) from `axis_start` leaves cell
// `axis_cell` of side `cell_size` on one axis; infinite where it does not move on that axis.
fn axis_exit(axis_start: f32, axis_travel: f32, axis_cell: i32, cell_size: f32) -> f32 {
    if abs(axis_travel) < 1e-9 {
        return 3.4e38;
    }
    let edge = f32(axis_cell + select(0, 1, axis_travel > 0.0)) * cell_size;
    return (edge - axis_start) / axis_travel;
}

// Largest gap (field above the ray) that still counts as the ray touching the field: the
// rounding of a patch's f32 heights along the ray.
const MAX_MIP_TOUCH: f32 = 1e-6;

// The first t in [earliest, latest] where the gap c2 t² + c1 t + c0 (field above the ray) turns
// positive, or −1: where the ray goes below the field, not where it merely touches it (a ray
// that enters on the top plane at a rim and passes above the drop goes on).
fn first_root(c2: f32, c1: f32, c0: f32, earliest: f32, latest: f32) -> f32 {
    let gap = (c2 * earliest + c1) * earliest + c0;
    if gap > MAX_MIP_TOUCH {
        return earliest;
    }
    // An interval of no length (the ray starts on the cell's far edge) says nothing of where
    // the ray goes: the patch beyond the edge is the next cell's.
    if latest <= earliest {
        return -1.0;
    }
    // Touching at `earliest`: a hit where the gap grows from there.
    let slope = 2.0 * c2 * earliest + c1;
    if gap >= -MAX_MIP_TOUCH && (slope > 0.0 || (slope == 0.0 && c2 > 0.0)) {
        return earliest;
    }
    // The one root where the gap turns positive: the gap is positive past the larger root
    // where it opens upwards, before the smaller where it opens downwards; a double root only
    // touches.
    var rising: f32;
    if abs(c2) < 1e-9 {
        if c1 < 1e-9 {
            return -1.0;
        }
        rising = -c0 / c1;
    } else {
        let discriminant = c1 * c1 - 4.0 * c2 * c0;
        if discriminant <= 0.0 {
            return -1.0;
        }
        // The stable pair: no cancellation between c1 and the square root.
        let sign_c1 = select(-1.0, 1.0, c1 >= 0.0);
        let q = -0.5 * (c1 + sign_c1 * sqrt(discriminant));
        let a = q / c2;
        let b = select(a, c0 / q, q != 0.0);
        rising = select(min(a, b), max(a, b), c2 > 0.0);
    }
    if rising >= earliest && rising <= latest {
        return rising;
    }
    return -1.0;
}

// A straight ray over the field: at t ∈ [0, 1] it is at uv + offset × t, at height
// start_height + rise × t (the view ray descends from the top, a shadow ray rises).
struct FieldRay {
    uv: vec2<f32>,
    offset: vec2<f32>,
    start_height: f32,
    rise: f32,
}

// Where the surface first reaches a ray (`hit`: at t), or (not `hit`) how far the ray is known
// to be free: 1 through every cell, less if it ran out of steps. `samples` counts texel fetches:
// one per pyramid maximum read, one per patch gathered.
struct FieldHit {
    t: f32,
    hit: bool,
    samples: u32,
}

// The visible point of the view ray entering at `uv` with parallax offset vector `offset`.
fn march_max_mip(
    height_texture: texture_2d<f32>,
    height_sampler: sampler,
    pyramid: texture_2d<f32>,
    field: HeightField,
    uv: vec2<f32>,
    offset: vec2<f32>,
) -> RayHit {
    // A miss reaches the bottom (t = 1); a ray that ran out of steps stops where it is free.
    let found = max_mip_first_hit(height_texture, height_sampler, pyramid, field, FieldRay(uv, offset, 1.0, -1.0));
    return RayHit(uv + offset * found.t, 1.0 - found.t, found.samples, true);
}

// Hard self-shadow, exactly (no blocker stepped over): 0 if the height field blocks the light
// ray from the visible point at `uv`, else 1 (also where the ray ran out of steps). Like
// `hard_shadow` the ray starts HARD_SHADOW_BIAS above the surface (the patches' bilinear
// surface, which the view ray met) and rises to the top along `light_offset` = ray_offset(L_ts, H).
fn max_mip_hard_shadow(
    height_texture: texture_2d<f32>,
    height_sampler: sampler,
    pyramid: texture_2d<f32>,
    field: HeightField,
    uv: vec2<f32>,
    light_offset: vec2<f32>,
) -> f32 {
    let start = bilinear_height(height_texture, height_sampler, field, uv) + HARD_SHADOW_BIAS;
    let rise = 1.0 - start;
    if rise <= 0.0 {
        return 1.0;
    }
    let ray = FieldRay(uv, light_offset * rise, start, rise);
    return select(1.0, 0.0, max_mip_first_hit(height_texture, height_sampler, pyramid, field, ray).hit);
}

// A digital-differential-analyser walk over integer cells: leaving a cell steps its index along
// the axis the ray leaves by, climbing a level when that also leaves the parent; descending
// picks the child under the ray, kept inside the parent.
fn max_mip_first_hit(
    height_texture: texture_2d<f32>,
    height_sampler: sampler,
    pyramid: texture_2d<f32>,
    field: HeightField,
    ray: FieldRay,
) -> FieldHit {
    let size = vec2<f32>(textureDimensions(height_texture));
    // Starting inside the first repetition keeps positions small and precise.
    let unwrapped = ray.uv * size - 0.5;
    let start = unwrapped - floor(unwrapped / size) * size;
    let travel = ray.offset * size;
    let top = textureNumLevels(pyramid) - 1u;
    // Start at the level whose cells are about the square root of the ray's length (fewest
    // fetches: see the reference).
    let crossed = u32(min(ceil(abs(travel.x) + abs(travel.y)), 1e9));
    var level = min((32u - countLeadingZeros(max(crossed, 1u))) / 2u, top);
    let direction = vec2<i32>(sign(travel));
    var cell = vec2<i32>(floor(start / f32(1u << level)));
    let bound = min(4u * (min(crossed, MAX_MIP_STEPS) + 2u) * (top + 2u), MAX_MIP_STEPS);
    var t = 0.0;
    var samples = 0u;
    for (var i = 0u; i < bound; i += 1u) {
        if t >= 1.0 {
            break;
        }
        let cell_size = f32(1u << level);
        // At level 0 the patch itself is tested: its maximum would cost a fetch for nothing.
        var maximum = 1.0;
        if level > 0u {
            maximum = pyramid_maximum(pyramid, level, cell);
            samples += 1u;
        }
        let exit_x = axis_exit(start.x, travel.x, cell.x, cell_size);
        let exit_y = axis_exit(start.y, travel.y, cell.y, cell_size);
        let exit = min(min(exit_x, exit_y), 1.0);
        // The ray's lowest point in the cell: where it leaves if it descends, else where it
        // entered.
        if min(ray.start_height + ray.rise * exit, ray.start_height + ray.rise * t) <= maximum {
            if ray.rise < 0.0 {
                // Down to the cell's highest point before anything can be hit.
                t = max(t, (maximum - ray.start_height) / ray.rise);
            }
            if level > 0u {
                level -= 1u;
                let child = vec2<i32>(floor((start + travel * t) / (cell_size * 0.5)));
                cell = clamp(child, cell * 2, cell * 2 + 1);
                continue;
            }
            // A level-0 cell: the bilinear patch along the ray is quadratic in t.
            let corners = patch_corners(height_texture, height_sampler, field, cell);
            samples += 1u;
            let a = start - vec2<f32>(cell);
            let b = travel;
            let du = corners.y - corners.x;
            let dv = corners.z - corners.x;
            let duv = corners.x - corners.y - corners.z + corners.w;
            let c2 = duv * b.x * b.y;
            let c1 = du * b.x + dv * b.y + duv * (a.x * b.y + a.y * b.x) - ray.rise;
            let c0 = corners.x + du * a.x + dv * a.y + duv * a.x * a.y - ray.start_height;
            let root = first_root(c2, c1, c0, t, exit);
            if root >= 0.0 {
                return FieldHit(root, true, samples);
            }
        }
        // Into the next cell along the axis the ray leaves by; up a level where that also
        // leaves the parent (whose cells the ray has not reached may then be skipped whole).
        t = max(t, exit);
        let parent = cell >> vec2<u32>(1u);
        if exit_x <= exit_y {
            cell.x += direction.x;
        } else {
            cell.y += direction.y;
        }
        if level < top && any(cell >> vec2<u32>(1u) != parent) {
            level += 1u;
            cell = cell >> vec2<u32>(1u);
        }
    }
    return FieldHit(min(t, 1.0), false, samples);
}
