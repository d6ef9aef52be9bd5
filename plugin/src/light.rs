//! Light sources, in the physical units glTF's `KHR_lights_punctual` uses: directional light
//! in lux, point and spot light in candela (world units are metres). The camera's
//! [`crate::Exposure`] maps them to the display; at its default a 100,000 lux sun (bright
//! daylight) lights a white surface facing it to 1.0.

use crate::Color;

/// Light from infinitely far away (the sun), shining along its entity's −Z axis.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DirectionalLight {
    /// Colour, linear.
    pub color: Color,
    /// Illuminance on a surface facing the light, in lux (bright sun ≈ 100,000; overcast
    /// day ≈ 1,000).
    pub intensity: f32,
}

impl Default for DirectionalLight {
    /// A bright sun, 100,000 lux.
    fn default() -> Self {
        Self {
            color: Color::WHITE,
            intensity: 100_000.0,
        }
    }
}

/// Light from a point at its entity's position, falling off with the square of the distance
/// and smoothly reaching zero at `range`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PointLight {
    /// Colour, linear.
    pub color: Color,
    /// Luminous intensity in candela: the illuminance in lux at one metre (a 60 W bulb ≈ 70).
    pub intensity: f32,
    /// Distance beyond which the light has no effect (`f32::INFINITY`: none, only the
    /// inverse-square falloff).
    pub range: f32,
}

impl Default for PointLight {
    /// 100,000 cd, reaching to 20 units: a floodlight, bright enough to see in daylight.
    fn default() -> Self {
        Self {
            color: Color::WHITE,
            intensity: 100_000.0,
            range: 20.0,
        }
    }
}

/// Light from a point at its entity's position into a cone along the entity's −Z axis
/// (`KHR_lights_punctual`'s spot): full inside `inner_angle`, fading to nothing at
/// `outer_angle`, and falling off with distance like a [`PointLight`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SpotLight {
    /// Colour, linear.
    pub color: Color,
    /// Luminous intensity in candela along the axis.
    pub intensity: f32,
    /// Distance beyond which the light has no effect (`f32::INFINITY`: none).
    pub range: f32,
    /// Half-angle in radians inside which the light is at full strength (0 ..= outer).
    pub inner_angle: f32,
    /// Half-angle in radians at which it reaches zero (0 < outer ≤ π/2).
    pub outer_angle: f32,
}

impl Default for SpotLight {
    /// glTF's default cone (inner 0, outer π/4), 100,000 cd, reaching to 20 units.
    fn default() -> Self {
        Self {
            color: Color::WHITE,
            intensity: 100_000.0,
            range: 20.0,
            inner_angle: 0.0,
            outer_angle: std::f32::consts::FRAC_PI_4,
        }
    }
}

impl SpotLight {
    /// The cone the renderer uses: outer clamped to (0, π/2], inner to [0, outer]; NaN as the
    /// defaults.
    pub fn sanitized_cone(&self) -> (f32, f32) {
        let default = Self::default();
        let outer = if self.outer_angle.is_finite() {
            self.outer_angle.clamp(1e-3, std::f32::consts::FRAC_PI_2)
        } else {
            default.outer_angle
        };
        let inner = if self.inner_angle.is_finite() {
            self.inner_angle.clamp(0.0, outer)
        } else {
            0.0
        };
        (inner, outer)
    }
}

/// The brightest a light may be: the largest component of its colour times its intensity at
/// most 2⁶⁴ (about 1.8e19, the square root of `f32::MAX`), so that the shading's products of
/// it (with the exposure, the BRDF, the falloff) stay within `f32` instead of turning into
/// infinity and NaN.
pub const MAX_LIGHT_OUTPUT: f32 = 18_446_744_073_709_551_616.0;

/// What is wrong with a light's linear `color` and `intensity`, naming the field, if anything:
/// each must be finite and ≥ 0, and their product at most [`MAX_LIGHT_OUTPUT`].
pub(crate) fn light_output_problem(
    color: [f32; 3],
    intensity: f32,
) -> Option<(&'static str, String)> {
    if color.iter().any(|c| !(c.is_finite() && *c >= 0.0)) {
        return Some(("color", format!("color {color:?} is not finite and ≥ 0")));
    }
    if !(intensity.is_finite() && intensity >= 0.0) {
        return Some((
            "intensity",
            format!("intensity {intensity:?} is not finite and ≥ 0"),
        ));
    }
    let brightest = color.iter().fold(0.0_f32, |max, c| max.max(*c));
    if f64::from(brightest) * f64::from(intensity) > f64::from(MAX_LIGHT_OUTPUT) {
        return Some((
            "intensity",
            format!(
                "color {color:?} × intensity {intensity:?} is over the limit of {MAX_LIGHT_OUTPUT:?}"
            ),
        ));
    }
    None
}

/// `color` and `intensity` brought within [`light_output_problem`]'s rules: a colour component
/// or intensity that is not finite or < 0 becomes 0; a product over [`MAX_LIGHT_OUTPUT`] scales
/// the larger of the two (brightest component or intensity) down to it.
pub(crate) fn clamped_light_output(color: [f32; 3], intensity: f32) -> ([f32; 3], f32) {
    let usable = |value: f32| {
        if value.is_finite() {
            value.max(0.0)
        } else {
            0.0
        }
    };
    let color = color.map(usable);
    let intensity = usable(intensity);
    let brightest = color.iter().fold(0.0_f32, |max, c| max.max(*c));
    let output = f64::from(brightest) * f64::from(intensity);
    if output <= f64::from(MAX_LIGHT_OUTPUT) {
        return (color, intensity);
    }
    // A hair under the limit, so that rounding back to f32 cannot land over it.
    let scale = f64::from(MAX_LIGHT_OUTPUT) / output * (1.0 - f64::from(f32::EPSILON));
    let scaled = |value: f32| (f64::from(value) * scale) as f32;
    if brightest > intensity {
        (color.map(scaled), intensity)
    } else {
        (color, scaled(intensity))
    }
}

/// Light arriving equally from everywhere (a sky); a resource, one per app.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AmbientLight {
    /// Colour, linear.
    pub color: Color,
    /// Illuminance it gives any surface, in lux.
    pub intensity: f32,
}

impl Default for AmbientLight {
    /// 5,000 lux: a dim sky, so that the side away from the sun is not black.
    fn default() -> Self {
        Self {
            color: Color::WHITE,
            intensity: 5_000.0,
        }
    }
}
