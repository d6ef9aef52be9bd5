//! The default environment: Preetham, Shirley & Smits' analytic daylight sky ("A Practical
//! Analytic Model for Daylight", SIGGRAPH 1999), in absolute luminance (cd/m²), with its sun
//! where the scene's first directional light shines from. Chosen over Hosek–Wilkie and a
//! Bruneton-style atmosphere because it is a closed form of a few exponentials per direction
//! (the background evaluates it per pixel, the prefilter per cube texel) with its tables small
//! enough to read here, and it is in physical units, so it sits beside a sun given in lux
//! without a fudge factor. Its known weaknesses (too bright near the horizon at low sun, no
//! twilight) are outside the daylight a game's sky spends most of its time in; below the
//! horizon it fades to night (see [`SkyState::night_fade`]).
//!
//! This file computes what the GPU evaluates (`sky.wgsl`: the Perez coefficients and zenith
//! values for a turbidity and sun) and the same evaluation on the CPU, which the tests compare
//! with the GPU's and which integrates the ground's irradiance.

use glam::Vec3;

/// The sky model's settings.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sky {
    /// Atmospheric turbidity, 2 (very clear) to 10 (hazy); the model is fitted for 2 to 10.
    pub turbidity: f32,
    /// Albedo of the ground below the horizon, lit by the sky and the sun (0..1).
    pub ground_albedo: f32,
}

impl Default for Sky {
    /// A clear day (turbidity 3) over grey ground (albedo 0.2).
    fn default() -> Self {
        Self {
            turbidity: 3.0,
            ground_albedo: 0.2,
        }
    }
}

/// Where the sun is when no directional light gives it: 45° up, towards −Z and +X.
pub const DEFAULT_SUN: Vec3 = Vec3::new(0.5, std::f32::consts::FRAC_1_SQRT_2, -0.5);

/// The Perez function's five coefficients (A to E) for luminance Y and chromaticity x, y
/// (Preetham et al., appendix A.2), each a linear function of turbidity.
fn perez_coefficients(turbidity: f32) -> [[f32; 3]; 5] {
    let t = turbidity;
    [
        [
            0.1787 * t - 1.4630,
            -0.0193 * t - 0.2592,
            -0.0167 * t - 0.2608,
        ],
        [
            -0.3554 * t + 0.4275,
            -0.0665 * t + 0.0008,
            -0.0950 * t + 0.0092,
        ],
        [
            -0.0227 * t + 5.3251,
            -0.0004 * t + 0.2125,
            -0.0079 * t + 0.2102,
        ],
        [
            0.1206 * t - 2.5771,
            -0.0641 * t - 0.8989,
            -0.0441 * t - 1.6537,
        ],
        [
            -0.0670 * t + 0.3703,
            -0.0033 * t + 0.0452,
            -0.0109 * t + 0.0529,
        ],
    ]
}

/// The zenith's luminance (cd/m²) and chromaticity for the sun at zenith angle `theta_sun`
/// (Preetham et al., appendix A.2).
fn zenith(turbidity: f32, theta_sun: f32) -> [f32; 3] {
    let t = turbidity;
    let chi = (4.0 / 9.0 - t / 120.0) * (std::f32::consts::PI - 2.0 * theta_sun);
    // The paper's formula is in kcd/m².
    let luminance = ((4.0453 * t - 4.9710) * chi.tan() - 0.2155 * t + 2.4192) * 1000.0;
    let s = [theta_sun.powi(3), theta_sun.powi(2), theta_sun, 1.0];
    let dot = |row: [f32; 4]| row.iter().zip(s).map(|(a, b)| a * b).sum::<f32>();
    let x = t * t * dot([0.00166, -0.00375, 0.00209, 0.0])
        + t * dot([-0.02903, 0.06377, -0.03202, 0.00394])
        + dot([0.11693, -0.21196, 0.06052, 0.25886]);
    let y = t * t * dot([0.00275, -0.00610, 0.00317, 0.0])
        + t * dot([-0.04214, 0.08970, -0.04153, 0.00516])
        + dot([0.15346, -0.26756, 0.06670, 0.26688]);
    [luminance.max(0.0), x, y]
}

/// The sky for one sun position, as the GPU reads it (`SkyParams` in sky.wgsl).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct SkyParams {
    /// The Perez coefficients A to E, each for Y, x, y (w unused).
    pub perez: [[f32; 4]; 5],
    /// Zenith Y, x, y divided by the Perez function at the zenith (so that the formula's ratio
    /// is one multiplication), w: the night fade.
    pub zenith: [f32; 4],
    /// xyz: unit vector towards the sun.
    pub sun: [f32; 4],
    /// rgb: the ground's radiance, cd/m².
    pub ground: [f32; 4],
}

crate::wgsl_layout!(SkyParams {
    perez,
    zenith,
    sun,
    ground
});

/// A sky for one sun position: what [`SkyParams`] holds, evaluated on the CPU too.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SkyState {
    params: SkyParams,
}

/// The Perez function F(θ, γ) for each of Y, x, y.
fn perez(coefficients: &[[f32; 4]; 5], cos_theta: f32, gamma: f32) -> [f32; 3] {
    let [a, b, c, d, e] = coefficients;
    let cos_gamma = gamma.cos();
    std::array::from_fn(|i| {
        (1.0 + a[i] * (b[i] / cos_theta.max(0.01)).exp())
            * (1.0 + c[i] * (d[i] * gamma).exp() + e[i] * cos_gamma * cos_gamma)
    })
}

/// Luminance Y and chromaticity x, y (CIE xyY, in Perez's order) to linear sRGB (Rec. 709
/// primaries, D65).
fn yxy_to_linear_srgb([luminance, x, y]: [f32; 3]) -> Vec3 {
    let y = y.max(1e-4);
    let big_x = x * luminance / y;
    let big_z = (1.0 - x - y) * luminance / y;
    Vec3::new(
        3.240_454 * big_x - 1.537_139 * luminance - 0.498_531 * big_z,
        -0.969_266 * big_x + 1.876_011 * luminance + 0.041_556 * big_z,
        0.055_643 * big_x - 0.204_026 * luminance + 1.057_225 * big_z,
    )
    .max(Vec3::ZERO)
}

impl SkyState {
    /// `sky` with the sun towards `sun` (normalized; a zero vector puts it at
    /// [`DEFAULT_SUN`]), whose light also falls on the ground: `sun_illuminance` lux on a
    /// surface facing it (0 where no light stands for the sun).
    pub fn new(sky: Sky, sun: Vec3, sun_illuminance: f32) -> Self {
        let sun = sun.try_normalize().unwrap_or(DEFAULT_SUN.normalize());
        let turbidity = if sky.turbidity.is_finite() {
            sky.turbidity.clamp(1.7, 10.0)
        } else {
            Sky::default().turbidity
        };
        // Below the horizon the model does not hold: it is evaluated for the sun on the horizon
        // and faded out over the first 6° of dusk (civil twilight's depth).
        let elevation = sun.y.clamp(-1.0, 1.0).asin();
        let night_fade = (1.0 + elevation / 6f32.to_radians())
            .clamp(0.0, 1.0)
            .powi(2);
        let theta_sun = (std::f32::consts::FRAC_PI_2 - elevation).min(std::f32::consts::FRAC_PI_2);
        let coefficients = perez_coefficients(turbidity);
        let perez4 = coefficients.map(|[y, x, yy]| [y, x, yy, 0.0]);
        let at_zenith = perez(&perez4, 1.0, theta_sun);
        let zenith = zenith(turbidity, theta_sun);
        let mut params = SkyParams {
            perez: perez4,
            zenith: [
                zenith[0] / at_zenith[0],
                zenith[1] / at_zenith[1],
                zenith[2] / at_zenith[2],
                night_fade,
            ],
            sun: sun.extend(0.0).into(),
            ground: [0.0; 4],
        };
        let mut state = Self { params };
        let albedo = if sky.ground_albedo.is_finite() {
            sky.ground_albedo.clamp(0.0, 1.0)
        } else {
            Sky::default().ground_albedo
        };
        let sun_on_ground = sun_illuminance.max(0.0) * sun.y.max(0.0);
        let ground = (state.sky_irradiance() + Vec3::splat(sun_on_ground))
            * albedo
            * std::f32::consts::FRAC_1_PI;
        params.ground = ground.extend(0.0).into();
        state.params = params;
        state
    }

    /// What the GPU reads.
    pub fn params(&self) -> SkyParams {
        self.params
    }

    /// How much of the daylight sky is left: 1 with the sun above the horizon, falling to 0
    /// when it is 6° below.
    pub fn night_fade(&self) -> f32 {
        self.params.zenith[3]
    }

    /// The radiance (linear sRGB, cd/m²) seen looking along the unit vector `direction`: the
    /// sky above the horizon, the ground below it.
    pub fn radiance(&self, direction: Vec3) -> Vec3 {
        if direction.y < 0.0 {
            return Vec3::from_slice(&self.params.ground[..3]);
        }
        let sun = Vec3::from_slice(&self.params.sun[..3]);
        let gamma = direction.dot(sun).clamp(-1.0, 1.0).acos();
        let f = perez(&self.params.perez, direction.y, gamma);
        let zenith = self.params.zenith;
        yxy_to_linear_srgb([zenith[0] * f[0], zenith[1] * f[1], zenith[2] * f[2]]) * zenith[3]
    }

    /// The sky's illuminance on a horizontal surface (lux), integrated over the upper
    /// hemisphere (the sun's own disc is the directional light's, not the sky's).
    pub fn sky_irradiance(&self) -> Vec3 {
        const RINGS: usize = 32;
        const SEGMENTS: usize = 64;
        let mut sum = Vec3::ZERO;
        for ring in 0..RINGS {
            // Equal steps of cos θ: each ring has the same solid angle.
            let cos_theta = (ring as f32 + 0.5) / RINGS as f32;
            let sin_theta = (1.0 - cos_theta * cos_theta).sqrt();
            for segment in 0..SEGMENTS {
                let phi = (segment as f32 + 0.5) / SEGMENTS as f32 * std::f32::consts::TAU;
                let direction = Vec3::new(sin_theta * phi.cos(), cos_theta, sin_theta * phi.sin());
                sum += self.radiance(direction) * cos_theta;
            }
        }
        sum * (std::f32::consts::TAU / (RINGS * SEGMENTS) as f32)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn luminance(rgb: Vec3) -> f32 {
        rgb.dot(Vec3::new(0.2126, 0.7152, 0.0722))
    }

    #[test]
    fn the_zenith_of_a_clear_sky_at_a_high_sun_is_a_few_thousand_nits() {
        // Preetham et al. fig. 4 and measured clear skies: a few kcd/m² at the zenith.
        let sky = SkyState::new(Sky::default(), Vec3::new(0.0, 0.9, -0.43), 100_000.0);
        let zenith = luminance(sky.radiance(Vec3::Y));
        assert!((2_000.0..15_000.0).contains(&zenith), "{zenith}");
        // Clear-sky horizontal illuminance with the sun high: 10 to 30 klux (CIE 110-1994).
        let horizontal = luminance(sky.sky_irradiance());
        assert!((8_000.0..35_000.0).contains(&horizontal), "{horizontal}");
    }

    #[test]
    fn the_sky_is_brighter_towards_the_sun_and_blue_away_from_it() {
        let sun = Vec3::new(0.0, 0.5, -0.866);
        let sky = SkyState::new(Sky::default(), sun, 100_000.0);
        let near_sun = sky.radiance((sun + Vec3::new(0.0, 0.1, 0.0)).normalize());
        let away = sky.radiance(Vec3::new(0.0, 0.5, 0.866));
        assert!(luminance(near_sun) > 2.0 * luminance(away));
        assert!(away.z > away.x, "{away}");
    }

    #[test]
    fn the_sky_fades_to_night_below_the_horizon_and_stays_finite() {
        let dusk = SkyState::new(Sky::default(), Vec3::new(0.0, -0.2, -1.0), 0.0);
        assert_eq!(dusk.night_fade(), 0.0);
        assert_eq!(dusk.radiance(Vec3::Y), Vec3::ZERO);
        for sky in [
            Sky {
                turbidity: f32::NAN,
                ground_albedo: f32::INFINITY,
            },
            Sky {
                turbidity: 100.0,
                ground_albedo: -1.0,
            },
        ] {
            let state = SkyState::new(sky, Vec3::ZERO, f32::NAN);
            for direction in [Vec3::Y, Vec3::X, Vec3::NEG_Y, Vec3::new(0.0, 1e-6, 1.0)] {
                assert!(state.radiance(direction).is_finite(), "{sky:?} {direction}");
            }
        }
    }

    #[test]
    fn the_ground_reflects_its_albedo_of_the_sky_and_the_sun() {
        let sun = Vec3::new(0.0, 1.0, 0.0);
        let sky = SkyState::new(Sky::default(), sun, 100_000.0);
        let ground = luminance(sky.radiance(Vec3::NEG_Y));
        let expected = (luminance(sky.sky_irradiance()) + 100_000.0) * 0.2 / std::f32::consts::PI;
        assert!(
            (ground - expected).abs() < 1e-3 * expected,
            "{ground} {expected}"
        );
    }
}
