//! The exact hierarchical march over a pyramid of maximum heights (Tevs, Ihrke and Seidel,
//! "Maximum mipmaps for fast, accurate, and scalable dynamic height field rendering", I3D 2008):
//! the CPU reference of the `MaxMip` method (`parallax/max_mip.wgsl` follows it step for step).
//!
//! The surface is the bilinear height field the GPU filters (texel centres at (i + ½) / size,
//! wrapping). Between four neighbouring texel centres it is one bilinear patch, which never rises
//! above its highest corner: a level-0 *cell* holds that corner maximum, and each level above
//! holds the maximum of its 2 × 2 cells. The view ray enters at height 1 and falls to 0 over the
//! parallax offset. Where it stays above a cell's maximum the whole cell is skipped (and the march
//! climbs a level); where it might not, it descends; in a level-0 cell the ray meets the patch
//! where a quadratic (bilinear along a line, against a linear height) has its first root. So the
//! answer is exact up to rounding, whatever the angle, and no thin peak is stepped over.

use glam::{Vec2, Vec3};

use super::{RayHit, ray_offset};
use crate::HeightField;

/// A height field with the maximum heights of its cells, level by level. Not
/// [`crate::Image::max_mip_chain`]: that reduces texels, while the bilinear surface between
/// texel centres needs level 0 to hold each cell's four corners.
#[derive(Clone, Debug)]
pub struct MaxPyramid {
    field: HeightField,
    /// (width, height, maxima row by row) of each level, finest first.
    levels: Vec<(u32, u32, Vec<f32>)>,
}

impl MaxPyramid {
    /// The pyramid of `field`. Levels halve while both sides stay even, so that every level
    /// repeats with the texture (a 1024² map gets 11 levels, a 96 × 64 one 6).
    pub fn new(field: &HeightField) -> Self {
        let (width, height) = field.size();
        let cells: Vec<f32> = (0..i64::from(height))
            .flat_map(|y| {
                (0..i64::from(width)).map(move |x| {
                    field
                        .texel(x, y)
                        .max(field.texel(x + 1, y))
                        .max(field.texel(x, y + 1))
                        .max(field.texel(x + 1, y + 1))
                })
            })
            .collect();
        let mut levels = vec![(width, height, cells)];
        while let Some((w, h, below)) = levels.last()
            && w % 2 == 0
            && h % 2 == 0
        {
            let (w, h) = (w / 2, h / 2);
            let row = 2 * w as usize;
            let maxima = (0..h as usize)
                .flat_map(|y| {
                    (0..w as usize).map(move |x| {
                        let at = 2 * y * row + 2 * x;
                        below[at]
                            .max(below[at + 1])
                            .max(below[at + row])
                            .max(below[at + row + 1])
                    })
                })
                .collect();
            levels.push((w, h, maxima));
        }
        Self {
            field: field.clone(),
            levels,
        }
    }

    /// The field the pyramid was built from.
    pub fn field(&self) -> &HeightField {
        &self.field
    }

    /// Number of levels (the finest is 0).
    pub fn level_count(&self) -> usize {
        self.levels.len()
    }

    /// The maximum of cell (x, y) of `level` (the coarsest past the last), wrapping.
    pub fn max_at(&self, level: usize, x: i64, y: i64) -> f32 {
        let (width, height, maxima) = &self.levels[level.min(self.levels.len() - 1)];
        let x = x.rem_euclid(i64::from(*width)) as usize;
        let y = y.rem_euclid(i64::from(*height)) as usize;
        maxima[y * *width as usize + x]
    }
}

/// Most traversal steps one ray takes (`MAX_MIP_STEPS` in WGSL).
pub(crate) const MAX_MIP_STEPS: u32 = 2048;

/// Largest gap (field above the ray) that still counts as the ray touching the field: the
/// rounding of a patch's f32 heights along the ray (`MAX_MIP_TOUCH` in WGSL).
pub(crate) const MAX_MIP_TOUCH: f32 = 1e-6;

/// The first t in `[from, to]` where the gap `c2 t² + c1 t + c0` (field above the ray) turns
/// positive: where the ray goes below the field, not where it merely touches it.
fn first_root(c2: f32, c1: f32, c0: f32, from: f32, to: f32) -> Option<f32> {
    let gap = (c2 * from + c1) * from + c0;
    if gap > MAX_MIP_TOUCH {
        return Some(from);
    }
    // An interval of no length (the ray starts on the cell's far edge) says nothing of where
    // the ray goes: the patch beyond the edge is the next cell's.
    if to <= from {
        return None;
    }
    // Touching at `from`: a hit where the gap grows from there.
    let slope = 2.0 * c2 * from + c1;
    if gap >= -MAX_MIP_TOUCH && (slope > 0.0 || (slope == 0.0 && c2 > 0.0)) {
        return Some(from);
    }
    // The one root where the gap turns positive: the gap is positive past the larger root
    // where it opens upwards, before the smaller where it opens downwards; a double root only
    // touches.
    let rising = if c2.abs() < 1e-9 {
        if c1 < 1e-9 {
            return None;
        }
        -c0 / c1
    } else {
        let discriminant = c1 * c1 - 4.0 * c2 * c0;
        if discriminant <= 0.0 {
            return None;
        }
        // The stable pair: no cancellation between c1 and the square root.
        let q = -0.5 * (c1 + c1.signum() * discriminant.sqrt());
        let a = q / c2;
        let b = if q != 0.0 { c0 / q } else { a };
        if c2 > 0.0 { a.max(b) } else { a.min(b) }
    };
    (from..=to).contains(&rising).then_some(rising)
}

/// Where a ray along `axis_travel` (cells per unit of t) from `axis_start` leaves the cell
/// `axis_cell` of side `cell_size` on one axis; infinite where it does not move on that axis.
fn axis_exit(axis_start: f32, axis_travel: f32, axis_cell: i32, cell_size: f32) -> f32 {
    if axis_travel.abs() < 1e-9 {
        return f32::INFINITY;
    }
    let edge = (axis_cell + i32::from(axis_travel > 0.0)) as f32 * cell_size;
    (edge - axis_start) / axis_travel
}

/// A straight ray over the field: at t ∈ [0, 1] it is at `uv + offset × t`, at height
/// `start_height + rise × t` (the view ray descends from the top, a shadow ray rises).
#[derive(Clone, Copy, Debug, PartialEq)]
struct FieldRay {
    uv: Vec2,
    offset: Vec2,
    start_height: f32,
    rise: f32,
}

/// Where the surface first reaches a ray (`hit`: at `t`), or (not `hit`) how far the ray is
/// known to be free: 1 through every cell, less if it ran out of steps ([`MAX_MIP_STEPS`]).
#[derive(Clone, Copy, Debug, PartialEq)]
struct FieldHit {
    /// The hit, or the end of the free part of the ray.
    t: f32,
    /// Whether the surface reaches the ray at `t`.
    hit: bool,
    /// Texel fetches: one per cell maximum read, one per patch gathered.
    samples: u32,
}

/// The visible point of the view ray entering at `uv` (heights 1 = top, 0 = deepest), with
/// `samples` counting texel fetches: one per cell maximum read, one per patch gathered.
pub fn march_max_mip(pyramid: &MaxPyramid, uv: Vec2, to_eye_ts: Vec3, height_scale: f32) -> RayHit {
    let ray = FieldRay {
        uv,
        offset: -ray_offset(to_eye_ts, height_scale),
        start_height: 1.0,
        rise: -1.0,
    };
    // A miss reaches the bottom (t = 1); a ray that ran out of steps stops where it is free.
    let found = first_hit(pyramid, &ray);
    RayHit {
        uv: uv + ray.offset * found.t,
        height: 1.0 - found.t,
        samples: found.samples,
    }
}

/// `max_mip_hard_shadow` of max_mip.wgsl: 0 if the height field blocks the light ray from the
/// visible point at `uv`, else 1 (also where the ray ran out of steps), exactly (no blocker
/// stepped over). Like [`super::hard_shadow`]
/// the ray starts [`super::HARD_SHADOW_BIAS`] above the surface and rises to the top along
/// `light_offset` = [`ray_offset`]`(to_light_ts, height_scale)`.
pub fn max_mip_hard_shadow(pyramid: &MaxPyramid, uv: Vec2, light_offset: Vec2) -> f32 {
    let start = pyramid.field().sample(uv.x, uv.y) + super::HARD_SHADOW_BIAS;
    let rise = 1.0 - start;
    if rise <= 0.0 {
        return 1.0;
    }
    let ray = FieldRay {
        uv,
        offset: light_offset * rise,
        start_height: start,
        rise,
    };
    if first_hit(pyramid, &ray).hit {
        0.0
    } else {
        1.0
    }
}

/// The level a walk starts at: the one whose cells are about the square root of the ray's
/// length in level-0 cells (`crossed`), at most `top`. Higher costs a fetch per level on the way
/// down to a ray that hits early (most rays over cobblestones), lower costs climbing on a long
/// empty ray. At 70° (the test below prints the fetches) this start takes fewer, on cobblestones
/// and on cones, than starting at the ray's length or at level 0.
fn starting_level(crossed: u32, top: u32) -> u32 {
    ((u32::BITS - crossed.max(1).leading_zeros()) / 2).min(top)
}

/// Where `ray` first meets the bilinear patch of level-0 `cell` between `from` and `to`, if it
/// does (one gather of the patch's four corners). `start` and `travel` are the ray in level-0
/// cell coordinates; along it the patch is quadratic in t.
fn patch_crossing(
    field: &HeightField,
    cell: [i32; 2],
    start: Vec2,
    travel: Vec2,
    ray: &FieldRay,
    from: f32,
    to: f32,
) -> Option<f32> {
    let (x, y) = (i64::from(cell[0]), i64::from(cell[1]));
    let (h00, h10, h01, h11) = (
        field.texel(x, y),
        field.texel(x + 1, y),
        field.texel(x, y + 1),
        field.texel(x + 1, y + 1),
    );
    // Patch coordinates f(t) = a + b t; surface − ray = c2 t² + c1 t + c0.
    let a = start - Vec2::new(cell[0] as f32, cell[1] as f32);
    let b = travel;
    let (du, dv, duv) = (h10 - h00, h01 - h00, h00 - h10 - h01 + h11);
    let c2 = duv * b.x * b.y;
    let c1 = du * b.x + dv * b.y + duv * (a.x * b.y + a.y * b.x) - ray.rise;
    let c0 = h00 + du * a.x + dv * a.y + duv * a.x * a.y - ray.start_height;
    first_root(c2, c1, c0, from, to)
}

/// The cell after `cell` of `level`, one `step` along `axis` (the axis the ray leaves by); up a
/// level (at most `top`) where that also leaves the parent, whose cells the ray has not reached
/// may then be skipped whole.
fn next_cell(cell: [i32; 2], level: u32, top: u32, axis: usize, step: i32) -> ([i32; 2], u32) {
    let parent = cell.map(|index| index >> 1);
    let mut next = cell;
    next[axis] += step;
    if level < top && next.map(|index| index >> 1) != parent {
        (next.map(|index| index >> 1), level + 1)
    } else {
        (next, level)
    }
}

/// The first t ∈ [0, 1] where the surface reaches `ray`, if any.
///
/// A digital-differential-analyser walk over integer cells: leaving a cell steps its index
/// along the axis the ray leaves by (no position is rounded back into a cell, so no ray stalls
/// on an edge), climbing a level when that also leaves the parent; descending picks the child
/// under the ray, kept inside the parent.
fn first_hit(pyramid: &MaxPyramid, ray: &FieldRay) -> FieldHit {
    let field = pyramid.field();
    let (width, height) = field.size();
    let size = Vec2::new(width as f32, height as f32);
    // In level-0 cell coordinates: cell (i, j) spans texel centres i..i+1, j..j+1. The field
    // repeats: starting inside the first repetition keeps positions small and precise.
    let start = (ray.uv * size - 0.5).rem_euclid(size);
    let travel = ray.offset * size;
    let at = |t: f32| start + travel * t;
    let height_at = |t: f32| ray.start_height + ray.rise * t;
    let top = pyramid.level_count() as u32 - 1;
    let crossed = (travel.x.abs() + travel.y.abs()).ceil().min(1e9) as u32;
    let mut level = starting_level(crossed, top);
    let direction = [travel.x, travel.y].map(|axis| i32::from(axis > 0.0) - i32::from(axis < 0.0));
    let first = (start / (1u32 << level) as f32).floor();
    let mut cell = [first.x as i32, first.y as i32];
    let mut t = 0.0_f32;
    let mut samples = 0;
    // Each step skips a cell, climbs or descends: bounded by the cells the ray crosses at
    // level 0 and the levels, with room to spare, and by the GPU's per-pixel cap.
    let bound = (4 * (crossed.min(MAX_MIP_STEPS) + 2) * (top + 2)).min(MAX_MIP_STEPS);
    for _ in 0..bound {
        if t >= 1.0 {
            break;
        }
        let cell_size = (1u32 << level) as f32;
        // At level 0 the patch itself is tested: its maximum would cost a fetch for nothing.
        let maximum = if level == 0 {
            1.0
        } else {
            samples += 1;
            pyramid.max_at(level as usize, i64::from(cell[0]), i64::from(cell[1]))
        };
        let exit_x = axis_exit(start.x, travel.x, cell[0], cell_size);
        let exit_y = axis_exit(start.y, travel.y, cell[1], cell_size);
        let exit = exit_x.min(exit_y).min(1.0);
        // The ray's lowest point in the cell: where it leaves if it descends, else where it
        // entered.
        if height_at(exit).min(height_at(t)) <= maximum {
            if ray.rise < 0.0 {
                // Down to the cell's highest point before anything can be hit.
                t = t.max((maximum - ray.start_height) / ray.rise);
            }
            if level > 0 {
                level -= 1;
                let child = (at(t) / (cell_size * 0.5)).floor();
                cell = [
                    (child.x as i32).clamp(cell[0] * 2, cell[0] * 2 + 1),
                    (child.y as i32).clamp(cell[1] * 2, cell[1] * 2 + 1),
                ];
                continue;
            }
            // A level-0 cell: the patch itself.
            samples += 1;
            if let Some(root) = patch_crossing(field, cell, start, travel, ray, t, exit) {
                return FieldHit {
                    t: root,
                    hit: true,
                    samples,
                };
            }
        }
        t = t.max(exit);
        let axis = usize::from(exit_x > exit_y);
        (cell, level) = next_cell(cell, level, top, axis, direction[axis]);
    }
    FieldHit {
        t: t.min(1.0),
        hit: false,
        samples,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::parallax::ParallaxMethod;
    use crate::patterns;
    use crate::reference::{exact_intersection, march_view};

    /// Errors in texels of max-mip against the exact intersection, with its mean fetches, and
    /// POM's errors and samples at `pom_steps`, over a grid of entry points seen `angle`
    /// degrees from the normal along +u.
    fn errors(
        field: &HeightField,
        angle: f32,
        height_scale: f32,
        pom_steps: u32,
        grid: u32,
    ) -> (Vec<f32>, f32, Vec<f32>, f32) {
        let radians = angle.to_radians();
        let to_eye = Vec3::new(-radians.sin(), 0.0, radians.cos());
        errors_along(field, to_eye, height_scale, pom_steps, grid)
    }

    /// [`errors`] for any view direction.
    fn errors_along(
        field: &HeightField,
        to_eye: Vec3,
        height_scale: f32,
        pom_steps: u32,
        grid: u32,
    ) -> (Vec<f32>, f32, Vec<f32>, f32) {
        let pyramid = MaxPyramid::new(field);
        let (width, height) = field.size();
        let size = Vec2::new(width as f32, height as f32);
        let (mut max_mip, mut pom) = (Vec::new(), Vec::new());
        let (mut fetches, mut samples) = (0, 0);
        for y in 0..grid {
            for x in 0..grid {
                let uv = (Vec2::new(x as f32, y as f32) + 0.5) / grid as f32;
                let exact = exact_intersection(field, uv, to_eye, height_scale);
                let ours = march_max_mip(&pyramid, uv, to_eye, height_scale);
                let marched = march_view(
                    field,
                    ParallaxMethod::Occlusion,
                    uv,
                    to_eye,
                    height_scale,
                    pom_steps,
                );
                max_mip.push(((ours.uv - exact) * size).length());
                pom.push(((marched.uv - exact) * size).length());
                fetches += ours.samples;
                samples += marched.samples;
            }
        }
        let count = (grid * grid) as f32;
        (max_mip, fetches as f32 / count, pom, samples as f32 / count)
    }

    fn mean(values: &[f32]) -> f32 {
        values.iter().sum::<f32>() / values.len() as f32
    }

    fn p99(values: &[f32]) -> f32 {
        let mut sorted = values.to_vec();
        sorted.sort_by(f32::total_cmp);
        sorted[(sorted.len() * 99 / 100).min(sorted.len() - 1)]
    }

    #[test]
    fn the_pyramid_holds_the_highest_corner_of_every_cell_below() {
        let field = patterns::cones(16, 4.0);
        let pyramid = MaxPyramid::new(&field);
        assert_eq!(pyramid.level_count(), 5);
        for level in 1..pyramid.level_count() {
            let side = 1 << level;
            for y in 0..(16 / side) {
                for x in 0..(16 / side) {
                    let mut highest = f32::MIN;
                    for j in 0..side {
                        for i in 0..side {
                            highest = highest.max(pyramid.max_at(0, x * side + i, y * side + j));
                        }
                    }
                    assert_eq!(
                        pyramid.max_at(level, x, y),
                        highest,
                        "level {level} ({x}, {y})"
                    );
                }
            }
        }
        // Level 0: the four corners of the patch, wrapping at the edge.
        let corner = field
            .texel(15, 15)
            .max(field.texel(0, 15))
            .max(field.texel(15, 0))
            .max(field.texel(0, 0));
        assert_eq!(pyramid.max_at(0, 15, 15), corner);
        // Odd sides stop the halving where the levels would no longer repeat with the map.
        assert_eq!(
            MaxPyramid::new(&HeightField::new(12, 8, vec![0.5; 96]).unwrap()).level_count(),
            3
        );
    }

    #[test]
    fn a_flat_floor_and_a_flat_top_are_hit_exactly() {
        let to_eye = Vec3::new(-0.6, 0.0, 0.8);
        let floor = HeightField::new(8, 8, vec![0.0; 64]).unwrap();
        let hit = march_max_mip(&MaxPyramid::new(&floor), Vec2::splat(0.5), to_eye, 0.1);
        let expected = Vec2::splat(0.5) - ray_offset(to_eye, 0.1);
        assert!((hit.uv - expected).length() < 1e-5, "{:?}", hit.uv);
        assert!(hit.height.abs() < 1e-5);
        let top = HeightField::new(8, 8, vec![1.0; 64]).unwrap();
        let hit = march_max_mip(&MaxPyramid::new(&top), Vec2::splat(0.5), to_eye, 0.1);
        assert_eq!(hit.uv, Vec2::splat(0.5));
        // Straight down onto a half-height field.
        let half = HeightField::new(8, 8, vec![0.5; 64]).unwrap();
        let hit = march_max_mip(&MaxPyramid::new(&half), Vec2::splat(0.3), Vec3::Z, 0.1);
        assert!((hit.uv - Vec2::splat(0.3)).length() < 1e-6 && (hit.height - 0.5).abs() < 1e-6);
    }

    /// Max-mip's acceptance measure: 1024² maps at 70°, POM at a fixed 50 samples (no texel
    /// cap).
    #[test]
    fn max_mip_is_exact_at_70_degrees_and_fetches_half_of_poms_on_the_cones() {
        for (name, field) in [
            ("cobblestones", patterns::cobblestones(1024, 8).quantized()),
            ("cones", patterns::cones(1024, 8.0).quantized()),
        ] {
            let (ours, fetches, pom, samples) = errors(&field, 70.0, 0.05, 50, 24);
            eprintln!(
                "{name} 70°: max-mip mean {:.4} p99 {:.4} texel, {fetches:.1} fetches; POM@50 mean {:.4} p99 {:.4} texel, {samples:.1} samples",
                mean(&ours),
                p99(&ours),
                mean(&pom),
                p99(&pom)
            );
            assert!(mean(&ours) <= 0.05, "{name}: mean {}", mean(&ours));
            assert!(p99(&ours) <= 0.5, "{name}: p99 {}", p99(&ours));
            assert!(p99(&pom) > p99(&ours), "{name}: POM's p99 {}", p99(&pom));
            // Not on the cobblestones, where the two are about even: there the ray meets relief
            // near the top within a few texels, where an exact march tests every patch it
            // crosses and POM strides 2.8 texels a sample.
            if name == "cones" {
                assert!(
                    fetches <= 0.5 * samples,
                    "{name}: {fetches} fetches vs POM's {samples}"
                );
            }
        }
    }

    #[test]
    fn max_mip_agrees_with_the_exact_intersection_along_every_direction_and_on_long_rays() {
        let small = patterns::cones(32, 3.0).quantized();
        let large = patterns::cones(1024, 8.0).quantized();
        // Towards −u, −v and diagonally; then a grazing ray at the offset cap: two repetitions
        // of a 1024² map, 2,000 texels long.
        for (field, to_eye, height_scale) in [
            (&small, Vec3::new(0.8, 0.0, 0.6), 0.08),
            (&small, Vec3::new(0.0, 0.8, 0.6), 0.08),
            (&small, Vec3::new(0.5, -0.6, 0.62).normalize(), 0.08),
            (&large, Vec3::new(-1.0, -0.3, 0.001).normalize(), 0.1),
        ] {
            let (ours, _, _, _) = errors_along(field, to_eye, height_scale, 32, 12);
            assert!(mean(&ours) <= 0.05, "{to_eye}: mean {}", mean(&ours));
        }
    }

    /// Whether anything blocks the light ray from `uv`, by a march of a twentieth of a texel.
    fn densely_blocked(field: &HeightField, uv: Vec2, light_offset: Vec2) -> bool {
        let start = field.sample(uv.x, uv.y) + crate::reference::HARD_SHADOW_BIAS;
        let rise = 1.0 - start;
        let (width, _) = field.size();
        let steps = ((light_offset * rise * width as f32).length() * 20.0)
            .ceil()
            .max(64.0) as u32;
        (1..=steps).any(|i| {
            let t = i as f32 / steps as f32;
            let at = uv + light_offset * rise * t;
            field.sample(at.x, at.y) >= start + rise * t
        })
    }

    #[test]
    fn max_mip_hard_shadows_miss_no_blocker_the_linear_march_steps_over() {
        let field = patterns::spikes(128, 16, 0.2);
        let pyramid = MaxPyramid::new(&field);
        let (mut wrong, mut linear_wrong, mut shadowed, count) = (0, 0, 0, 48 * 48);
        for index in 0..count {
            let uv = (Vec2::new((index % 48) as f32, (index / 48) as f32) + 0.5) / 48.0;
            let to_light = Vec3::new(0.9, 0.35, 0.25).normalize();
            let light_offset = ray_offset(to_light, 0.06);
            let blocked = densely_blocked(&field, uv, light_offset);
            let ours = max_mip_hard_shadow(&pyramid, uv, light_offset) == 0.0;
            let linear = crate::reference::hard_shadow(&field, uv, light_offset, 8) == 0.0;
            wrong += usize::from(ours != blocked);
            linear_wrong += usize::from(linear != blocked);
            shadowed += usize::from(blocked);
        }
        eprintln!(
            "hard shadows over {count} points ({shadowed} shadowed): max-mip wrong at {wrong}, linear (8 steps) at {linear_wrong}"
        );
        // A dense march can itself step over a blocker thinner than a twentieth of a texel.
        assert!(wrong <= count / 500, "max-mip wrong at {wrong} of {count}");
        assert!(
            linear_wrong > 10 * wrong.max(1),
            "linear wrong at {linear_wrong}"
        );
        assert!(shadowed > count / 50, "{shadowed} shadowed");
    }

    /// The step cap (`MAX_MIP_STEPS`) never cuts a ray short on grazing rays at the offset cap
    /// (2,000 texels over a 1024² map, at height scale 0.1) over spikes, cones and
    /// cobblestones, descending or rising.
    #[test]
    fn no_ray_runs_out_of_steps_at_the_offset_cap() {
        for (name, field) in [
            ("spikes", patterns::spikes(1024, 16, 0.2)),
            ("cones", patterns::cones(1024, 8.0).quantized()),
            ("cobblestones", patterns::cobblestones(1024, 8).quantized()),
        ] {
            let pyramid = MaxPyramid::new(&field);
            let grazing = Vec3::new(-1.0, -0.3, 0.001).normalize();
            let offset = ray_offset(grazing, 0.1);
            let mut cut_short = 0;
            for index in 0..32 * 32 {
                let uv = (Vec2::new((index % 32) as f32, (index / 32) as f32) + 0.5) / 32.0;
                for ray in [
                    FieldRay {
                        uv,
                        offset: -offset,
                        start_height: 1.0,
                        rise: -1.0,
                    },
                    FieldRay {
                        uv,
                        offset,
                        start_height: 0.0,
                        rise: 1.0,
                    },
                ] {
                    let found = first_hit(&pyramid, &ray);
                    cut_short += usize::from(!found.hit && found.t < 1.0);
                }
            }
            assert_eq!(cut_short, 0, "{name}: {cut_short} rays ran out of steps");
        }
    }

    #[test]
    fn max_mip_agrees_with_the_exact_intersection_at_every_angle() {
        let field = patterns::cones(32, 3.0).quantized();
        for angle in [0.0_f32, 20.0, 45.0, 60.0, 80.0, 88.0] {
            let (ours, _, _, _) = errors(&field, angle, 0.08, 32, 16);
            assert!(mean(&ours) <= 0.05, "{angle}°: mean {}", mean(&ours));
        }
    }
}
