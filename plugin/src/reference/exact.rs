//! The exact first intersection of a view ray with the bilinear height field, which every
//! method's error is measured against. In f64, without a march: the ray is cut where it crosses
//! a row or column of texel centres; between two cuts the field is one bilinear patch, so the
//! gap between field and ray is a quadratic whose highest point is known from three values, and
//! the first piece where the gap turns positive is bisected. No ridge tip or saddle top the ray
//! only clips is stepped over, however thin.
//!
//! The ray hits where it goes *below* the field, not where it merely touches it: a ray that
//! enters on the top plane at a rim (a texel of height 1 with lower ones after it along the ray)
//! touches the field there, and passes above the drop when the field falls faster than the ray.

use glam::{Vec2, Vec3};

use super::ray_offset;
use crate::HeightField;

/// Halvings of the piece that holds the hit: more than f64 resolves on a fraction of the ray.
const BISECTIONS: u32 = 64;
/// Largest gap (field above the ray) that still counts as the ray touching the field: rounding
/// of f64 heights, far below any height a texel holds.
const TOUCH: f64 = 1e-12;

/// The true first intersection of the view ray entering at `uv` with the bilinear height field
/// (texel centres at (i + ½) / size, wrapping): the ray falls from the top (1) at `uv` to the
/// bottom (0) at `uv` + P, P = −[`ray_offset`]`(to_eye_ts, height_scale)`. `uv` itself where
/// the ray goes below the field at once (on a plateau at the top), not where it only touches
/// the top there and the field falls away faster than the ray.
pub fn exact_intersection(
    field: &HeightField,
    uv: Vec2,
    to_eye_ts: Vec3,
    height_scale: f32,
) -> Vec2 {
    exact_intersection_along(field, uv, -ray_offset(to_eye_ts, height_scale))
}

/// [`exact_intersection`] of the ray that travels `offset` (in uv) from the top to the bottom.
pub fn exact_intersection_along(field: &HeightField, uv: Vec2, offset: Vec2) -> Vec2 {
    let ray = CellRay::new(field, uv, offset);
    let mut from = 0.0;
    // The ray reaches the bottom at t = 1, where the gap cannot be negative: a ray that goes
    // below the field nowhere before ends there.
    let mut hit = 1.0;
    for to in ray.cuts().chain([1.0]) {
        if let Some(t) = ray.first_hit_between(from, to) {
            hit = t;
            break;
        }
        from = to;
    }
    let along = |entry: f32, travel: f32| (f64::from(entry) + f64::from(travel) * hit) as f32;
    Vec2::new(along(uv.x, offset.x), along(uv.y, offset.y))
}

/// A view ray in level-0 cell coordinates (texel centre i at i), t = 0 at the top, 1 at the
/// bottom.
struct CellRay<'a> {
    field: &'a HeightField,
    start: (f64, f64),
    travel: (f64, f64),
}

impl<'a> CellRay<'a> {
    fn new(field: &'a HeightField, uv: Vec2, offset: Vec2) -> Self {
        let (width, height) = field.size();
        let (width, height) = (f64::from(width), f64::from(height));
        Self {
            field,
            start: (
                f64::from(uv.x) * width - 0.5,
                f64::from(uv.y) * height - 0.5,
            ),
            travel: (f64::from(offset.x) * width, f64::from(offset.y) * height),
        }
    }

    /// Field height minus ray height at `t`: bilinear in f64 between the wrapped texels.
    fn gap(&self, t: f64) -> f64 {
        let (x, y) = (
            self.start.0 + self.travel.0 * t,
            self.start.1 + self.travel.1 * t,
        );
        let (x0, y0) = (x.floor(), y.floor());
        let (fx, fy) = (x - x0, y - y0);
        // Wrapped here, in f64, so that far-off coordinates neither overflow nor lose texels.
        let (width, height) = self.field.size();
        let column = x0.rem_euclid(f64::from(width)) as i64;
        let row = y0.rem_euclid(f64::from(height)) as i64;
        let texel = |dx, dy| f64::from(self.field.texel(column + dx, row + dy));
        // a + (b − a) f: exactly a where a = b, so a plateau at the top is exactly 1.
        let mix = |a: f64, b: f64, f: f64| a + (b - a) * f;
        let top = mix(texel(0, 0), texel(1, 0), fx);
        let bottom = mix(texel(0, 1), texel(1, 1), fx);
        mix(top, bottom, fy) - (1.0 - t)
    }

    /// The fractions of the ray in [0, 1] where it crosses a row or column of texel centres, in
    /// order; generated as walked, so a ray that hits early costs only the pieces before.
    fn cuts(&self) -> impl Iterator<Item = f64> {
        let mut columns = line_crossings(self.start.0, self.travel.0).peekable();
        let mut rows = line_crossings(self.start.1, self.travel.1).peekable();
        std::iter::from_fn(move || match (columns.peek(), rows.peek()) {
            (Some(column), Some(row)) if row < column => rows.next(),
            _ => columns.next().or_else(|| rows.next()),
        })
    }

    /// The first t from `from` to `to` where the ray goes below the field (the gap turns
    /// positive), the ray being over one patch there (`gap` quadratic in t).
    fn first_hit_between(&self, from: f64, to: f64) -> Option<f64> {
        let (at_from, at_middle, at_to) =
            (self.gap(from), self.gap(0.5 * (from + to)), self.gap(to));
        // gap(from + s (to − from)) = at_from + linear s + quadratic s².
        let linear = 4.0 * at_middle - 3.0 * at_from - at_to;
        let quadratic = 2.0 * (at_from + at_to) - 4.0 * at_middle;
        if at_from > TOUCH {
            return Some(from);
        }
        // A piece of no length (the ray starts on a texel-centre line) says nothing of where
        // the ray goes: the next piece does.
        if to <= from {
            return None;
        }
        // Touching at `from`: a hit where the gap grows from there, not where the field falls
        // away faster than the ray.
        if at_from >= -TOUCH && (linear > 0.0 || (linear == 0.0 && quadratic > 0.0)) {
            return Some(from);
        }
        // A gap that peaks inside the piece may turn positive there and fall below again by
        // `to`.
        let peak = (quadratic < 0.0)
            .then(|| -linear / (2.0 * quadratic))
            .filter(|s| (0.0..1.0).contains(s))
            .map(|s| from + (to - from) * s)
            .filter(|&t| self.gap(t) > TOUCH);
        // The gap rises from at most 0 after `from` to above 0 at `reached`, crossing 0 once; a
        // gap that only touches 0 at `to` is the next piece's to judge.
        let reached = peak.or((at_to > TOUCH).then_some(to))?;
        let (mut below, mut above) = (from, reached);
        for _ in 0..BISECTIONS {
            let middle = 0.5 * (below + above);
            if self.gap(middle) > 0.0 {
                above = middle;
            } else {
                below = middle;
            }
        }
        Some(above)
    }
}

/// The fractions t in [0, 1] where `start` + `travel` t is an integer, in increasing order.
fn line_crossings(start: f64, travel: f64) -> impl Iterator<Item = f64> {
    let end = start + travel;
    let (first, last) = (start.min(end).ceil(), start.max(end).floor());
    // No line crossed, or a ray that is not finite (NaN or endless): no cuts, not an endless
    // walk; its one piece then finds no hit and the ray ends at its bottom.
    let count = if travel != 0.0 && end.is_finite() && last >= first {
        (last - first) as u64 + 1
    } else {
        0
    };
    (0..count).map(move |index| {
        let line = if travel > 0.0 {
            first + index as f64
        } else {
            last - index as f64
        };
        ((line - start) / travel).clamp(0.0, 1.0)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    const SIZE: u32 = 64;
    /// How far below the top of the ridge or saddle the rays pass.
    const BELOW_THE_TOP: f32 = 1e-4;

    /// The hit, in cell coordinates, of the ray from texel centre (0, 0) that travels `travel`
    /// texels along each axis while it falls from the top to the bottom.
    fn hit_from_the_first_texel(field: &HeightField, travel: Vec2) -> Vec2 {
        let uv = Vec2::splat(0.5 / SIZE as f32);
        exact_intersection_along(field, uv, travel / SIZE as f32) * SIZE as f32 - 0.5
    }

    /// A ray that passes 10⁻⁴ below the tip of a ridge (a kink where two patches meet at a
    /// texel centre) meets its near flank, where a march of a tenth of a texel steps over it.
    #[test]
    fn a_ray_that_only_clips_the_tip_of_a_ridge_hits_it() {
        // A ridge 0.5 high at texel 10 on a floor at 0; the ray is 0.5 − 10⁻⁴ high over it.
        let ridge = HeightField::from_fn(SIZE, SIZE, |u, _| {
            if (u * SIZE as f32) as u32 == 10 {
                0.5
            } else {
                0.0
            }
        });
        let travel = 10.0 / (0.5 + BELOW_THE_TOP);
        let found = hit_from_the_first_texel(&ridge, Vec2::new(travel, 0.0));
        // The field rises 0.5 per texel towards the tip, the ray falls 1 / travel.
        let expected = 10.0 - BELOW_THE_TOP / (0.5 + 1.0 / travel);
        assert!(
            (found - Vec2::new(expected, 0.0)).length() < 1e-3,
            "ridge: hit at {found}, expected {expected}"
        );
    }

    /// A ray along the diagonal of a checkerboard of 0 and 1, where every patch is 2s − 2s²,
    /// meets the hundredth patch just before its top (0.5, mid-patch), which it passes 10⁻⁴
    /// below. The ray crosses 228 texels (a march of a tenth of a texel steps over the top).
    #[test]
    fn a_ray_that_only_clips_the_top_of_a_saddle_hits_it() {
        const PATCH: f64 = 100.0;
        let checkerboard = HeightField::from_fn(SIZE, SIZE, |u, v| {
            (((u * SIZE as f32) as u32 + (v * SIZE as f32) as u32) % 2) as f32
        });
        let travel = (PATCH + 0.5) / f64::from(0.5 + BELOW_THE_TOP);
        let found = hit_from_the_first_texel(&checkerboard, Vec2::splat(travel as f32));
        // 2s − 2s² = 1 − (PATCH + s) / travel: the smaller root.
        let (b, c) = (2.0 + 1.0 / travel, 1.0 - PATCH / travel);
        let expected = PATCH + (b - (b * b - 8.0 * c).sqrt()) / 4.0;
        assert!(
            (found - Vec2::splat(expected as f32)).length() < 1e-3,
            "saddle: hit at {found}, expected {expected} on both axes"
        );
    }

    /// The latest of the points a march of `steps_per_texel` samples a texel finds under the
    /// field (f32 bilinear samples of `HeightField::sample`, apart from the reference's own
    /// f64 ones) before the hit; and how far the field at the hit is from the ray's height.
    fn check_against_a_dense_march(
        field: &HeightField,
        uv: Vec2,
        offset: Vec2,
        steps_per_texel: f32,
    ) -> (Option<f32>, f32) {
        let hit = exact_intersection_along(field, uv, offset);
        let texels = (offset * SIZE as f32).length();
        // The fraction of the ray the hit lies at, and the ray's height there.
        let hit_t = (hit - uv).dot(offset) / offset.length_squared();
        let off_the_surface = (field.sample(hit.x, hit.y) - (1.0 - hit_t)).abs();
        let steps = (texels * steps_per_texel).ceil() as u32;
        let missed = (0..steps)
            .map(|i| i as f32 / steps as f32)
            .take_while(|&t| t < hit_t - 1e-5)
            .filter(|&t| {
                let at = uv + offset * t;
                field.sample(at.x, at.y) - (1.0 - t) > 1e-5
            })
            .last();
        (missed, off_the_surface)
    }

    /// On thin spikes whose tips reach the top and on sharp cones, along rays in eight
    /// directions at 70° and 85°: the hit lies on the field, and a march of a fiftieth of a
    /// texel finds no point before it where the ray is under the field.
    #[test]
    fn the_hit_is_on_the_field_and_no_dense_march_finds_the_ray_under_it_earlier() {
        for (name, field) in [
            ("spikes", crate::patterns::spikes(SIZE, 8, 0.2)),
            ("cones", crate::patterns::cones(SIZE, 4.0).quantized()),
        ] {
            let mut rays = 0;
            for angle in [70.0_f32, 85.0] {
                for azimuth in (0..8).map(|k| (k as f32 * 45.0 + 7.0).to_radians()) {
                    let to_eye = Vec3::new(
                        -azimuth.cos() * angle.to_radians().sin(),
                        -azimuth.sin() * angle.to_radians().sin(),
                        angle.to_radians().cos(),
                    );
                    let offset = -ray_offset(to_eye, 0.05);
                    for index in 0..81 {
                        let uv = (Vec2::new((index % 9) as f32, (index / 9) as f32) + 0.37) / 9.0;
                        let (missed, off_the_surface) =
                            check_against_a_dense_march(&field, uv, offset, 50.0);
                        assert!(
                            missed.is_none(),
                            "{name}, {angle}°, azimuth {azimuth}, entry {uv}: the ray is under \
                             the field at t = {missed:?}, before the hit"
                        );
                        assert!(
                            off_the_surface < 1e-4,
                            "{name}, {angle}°, azimuth {azimuth}, entry {uv}: the hit is \
                             {off_the_surface} off the field"
                        );
                        rays += 1;
                    }
                }
            }
            eprintln!("{name}: {rays} rays");
        }
    }

    /// A ray that is not finite (NaN, or an endless offset passed straight to
    /// [`exact_intersection_along`]) gives an answer instead of an endless or overflowing walk.
    #[test]
    fn a_ray_that_is_not_finite_ends() {
        let field = crate::patterns::cones(SIZE, 4.0);
        for (uv, offset) in [
            (Vec2::splat(0.3), Vec2::new(f32::INFINITY, 0.0)),
            (Vec2::splat(0.3), Vec2::new(-0.2, f32::NEG_INFINITY)),
            (Vec2::new(f32::NAN, 0.3), Vec2::new(0.2, 0.1)),
            (Vec2::splat(0.3), Vec2::new(f32::NAN, 0.1)),
        ] {
            // Any answer will do; reaching this line is the test.
            let _ = exact_intersection_along(&field, uv, offset);
        }
    }
}
