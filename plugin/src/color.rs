//! Colours in linear light.

/// A colour in linear light with alpha; the renderer converts to sRGB only when writing pixels.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Color {
    /// Red, linear.
    pub r: f32,
    /// Green, linear.
    pub g: f32,
    /// Blue, linear.
    pub b: f32,
    /// Alpha (opacity).
    pub a: f32,
}

/// Opaque white: the colour that leaves what it multiplies unchanged.
impl Default for Color {
    fn default() -> Self {
        Self::WHITE
    }
}

// A colour reads and writes as the tuple (r, g, b, a), as `[f32; 4]` does: presets and glTF
// extras stay short.
impl serde::Serialize for Color {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        self.to_array().serialize(serializer)
    }
}

impl<'de> serde::Deserialize<'de> for Color {
    fn deserialize<D: serde::Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        let [r, g, b, a] = <[f32; 4]>::deserialize(deserializer)?;
        Ok(Self { r, g, b, a })
    }
}

impl Color {
    /// Opaque white.
    pub const WHITE: Self = Self::linear_rgb(1.0, 1.0, 1.0);
    /// Opaque black.
    pub const BLACK: Self = Self::linear_rgb(0.0, 0.0, 0.0);

    /// An opaque colour from linear components.
    pub const fn linear_rgb(r: f32, g: f32, b: f32) -> Self {
        Self { r, g, b, a: 1.0 }
    }

    /// An opaque colour from sRGB-encoded components in 0..=1 (what a colour picker shows).
    pub fn srgb(r: f32, g: f32, b: f32) -> Self {
        Self::linear_rgb(srgb_to_linear(r), srgb_to_linear(g), srgb_to_linear(b))
    }

    /// An opaque colour from 8-bit sRGB components.
    pub fn srgb_u8(r: u8, g: u8, b: u8) -> Self {
        Self::srgb(
            f32::from(r) / 255.0,
            f32::from(g) / 255.0,
            f32::from(b) / 255.0,
        )
    }

    /// The linear components as an array.
    pub fn to_array(self) -> [f32; 4] {
        [self.r, self.g, self.b, self.a]
    }
}

/// Decodes one sRGB-encoded channel (0..=1) to linear light.
pub fn srgb_to_linear(encoded: f32) -> f32 {
    if encoded <= 0.04045 {
        encoded / 12.92
    } else {
        ((encoded + 0.055) / 1.055).powf(2.4)
    }
}

/// Encodes one linear channel (0..=1) as sRGB.
pub fn linear_to_srgb(linear: f32) -> f32 {
    if linear <= 0.003_130_8 {
        linear * 12.92
    } else {
        1.055 * linear.powf(1.0 / 2.4) - 0.055
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn srgb_round_trips() {
        for i in 0..=255_u8 {
            let encoded = f32::from(i) / 255.0;
            let back = linear_to_srgb(srgb_to_linear(encoded));
            assert!((back - encoded).abs() < 1e-5, "{i}: {back}");
        }
    }
}
