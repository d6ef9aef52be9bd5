//! Height-based blending of up to four layers, the CPU reference of the layered parallax
//! material's blend: where weights overlap, the layer standing higher wins.
//!
//! Each layer scores its height plus its weight; with `k = contrast / (1 − contrast)`, a layer
//! scoring `d` below the best gets `weight × max(1 − k·d, 0)` of the mix. Contrast 0 (k = 0)
//! is the plain weighted average; as it nears 1 only the layers within a sliver of the best
//! score remain. The blended height is a weighted average of the layers' heights, so it never
//! rises above the highest of them: a pyramid of each texel's highest layer bounds it, as the
//! max-mip march needs. It is continuous in the heights and weights for any contrast below 1,
//! which the linear search and its refinement need. Four layers fit the lanes of a `Vec4`
//! (a `vec4` in WGSL), so a march step reads all heights with one fetch of a packed texture.

use glam::Vec4;

pub use crate::parallax::MAX_BLEND_CONTRAST;

/// Each layer's share of the mix at one point (the shares sum to 1), from the layers'
/// `heights` (0..1), their `weights` (≥ 0; layers beyond the material's count weigh 0) and the
/// blend `contrast` (0..=[`MAX_BLEND_CONTRAST`]). A layer of weight 0 never shows, however
/// high it stands; where every weight is 0 the first layer is the whole mix.
pub fn layer_shares(heights: Vec4, weights: Vec4, contrast: f32) -> Vec4 {
    let weights = weights.max(Vec4::ZERO);
    if weights.element_sum() <= 0.0 {
        return Vec4::X;
    }
    let contrast = contrast.clamp(0.0, MAX_BLEND_CONTRAST);
    let sharpness = contrast / (1.0 - contrast);
    let scores = heights + weights;
    // The best score among the layers that show at all.
    let shown = Vec4::select(weights.cmpgt(Vec4::ZERO), scores, Vec4::splat(f32::MIN));
    let best = shown.max_element();
    let shares = weights * (Vec4::ONE - sharpness * (Vec4::splat(best) - scores)).max(Vec4::ZERO);
    shares / shares.element_sum()
}

/// The blended height at one point: the layers' heights mixed by [`layer_shares`].
pub fn blended_height(heights: Vec4, weights: Vec4, contrast: f32) -> f32 {
    layer_shares(heights, weights, contrast).dot(heights)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn random_vec4(random: &mut impl FnMut() -> f32) -> Vec4 {
        Vec4::new(random(), random(), random(), random())
    }

    #[test]
    fn contrast_zero_is_the_weighted_average() {
        let mut random = crate::test_numbers::seeded(3);
        for _ in 0..1000 {
            let (heights, weights) = (random_vec4(&mut random), random_vec4(&mut random));
            let average = weights.dot(heights) / weights.element_sum();
            assert!((blended_height(heights, weights, 0.0) - average).abs() < 1e-6);
        }
    }

    #[test]
    fn at_high_contrast_the_layer_standing_higher_wins() {
        // Equal weights: the taller layer is the whole mix.
        let heights = Vec4::new(0.2, 0.9, 0.5, 0.0);
        let weights = Vec4::new(0.5, 0.5, 0.0, 0.0);
        assert_eq!(blended_height(heights, weights, MAX_BLEND_CONTRAST), 0.9);
        // A layer that stands lower but weighs enough more wins: 0.2 + 0.9 beats 0.9 + 0.1.
        let weights = Vec4::new(0.9, 0.1, 0.0, 0.0);
        assert_eq!(blended_height(heights, weights, MAX_BLEND_CONTRAST), 0.2);
        // In between, the loser still shows a little.
        let mid = blended_height(heights, Vec4::new(0.5, 0.5, 0.0, 0.0), 0.5);
        assert!(mid > 0.55 && mid < 0.9, "{mid}");
    }

    #[test]
    fn the_blend_stays_between_the_lowest_and_highest_layer_that_shows() {
        let mut random = crate::test_numbers::seeded(5);
        for _ in 0..5000 {
            let heights = random_vec4(&mut random);
            // Some layers weigh nothing.
            let weights = random_vec4(&mut random)
                * Vec4::select(
                    random_vec4(&mut random).cmpgt(Vec4::splat(0.3)),
                    Vec4::ONE,
                    Vec4::ZERO,
                );
            let contrast = random() * MAX_BLEND_CONTRAST;
            let shares = layer_shares(heights, weights, contrast);
            assert!((shares.element_sum() - 1.0).abs() < 1e-5, "{shares}");
            let shown = weights.cmpgt(Vec4::ZERO);
            if !shown.any() {
                assert_eq!(shares, Vec4::X);
                continue;
            }
            assert!(
                (0..4).all(|i| weights[i] > 0.0 || shares[i] == 0.0),
                "a layer of weight 0 shows: {shares} for {weights}"
            );
            let high = Vec4::select(shown, heights, Vec4::ZERO).max_element();
            let low = Vec4::select(shown, heights, Vec4::ONE).min_element();
            let blended = blended_height(heights, weights, contrast);
            assert!(blended <= high + 1e-6 && blended >= low - 1e-6, "{blended}");
        }
    }

    #[test]
    fn a_tall_layer_of_weight_zero_never_shows_and_no_weight_is_the_first_layer() {
        let heights = Vec4::new(0.1, 1.0, 0.3, 0.0);
        let weights = Vec4::new(0.4, 0.0, 0.6, 0.0);
        for contrast in [0.0, 0.5, MAX_BLEND_CONTRAST] {
            assert_eq!(layer_shares(heights, weights, contrast).y, 0.0);
        }
        assert_eq!(layer_shares(heights, Vec4::ZERO, 0.5), Vec4::X);
        assert_eq!(blended_height(heights, Vec4::ZERO, 0.5), 0.1);
    }

    #[test]
    fn the_blend_moves_smoothly_as_the_weights_ramp() {
        // One layer's top at 1 and the other's floor at 0, the weights ramping across: the
        // blended height changes by little between neighbouring points at any contrast < 1
        // (at 0.9 its steepest slope is about 300 per unit of weight; a jump would be ~1).
        let heights = Vec4::new(1.0, 0.0, 0.0, 0.0);
        for contrast in [0.0, 0.5, 0.9] {
            let mut last = None;
            for step in 0..=10_000 {
                let t = step as f32 / 10_000.0;
                let blended = blended_height(heights, Vec4::new(t, 1.0 - t, 0.0, 0.0), contrast);
                if let Some(last) = last {
                    let jump: f32 = blended - last;
                    assert!(jump.abs() < 0.05, "{contrast}: a jump of {jump} at {t}");
                }
                last = Some(blended);
            }
            assert_eq!(
                blended_height(heights, Vec4::new(0.0, 1.0, 0.0, 0.0), contrast),
                0.0
            );
            assert_eq!(
                blended_height(heights, Vec4::new(1.0, 0.0, 0.0, 0.0), contrast),
                1.0
            );
        }
    }
}
