//! How much of the scene's light a camera takes in: [`Exposure`], a component of the camera
//! entity (the default applies where it is missing). The lights carry it into the scene (the
//! scene target holds pre-exposed values); how exposed values become display values is
//! tonemapping's (`render/tonemapping/`).

use serde::{Deserialize, Serialize};

/// The camera's exposure in EV100: the exposure value at ISO 100 a physical camera would be
/// set to. The scene value `L` reaches the tonemapper as `L / (1.2 · 2^EV100)` (the saturation
/// based calibration of Lagarde & de Rousiers, "Moving Frostbite to PBR", §4.5).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Exposure {
    /// EV100; higher is darker, +1 halves the light.
    pub ev100: f32,
}

impl Exposure {
    /// 14.7 EV100 (bright daylight; "sunny 16" is 15): the exposure at which a 100,000 lux sun
    /// lights a white Lambertian surface facing it to exactly 1.0 before tonemapping
    /// (`100,000 / π / (1.2 · 2^EV100) = 1`). A glTF file with a real sun and one lit by the
    /// loader's default light (a 160,000 lux sun) both look right at it.
    pub const DEFAULT_EV100: f32 = 14.695_11;
    /// The range the command line, scripts and the sandbox accept.
    pub const RANGE: std::ops::RangeInclusive<f32> = -16.0..=24.0;

    /// The factor scene values are multiplied by before tonemapping.
    pub fn multiplier(self) -> f32 {
        let ev100 = if self.ev100.is_finite() {
            self.ev100.clamp(*Self::RANGE.start(), *Self::RANGE.end())
        } else {
            Self::DEFAULT_EV100
        };
        1.0 / (1.2 * ev100.exp2())
    }
}

impl Default for Exposure {
    fn default() -> Self {
        Self {
            ev100: Self::DEFAULT_EV100,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_default_exposure_shows_a_bright_sun_on_white_as_one() {
        let sun_on_white = 100_000.0 * std::f32::consts::FRAC_1_PI;
        assert!((sun_on_white * Exposure::default().multiplier() - 1.0).abs() < 1e-5);
        let darker = Exposure {
            ev100: 1.0 + Exposure::DEFAULT_EV100,
        };
        assert!((darker.multiplier() / Exposure::default().multiplier() - 0.5).abs() < 1e-6);
        // Out-of-range and non-finite values never reach the GPU as such.
        assert_eq!(
            Exposure { ev100: f32::NAN }.multiplier(),
            Exposure::default().multiplier()
        );
        assert!(Exposure { ev100: 1e9 }.multiplier() > 0.0);
    }
}
