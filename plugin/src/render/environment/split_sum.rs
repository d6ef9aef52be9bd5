//! The split-sum table (Karis, "Real Shading in Unreal Engine 4", 2013): the GGX specular
//! lobe's directional albedo split into a scale and a bias of F0, at each N·V and perceptual
//! roughness, integrated here by importance sampling, so that the environment's specular is
//! `prefiltered radiance × (F0 · scale + bias)`, and `scale + bias` (the lobe's albedo at F0 = 1)
//! gives the energy compensation for multiple scattering (Fdez-Agüera 2019; Filament §5.3.4.7).
//!
//! Karis' analytic fit of the same table (his mobile `EnvBRDFApprox`) avoids the texture; the
//! tests measure how far it is from the table ([`analytic_fit`]) — too far at grazing angles on
//! rough metals for the furnace test, so the table is what the shaders read.

use std::sync::OnceLock;

use glam::Vec3;

/// Texels along each side of the table (N·V across, roughness down).
pub const SPLIT_SUM_SIZE: usize = 32;

/// GGX samples per texel.
const SAMPLES: u32 = 1024;

/// The i-th of `count` points of the Hammersley set on the unit square.
fn hammersley(i: u32, count: u32) -> (f32, f32) {
    (
        (i as f32 + 0.5) / count as f32,
        i.reverse_bits() as f32 * (1.0 / 4_294_967_296.0),
    )
}

/// A half vector around +Z distributed as GGX's normals of width `alpha`.
fn ggx_half_vector((u, v): (f32, f32), alpha: f32) -> Vec3 {
    let phi = std::f32::consts::TAU * u;
    let cos_theta = ((1.0 - v) / (1.0 + (alpha * alpha - 1.0) * v)).sqrt();
    let sin_theta = (1.0 - cos_theta * cos_theta).max(0.0).sqrt();
    Vec3::new(sin_theta * phi.cos(), sin_theta * phi.sin(), cos_theta)
}

/// Smith's masking for one direction, Schlick's form with Karis' k = α / 2 for image-based
/// light.
fn smith_schlick(n_dot: f32, alpha: f32) -> f32 {
    let k = alpha * 0.5;
    n_dot / (n_dot * (1.0 - k) + k)
}

/// The scale and bias of F0 at `n_dot_v` and perceptual `roughness`.
pub fn split_sum(n_dot_v: f32, roughness: f32) -> (f32, f32) {
    let n_dot_v = n_dot_v.clamp(1e-4, 1.0);
    let alpha = (roughness * roughness).max(1e-4);
    let view = Vec3::new((1.0 - n_dot_v * n_dot_v).sqrt(), 0.0, n_dot_v);
    let (mut scale, mut bias) = (0.0, 0.0);
    for i in 0..SAMPLES {
        let half = ggx_half_vector(hammersley(i, SAMPLES), alpha);
        let v_dot_h = view.dot(half);
        let light = 2.0 * v_dot_h * half - view;
        if light.z <= 0.0 || v_dot_h <= 0.0 {
            continue;
        }
        // Sampled with pdf D·(N·H) / (4 V·H): the estimator of ∫ f·(N·L) without F is
        // G · (V·H) / ((N·H)(N·V)).
        let visible = smith_schlick(n_dot_v, alpha) * smith_schlick(light.z, alpha) * v_dot_h
            / (half.z * n_dot_v);
        let fresnel = (1.0 - v_dot_h).powi(5);
        scale += (1.0 - fresnel) * visible;
        bias += fresnel * visible;
    }
    (scale / SAMPLES as f32, bias / SAMPLES as f32)
}

/// The table, row by row (roughness down, N·V across, each at its texel's centre), as RGBA:
/// scale, bias, 0, 1. Made once per process.
pub fn split_sum_table() -> &'static [[f32; 4]] {
    static TABLE: OnceLock<Vec<[f32; 4]>> = OnceLock::new();
    TABLE.get_or_init(|| {
        let centre = |i: usize| (i as f32 + 0.5) / SPLIT_SUM_SIZE as f32;
        (0..SPLIT_SUM_SIZE * SPLIT_SUM_SIZE)
            .map(|texel| {
                let (scale, bias) = split_sum(
                    centre(texel % SPLIT_SUM_SIZE),
                    centre(texel / SPLIT_SUM_SIZE),
                );
                [scale, bias, 0.0, 1.0]
            })
            .collect()
    })
}

/// Karis' analytic fit of the table ("Physically Based Shading on Mobile", 2014): scale and
/// bias at `n_dot_v` and perceptual `roughness`.
pub fn analytic_fit(n_dot_v: f32, roughness: f32) -> (f32, f32) {
    let c0 = [-1.0, -0.0275, -0.572, 0.022];
    let c1 = [1.0, 0.0425, 1.04, -0.04];
    let r: [f32; 4] = std::array::from_fn(|i| roughness * c0[i] + c1[i]);
    let a004 = (r[0] * r[0]).min((-9.28 * n_dot_v).exp2()) * r[0] + r[1];
    (-1.04 * a004 + r[2], 1.04 * a004 + r[3])
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The same integral by brute force over a grid of light directions (no importance
    /// sampling): an independent check of the table.
    fn split_sum_by_quadrature(n_dot_v: f32, roughness: f32) -> (f64, f64) {
        let alpha = f64::from(roughness * roughness);
        let n_dot_v = f64::from(n_dot_v);
        let view = [(1.0 - n_dot_v * n_dot_v).sqrt(), 0.0, n_dot_v];
        let (steps_theta, steps_phi) = (600, 600);
        let (mut scale, mut bias) = (0.0, 0.0);
        for t in 0..steps_theta {
            let theta = (t as f64 + 0.5) / steps_theta as f64 * std::f64::consts::FRAC_PI_2;
            for p in 0..steps_phi {
                let phi = (p as f64 + 0.5) / steps_phi as f64 * std::f64::consts::TAU;
                let light = [
                    theta.sin() * phi.cos(),
                    theta.sin() * phi.sin(),
                    theta.cos(),
                ];
                let half: Vec<f64> = (0..3).map(|i| view[i] + light[i]).collect();
                let length = half.iter().map(|h| h * h).sum::<f64>().sqrt();
                let half: Vec<f64> = half.iter().map(|h| h / length).collect();
                let n_dot_h = half[2];
                let v_dot_h: f64 = (0..3).map(|i| view[i] * half[i]).sum();
                let n_dot_l = light[2];
                let d = alpha * alpha
                    / (std::f64::consts::PI
                        * (n_dot_h * n_dot_h * (alpha * alpha - 1.0) + 1.0).powi(2));
                let k = alpha / 2.0;
                let g = n_dot_v / (n_dot_v * (1.0 - k) + k) * n_dot_l / (n_dot_l * (1.0 - k) + k);
                let brdf = d * g / (4.0 * n_dot_v * n_dot_l);
                let solid_angle = theta.sin()
                    * (std::f64::consts::FRAC_PI_2 / steps_theta as f64)
                    * (std::f64::consts::TAU / steps_phi as f64);
                let fresnel = (1.0 - v_dot_h).powi(5);
                scale += (1.0 - fresnel) * brdf * n_dot_l * solid_angle;
                bias += fresnel * brdf * n_dot_l * solid_angle;
            }
        }
        (scale, bias)
    }

    #[test]
    fn the_table_agrees_with_a_brute_force_integral() {
        for (n_dot_v, roughness) in [(0.9, 0.5), (0.5, 0.5), (0.2, 0.8), (0.7, 0.9), (0.3, 0.3)] {
            let (scale, bias) = split_sum(n_dot_v, roughness);
            let (expected_scale, expected_bias) = split_sum_by_quadrature(n_dot_v, roughness);
            assert!(
                (f64::from(scale) - expected_scale).abs() < 0.01
                    && (f64::from(bias) - expected_bias).abs() < 0.01,
                "at N·V {n_dot_v}, roughness {roughness}: table {scale} {bias}, \
                 quadrature {expected_scale} {expected_bias}"
            );
        }
    }

    #[test]
    fn a_smooth_mirror_reflects_everything_and_rough_metals_lose_energy() {
        let (scale, bias) = split_sum(1.0, 0.02);
        assert!((scale + bias - 1.0).abs() < 0.01, "{scale} {bias}");
        for row in split_sum_table() {
            assert!(
                row[0] >= 0.0 && row[1] >= 0.0 && row[0] + row[1] <= 1.001,
                "{row:?}"
            );
        }
        // The energy a single scattering loses at roughness 1 is what compensation restores.
        let (scale, bias) = split_sum(0.5, 1.0);
        assert!(scale + bias < 0.8, "{scale} {bias}");
    }

    /// Karis' fit against the table: its largest differences (and where), at F0 = 0.04 (a
    /// dielectric) and F0 = 1 (a white metal), over the table's texels.
    #[test]
    fn the_analytic_fit_is_measured_against_the_table() {
        let centre = |i: usize| (i as f32 + 0.5) / SPLIT_SUM_SIZE as f32;
        let worst = |f0: f32| {
            let mut worst = (0.0_f32, 0.0, 0.0);
            for (texel, row) in split_sum_table().iter().enumerate() {
                let (n_dot_v, roughness) = (
                    centre(texel % SPLIT_SUM_SIZE),
                    centre(texel / SPLIT_SUM_SIZE),
                );
                let (scale, bias) = analytic_fit(n_dot_v, roughness);
                let difference = (f0 * (scale - row[0]) + bias - row[1]).abs();
                if difference > worst.0 {
                    worst = (difference, n_dot_v, roughness);
                }
            }
            worst
        };
        let (dielectric, metal) = (worst(0.04), worst(1.0));
        println!(
            "Karis' fit against the table: largest difference {:.3} at F0 0.04 (N·V {:.2}, \
             roughness {:.2}), {:.3} at F0 1 (N·V {:.2}, roughness {:.2})",
            dielectric.0, dielectric.1, dielectric.2, metal.0, metal.1, metal.2
        );
        assert!(dielectric.0.is_finite() && metal.0.is_finite());
    }
}
