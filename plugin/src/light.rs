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
