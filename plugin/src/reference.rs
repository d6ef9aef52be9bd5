//! The CPU reference of the parallax march: the same steps as `parallax/march.wgsl`, in Rust,
//! plus an exact ray / height-field intersection to measure every method's error against.
//!
//! Heights use Tatarchuk's convention (1 = the polygon's surface, 0 = deepest). Tangent-space
//! vectors are (u, v, normal) components. Sampling is bilinear with wrapping at mip level 0,
//! which is what the GPU does when a texel covers at least a pixel.

mod exact;
mod layers;
mod max_mip;
mod triplanar;

pub use exact::{exact_intersection, exact_intersection_along};
pub use layers::{MAX_BLEND_CONTRAST, blended_height, layer_shares};
pub use max_mip::{MaxPyramid, march_max_mip, max_mip_hard_shadow};
pub use triplanar::{TRIPLANAR_MIN_SHARE, triplanar_height, triplanar_uvs, triplanar_weights};

use glam::{Vec2, Vec3};

use crate::HeightField;
use crate::parallax::ParallaxMethod;

/// Longest sideways travel per unit of depth (`MAX_PARALLAX_RATIO` in WGSL).
pub const MAX_PARALLAX_RATIO: f32 = 20.0;
/// Height bias of hard shadow rays (`HARD_SHADOW_BIAS` in WGSL).
pub const HARD_SHADOW_BIAS: f32 = 0.01;
/// Tatarchuk's fShadowSoftening default (`SEED_SHADOW_SOFTENING` in WGSL).
pub const SEED_SHADOW_SOFTENING: f32 = 0.58;

/// Where a ray meets the height field.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RayHit {
    /// Texture coordinate of the visible point.
    pub uv: Vec2,
    /// Its height.
    pub height: f32,
    /// Height samples taken to find it.
    pub samples: u32,
}

/// `ray_offset` of march.wgsl: the sideways travel of a ray along `direction_ts` while it rises
/// by `height_scale`, capped at [`MAX_PARALLAX_RATIO`] × `height_scale`.
pub fn ray_offset(direction_ts: Vec3, height_scale: f32) -> Vec2 {
    let sideways = direction_ts.truncate().length();
    if sideways < 1e-7 {
        return Vec2::ZERO;
    }
    let ratio = (sideways / direction_ts.z.max(1e-7)).min(MAX_PARALLAX_RATIO);
    direction_ts.truncate() / sideways * (ratio * height_scale)
}

/// `march_steps` of march.wgsl: T eq. 1, capped by the texels the ray crosses.
pub fn march_steps(min_samples: u32, max_samples: u32, n_dot_v: f32, texels_crossed: f32) -> u32 {
    let t = n_dot_v.clamp(0.0, 1.0);
    let wanted = (max_samples as f32 + (min_samples as f32 - max_samples as f32) * t).floor();
    let needed = texels_crossed.max(0.0).ceil();
    wanted.min(needed).clamp(1.0, max_samples.max(1) as f32) as u32
}

#[derive(Clone)]
struct Crossing {
    above_uv: Vec2,
    above_ray: f32,
    above_surface: f32,
    below_uv: Vec2,
    below_ray: f32,
    below_surface: f32,
    found: bool,
    samples: u32,
}

#[allow(clippy::too_many_arguments)]
fn linear_search(
    field: &HeightField,
    start_uv: Vec2,
    start_ray: f32,
    start_surface: f32,
    uv_span: Vec2,
    ray_span: f32,
    steps: u32,
) -> Crossing {
    let mut crossing = Crossing {
        above_uv: start_uv,
        above_ray: start_ray,
        above_surface: start_surface,
        below_uv: start_uv,
        below_ray: start_ray,
        below_surface: start_surface,
        found: false,
        samples: 0,
    };
    for i in 1..=steps {
        let t = if i == steps {
            1.0
        } else {
            i as f32 * (1.0 / steps as f32)
        };
        let uv = start_uv + uv_span * t;
        let ray = start_ray + ray_span * t;
        let surface = field.sample(uv.x, uv.y);
        crossing.samples += 1;
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
    crossing
}

fn secant_refinement(crossing: &Crossing) -> RayHit {
    let above_gap = crossing.above_ray - crossing.above_surface;
    let below_gap = crossing.below_ray - crossing.below_surface;
    let denominator = above_gap - below_gap;
    let t = if denominator > 1e-7 {
        (above_gap / denominator).clamp(0.0, 1.0)
    } else {
        1.0
    };
    RayHit {
        uv: crossing.above_uv.lerp(crossing.below_uv, t),
        height: crossing.above_ray + (crossing.below_ray - crossing.above_ray) * t,
        samples: crossing.samples,
    }
}

/// `narrowed` of march.wgsl: `bracket` with the sample at `uv` as its end on the side the
/// sample falls.
fn narrowed(bracket: &Crossing, uv: Vec2, ray: f32, surface: f32) -> Crossing {
    let mut narrower = bracket.clone();
    narrower.samples += 1;
    if surface >= ray {
        (
            narrower.below_uv,
            narrower.below_ray,
            narrower.below_surface,
        ) = (uv, ray, surface);
    } else {
        (
            narrower.above_uv,
            narrower.above_ray,
            narrower.above_surface,
        ) = (uv, ray, surface);
    }
    narrower
}

/// `secant_steps_refinement` of march.wgsl: the secant `steps` times, keeping the bracket
/// that holds the crossing each time (false position).
fn secant_steps_refinement(field: &HeightField, crossing: &Crossing, steps: u32) -> RayHit {
    let mut bracket = crossing.clone();
    for _ in 1..steps {
        let hit = secant_refinement(&bracket);
        bracket = narrowed(
            &bracket,
            hit.uv,
            hit.height,
            field.sample(hit.uv.x, hit.uv.y),
        );
    }
    secant_refinement(&bracket)
}

fn binary_refinement(field: &HeightField, crossing: &Crossing, steps: u32) -> RayHit {
    let mut bracket = crossing.clone();
    for _ in 0..steps {
        let middle_uv = (bracket.above_uv + bracket.below_uv) * 0.5;
        let middle_ray = (bracket.above_ray + bracket.below_ray) * 0.5;
        let surface = field.sample(middle_uv.x, middle_uv.y);
        bracket = narrowed(&bracket, middle_uv, middle_ray, surface);
    }
    RayHit {
        uv: (bracket.above_uv + bracket.below_uv) * 0.5,
        height: (bracket.above_ray + bracket.below_ray) * 0.5,
        samples: bracket.samples,
    }
}

/// `march_view` of march.wgsl: the visible point for the view ray entering at `uv`, relief
/// mapping and parallax occlusion mapping taking the material's default refinement steps.
pub fn march_view(
    field: &HeightField,
    method: ParallaxMethod,
    uv: Vec2,
    to_eye_ts: Vec3,
    height_scale: f32,
    steps: u32,
) -> RayHit {
    let defaults = crate::ParallaxOcclusionMaterial::default();
    let refinement_steps = match method {
        ParallaxMethod::Relief => defaults.relief_binary_steps,
        _ => defaults.secant_steps,
    };
    march_view_with(
        field,
        method,
        refinement_steps,
        uv,
        to_eye_ts,
        height_scale,
        steps,
    )
}

/// [`march_view`] with the refinement's steps given: relief mapping's bisections, or parallax
/// occlusion mapping's secant steps.
/// The parallax offset vector is P = −[`ray_offset`]`(to_eye_ts, height_scale)`.
pub fn march_view_with(
    field: &HeightField,
    method: ParallaxMethod,
    refinement_steps: u32,
    uv: Vec2,
    to_eye_ts: Vec3,
    height_scale: f32,
    steps: u32,
) -> RayHit {
    let offset = -ray_offset(to_eye_ts, height_scale);
    match method {
        ParallaxMethod::NormalMapping => {
            return RayHit {
                uv,
                height: 1.0,
                samples: 0,
            };
        }
        ParallaxMethod::ParallaxOffset => {
            let surface = field.sample(uv.x, uv.y);
            return RayHit {
                uv: uv - (1.0 - surface) * height_scale * to_eye_ts.truncate(),
                height: surface,
                samples: 1,
            };
        }
        // Builds the pyramid for this one ray: loops over many rays keep a `MaxPyramid` and
        // call `march_max_mip`.
        ParallaxMethod::MaxMip => {
            return march_max_mip(&MaxPyramid::new(field), uv, to_eye_ts, height_scale);
        }
        _ => {}
    }
    let surface = field.sample(uv.x, uv.y);
    if surface >= 1.0 {
        return RayHit {
            uv,
            height: 1.0,
            samples: 1,
        };
    }
    let mut crossing = linear_search(field, uv, 1.0, surface, offset, -1.0, steps);
    crossing.samples += 1;
    match method {
        ParallaxMethod::Steep => RayHit {
            uv: crossing.below_uv,
            height: crossing.below_ray,
            samples: crossing.samples,
        },
        ParallaxMethod::Relief => binary_refinement(field, &crossing, refinement_steps),
        _ => secant_steps_refinement(field, &crossing, refinement_steps),
    }
}

/// The sample count the shader uses at mip level 0 on a texture of `texture_size` texels:
/// T eq. 1 with N·V = `to_eye_ts.z`, capped by the texels the ray crosses.
pub fn view_steps(
    to_eye_ts: Vec3,
    height_scale: f32,
    texture_size: Vec2,
    min_samples: u32,
    max_samples: u32,
) -> u32 {
    let offset = ray_offset(to_eye_ts, height_scale);
    let texels = (offset * texture_size).length();
    march_steps(min_samples, max_samples, to_eye_ts.z, texels)
}

/// `hard_shadow` of march.wgsl: 0 if the height field blocks the light ray from `uv`, else 1.
/// `light_offset` is [`ray_offset`]`(to_light_ts, height_scale)`; `steps` span the ray from the
/// visible point to the top (the shader takes [`march_steps`] with the texels that part crosses).
pub fn hard_shadow(field: &HeightField, uv: Vec2, light_offset: Vec2, steps: u32) -> f32 {
    let start = field.sample(uv.x, uv.y) + HARD_SHADOW_BIAS;
    let rise = 1.0 - start;
    if rise <= 0.0 {
        return 1.0;
    }
    let crossing = linear_search(field, uv, start, start, light_offset * rise, rise, steps);
    if crossing.found { 0.0 } else { 1.0 }
}

/// `soft_shadow` of march.wgsl: Tatarchuk's seven weighted samples along the light ray, moved
/// `tap_shift` (−0.5..0.5, 0 for his places) of their spacing along it, as TAA's noise moves them.
pub fn soft_shadow(
    field: &HeightField,
    uv: Vec2,
    light_offset: Vec2,
    softening: f32,
    tap_shift: f32,
) -> f32 {
    let start = field.sample(uv.x, uv.y);
    let strongest = (0..7).fold(0.0_f32, |strongest, k| {
        let place = k as f32 + tap_shift;
        let fraction = 0.88 - 0.11 * place;
        let weight = (2.0 * place).max(1.0);
        let at = uv + light_offset * fraction;
        strongest.max((field.sample(at.x, at.y) - start - fraction) * weight)
    });
    let sharpness = SEED_SHADOW_SOFTENING * SEED_SHADOW_SOFTENING / softening.max(1e-4);
    (1.0 - strongest * sharpness).clamp(0.0, 1.0)
}

/// The soft shadow of many samples: `soft_shadow`'s seven at `shifts_per_spacing` evenly spaced
/// shifts together, the strongest of all of them winning (what the shifted samples of a pixel
/// reach between them as the shifts fill the spacing).
pub fn soft_shadow_many_taps(
    field: &HeightField,
    uv: Vec2,
    light_offset: Vec2,
    softening: f32,
    shifts_per_spacing: u32,
) -> f32 {
    let count = shifts_per_spacing.max(1);
    // The darkest visibility is the strongest blocker's: the clamp keeps the order.
    (0..count)
        .map(|i| {
            let shift = (i as f32 + 0.5) / count as f32 - 0.5;
            soft_shadow(field, uv, light_offset, softening, shift)
        })
        .fold(1.0_f32, f32::min)
}

/// Distance, in texels, between `method`'s answer at `steps` samples and the exact
/// intersection at each entry point of a `grid`×`grid` grid (row by row), for a view `angle`
/// degrees from the normal along +u. MaxMip walks one pyramid built for the whole grid.
pub fn errors_in_texels(
    field: &HeightField,
    method: ParallaxMethod,
    angle_degrees: f32,
    height_scale: f32,
    steps: u32,
    grid: u32,
) -> Vec<f32> {
    let angle = angle_degrees.to_radians();
    // Looking along +u, as the preview camera at azimuth 0 does: the eye is on the −u side.
    let to_eye_ts = Vec3::new(-angle.sin(), 0.0, angle.cos());
    let (width, height) = field.size();
    let size = Vec2::new(width as f32, height as f32);
    let pyramid = (method == ParallaxMethod::MaxMip).then(|| MaxPyramid::new(field));
    (0..grid)
        .flat_map(|y| (0..grid).map(move |x| (Vec2::new(x as f32, y as f32) + 0.5) / grid as f32))
        .map(|uv| {
            let approximate = match &pyramid {
                Some(pyramid) => march_max_mip(pyramid, uv, to_eye_ts, height_scale),
                None => march_view(field, method, uv, to_eye_ts, height_scale, steps),
            };
            let exact = exact_intersection(field, uv, to_eye_ts, height_scale);
            ((approximate.uv - exact) * size).length()
        })
        .collect()
}

/// The mean of [`errors_in_texels`].
pub fn mean_error_in_texels(
    field: &HeightField,
    method: ParallaxMethod,
    angle_degrees: f32,
    height_scale: f32,
    steps: u32,
    grid: u32,
) -> f32 {
    let errors = errors_in_texels(field, method, angle_degrees, height_scale, steps, grid);
    errors.iter().sum::<f32>() / errors.len() as f32
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The constants this reference shares with march.wgsl, max_mip.wgsl and triplanar.wgsl have the same
    /// values in both.
    #[test]
    fn constants_match_their_wgsl_twins() {
        let source = crate::parallax::PARALLAX_SHADER.source();
        for declaration in [
            format!("const MAX_PARALLAX_RATIO: f32 = {MAX_PARALLAX_RATIO:?};"),
            format!("const HARD_SHADOW_BIAS: f32 = {HARD_SHADOW_BIAS:?};"),
            format!("const SEED_SHADOW_SOFTENING: f32 = {SEED_SHADOW_SOFTENING:?};"),
            format!("const MAX_MIP_STEPS: u32 = {}u;", max_mip::MAX_MIP_STEPS),
            format!("const MAX_MIP_TOUCH: f32 = {:?};", max_mip::MAX_MIP_TOUCH),
            format!("const TRIPLANAR_MIN_SHARE: f32 = {TRIPLANAR_MIN_SHARE:?};"),
        ] {
            assert!(source.contains(&declaration), "WGSL lacks `{declaration}`");
        }
    }
    use crate::patterns;

    #[test]
    fn a_flat_floor_is_hit_exactly_by_every_marching_method() {
        let floor = HeightField::new(4, 4, vec![0.0; 16]).unwrap();
        let to_eye = Vec3::new(-0.6, 0.0, 0.8);
        let expected = Vec2::new(0.5, 0.5) - ray_offset(to_eye, 0.1);
        for method in [
            ParallaxMethod::Steep,
            ParallaxMethod::Occlusion,
            ParallaxMethod::Relief,
        ] {
            let hit = march_view(&floor, method, Vec2::splat(0.5), to_eye, 0.1, 8);
            // Bisection narrows the last step (1/8 of the offset) 2^6 times, no further.
            let tolerance = if matches!(method, ParallaxMethod::Relief) {
                1e-3
            } else {
                1e-5
            };
            assert!(
                (hit.uv - expected).length() < tolerance,
                "{method:?}: {:?}",
                hit.uv
            );
            assert!(hit.height < 0.01);
        }
        assert!(
            (exact_intersection(&floor, Vec2::splat(0.5), to_eye, 0.1) - expected).length() < 1e-5
        );
    }

    #[test]
    fn the_offset_is_capped_at_grazing_angles_and_finite_below_the_horizon() {
        for z in [1e-9, 0.0, -0.5] {
            let offset = ray_offset(Vec3::new(1.0, 0.0, z), 0.05);
            assert!(offset.is_finite());
            assert!((offset.length() - MAX_PARALLAX_RATIO * 0.05).abs() < 1e-5);
        }
        assert_eq!(ray_offset(Vec3::Z, 0.05), Vec2::ZERO);
    }

    #[test]
    fn steps_follow_equation_one_and_the_texel_cap() {
        assert_eq!(march_steps(8, 50, 1.0, 1000.0), 8);
        assert_eq!(march_steps(8, 50, 0.0, 1000.0), 50);
        assert_eq!(march_steps(8, 50, 0.5, 1000.0), 29);
        assert_eq!(
            march_steps(8, 50, 0.0, 3.2),
            4,
            "a ray crossing 3.2 texels needs 4 steps"
        );
        assert_eq!(march_steps(8, 50, 1.0, 0.0), 1);
    }

    #[test]
    fn pom_beats_steep_at_equal_samples() {
        let cobbles = patterns::cobblestones(64, 4).quantized();
        for steps in [8, 16, 32] {
            let steep =
                mean_error_in_texels(&cobbles, ParallaxMethod::Steep, 60.0, 0.05, steps, 24);
            let pom =
                mean_error_in_texels(&cobbles, ParallaxMethod::Occlusion, 60.0, 0.05, steps, 24);
            assert!(pom < steep, "{steps} samples: POM {pom} vs steep {steep}");
        }
    }

    #[test]
    fn a_block_occludes_the_light_behind_it() {
        let block = patterns::raised_block(64, 0.5);
        // Light from −u at 45°: points just past the block's +u edge lie in its shadow.
        let light_offset = ray_offset(Vec3::new(-1.0, 0.0, 1.0).normalize(), 0.1);
        let behind = Vec2::new(0.78, 0.5);
        let in_front = Vec2::new(0.22, 0.5);
        assert_eq!(hard_shadow(&block, behind, light_offset, 32), 0.0);
        assert_eq!(hard_shadow(&block, in_front, light_offset, 32), 1.0);
        assert!(soft_shadow(&block, behind, light_offset, 0.58, 0.0) < 0.5);
        assert_eq!(soft_shadow(&block, in_front, light_offset, 0.58, 0.0), 1.0);
    }
}
