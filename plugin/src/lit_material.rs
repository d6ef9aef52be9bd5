//! The lit, normal-mapped material every mesh without a POM material is drawn with.

use crate::{Color, Handle, Image};

/// A Blinn-Phong material with an optional colour texture and normal map.
///
/// Put it on an entity with a `Handle<Mesh>` and a [`crate::Transform`]; a mesh entity without a
/// material is drawn with `LitMaterial::default()`.
#[derive(Clone, Debug, PartialEq)]
pub struct LitMaterial {
    /// Colour multiplied with the texture, linear.
    pub base_color: Color,
    /// sRGB colour texture (white when absent).
    pub base_color_texture: Option<Handle<Image>>,
    /// Tangent-space normal map, OpenGL convention (green up the image); flat when absent.
    pub normal_map: Option<Handle<Image>>,
    /// Scales the normal map's XY tilt: 0 = flat, 1 = as authored.
    pub normal_strength: f32,
    /// Weight of the specular highlight.
    pub specular_strength: f32,
    /// Blinn-Phong exponent: higher = smaller, sharper highlight (clamped to ≥ 1).
    pub shininess: f32,
}

impl Default for LitMaterial {
    fn default() -> Self {
        Self {
            base_color: Color::WHITE,
            base_color_texture: None,
            normal_map: None,
            normal_strength: 1.0,
            specular_strength: 0.25,
            shininess: 32.0,
        }
    }
}

impl LitMaterial {
    /// A material of one colour.
    pub fn from_color(base_color: Color) -> Self {
        Self {
            base_color,
            ..Self::default()
        }
    }
}
