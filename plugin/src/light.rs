//! Light sources.

use crate::Color;

/// Light from infinitely far away (the sun), shining along its entity's −Z axis.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DirectionalLight {
    /// Colour, linear.
    pub color: Color,
    /// Brightness multiplier: radiance arriving on a surface facing the light.
    pub intensity: f32,
}

impl Default for DirectionalLight {
    fn default() -> Self {
        Self {
            color: Color::WHITE,
            intensity: 1.0,
        }
    }
}

/// Light from a point at its entity's position, falling off with the square of the distance
/// and smoothly reaching zero at `range`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PointLight {
    /// Colour, linear.
    pub color: Color,
    /// Brightness at a distance of one world unit.
    pub intensity: f32,
    /// Distance beyond which the light has no effect (`f32::INFINITY`: none, only the
    /// inverse-square falloff).
    pub range: f32,
}

impl Default for PointLight {
    fn default() -> Self {
        Self {
            color: Color::WHITE,
            intensity: 1.0,
            range: 20.0,
        }
    }
}

/// Light arriving equally from everywhere; a resource, one per app.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AmbientLight {
    /// Colour, linear.
    pub color: Color,
    /// Brightness multiplier.
    pub intensity: f32,
}

impl Default for AmbientLight {
    fn default() -> Self {
        Self {
            color: Color::WHITE,
            intensity: 0.05,
        }
    }
}
