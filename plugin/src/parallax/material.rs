//! `ParallaxOcclusionMaterial`: the artist-facing parameters, their defaults and validation.

use crate::{Color, Handle, Image};

/// How the ray/height-field intersection is found. One march serves every method; they differ in
/// how many samples they take and how they refine the crossing.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
pub enum ParallaxMethod {
    /// No parallax: the texture coordinate is used as is (normal mapping only).
    NormalMapping,
    /// One height sample, shifted along the view with offset limiting (Welsh 2004): cheap,
    /// right for shallow, low-frequency relief only.
    ParallaxOffset,
    /// Steep parallax (McGuire & McGuire 2005): linear search, shading at the first sample below
    /// the surface. Shows layers at grazing angles.
    Steep,
    /// Parallax occlusion mapping (Tatarchuk 2006): linear search, then the intersection of the
    /// ray with the piecewise-linear height profile between the last two samples.
    Occlusion,
    /// Relief mapping (Policarpo et al. 2005): linear search, then `binary_steps` bisections.
    Relief {
        /// Bisection steps after the linear search (1..=16).
        binary_steps: u32,
    },
}

/// Self-shadowing of the height field.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
pub enum ShadowMode {
    /// No self-shadowing.
    Off,
    /// March towards the light; any blocker makes the point fully dark (McGuire).
    Hard,
    /// Tatarchuk's penumbra estimate from weighted height samples along the light ray.
    Soft,
}

/// What the height texture's values mean.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
pub enum HeightConvention {
    /// White is the top (the polygon's surface), black the deepest point: Tatarchuk's convention.
    Height,
    /// White is the deepest point: LearnOpenGL's and Bevy's depth maps.
    Depth,
}

/// Where the height comes from.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub enum HeightSource {
    /// A texture of its own; the red channel is read (grey images have it in every channel).
    Texture(Handle<Image>),
    /// The alpha channel of the normal map, as McGuire and Tatarchuk pack it.
    NormalMapAlpha,
}

/// The unit of [`ParallaxOcclusionMaterial::height_scale`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
pub enum HeightUnits {
    /// Texture-coordinate units, Tatarchuk's fHeightMapRange: the depth changes when the UVs are
    /// tiled differently or the object is scaled.
    Texture,
    /// World units (Luna §3): converted per pixel with the surface's UVs per world unit, so the
    /// depth stays the same under any tiling or object scale.
    World,
}

/// The lighting model.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
pub enum LightingModel {
    /// Phong, as in Tatarchuk's listing: highlight around the mirrored view ray.
    Phong,
    /// Blinn-Phong: highlight around the half vector.
    BlinnPhong,
    /// Cook-Torrance (GGX) specular over Oren-Nayar diffuse, driven by roughness and metallic.
    CookTorrance,
}

/// What the fragment shader outputs instead of the lit colour, for inspection.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
pub enum DebugView {
    /// The lit surface.
    None,
    /// Tatarchuk's LOD tint: lit colour, blue growing through the transition band, deepest blue
    /// where only normal mapping runs.
    Lod,
    /// The mip level as grey: black = level 0, white = the smallest level.
    Mip,
    /// March samples taken, as a heat map from black (none) through red and yellow to white
    /// (`max_samples`).
    Samples,
    /// Raw values: R = fract(u), G = fract(v) of the final texture coordinate; B = 1 where the
    /// full march ran, 0.5 in the LOD band, 0 where only normal mapping ran.
    Uv,
    /// The self-shadowing visibility of the first light (1 = lit), raw, in R, G and B.
    Shadow,
    /// The shading normal in tangent space, encoded as `n × 0.5 + 0.5`.
    Normal,
}

/// Most height samples one march may take; larger `max_samples` are clamped to it.
pub const MAX_SAMPLES_LIMIT: u32 = 256;

/// A surface that looks displaced: Tatarchuk's parallax occlusion mapping with soft
/// self-shadows and per-pixel LOD. Put it on an entity with a `Handle<Mesh>` and a transform.
///
/// Defaults are the seed's: samples 8..50, LOD threshold 4, soft shadows with softening 0.58.
/// The height field is pushed *down* from the polygon: the brightest height is at the surface.
#[derive(Clone, Debug, PartialEq)]
pub struct ParallaxOcclusionMaterial {
    /// Colour multiplied with the texture, linear. Default white.
    pub base_color: Color,
    /// sRGB colour texture, sampled at the displaced coordinate (white when absent).
    pub base_color_texture: Option<Handle<Image>>,
    /// Tangent-space normal map (OpenGL convention), sampled at the displaced coordinate; flat
    /// when absent.
    pub normal_map: Option<Handle<Image>>,
    /// Where the height field comes from; `None` means flat (no parallax).
    pub height_map: Option<HeightSource>,
    /// Whether white is high (height) or deep (depth). Default: height.
    pub height_convention: HeightConvention,
    /// Depth of the height field from white to black, in [`Self::height_units`]. Tatarchuk's
    /// fHeightMapRange; default 0.05 texture units.
    pub height_scale: f32,
    /// Unit of `height_scale`. Default: texture units.
    pub height_units: HeightUnits,
    /// Samples when looking straight at the surface (T eq. 1's n_min). Default 8.
    pub min_samples: u32,
    /// Samples at grazing angles (T eq. 1's n_max). Default 50; at most [`MAX_SAMPLES_LIMIT`].
    pub max_samples: u32,
    /// Mip level past which only normal mapping runs (T's nLODThreshold). Default 4.
    pub lod_threshold: f32,
    /// Width in mip levels of the band below the threshold where parallax fades out. Default 1.
    pub lod_band: f32,
    /// Self-shadowing. Default soft.
    pub shadows: ShadowMode,
    /// Penumbra width of soft shadows: larger is softer. Default 0.58 reproduces Tatarchuk's
    /// fShadowSoftening = 0.58 (whose own scale ran the other way).
    pub shadow_softening: f32,
    /// The intersection method. Default POM.
    pub method: ParallaxMethod,
    /// Write the depth of the displaced point, so other geometry intersects the relief
    /// correctly (costs early depth testing). Default off.
    pub depth_offset: bool,
    /// Lighting model. Default Phong, as in Tatarchuk's listing.
    pub lighting: LightingModel,
    /// Phong / Blinn-Phong highlight weight. Default 0.3.
    pub specular_strength: f32,
    /// Phong / Blinn-Phong exponent (≥ 1). Default 32.
    pub shininess: f32,
    /// Cook-Torrance / Oren-Nayar roughness, 0..1. Default 0.6.
    pub roughness: f32,
    /// Cook-Torrance metalness, 0..1. Default 0.
    pub metallic: f32,
    /// Scales the normal map's tilt: 0 = flat, 1 = as authored. Default 1.
    pub normal_strength: f32,
    /// Output an inspection view instead of the lit colour. Default none.
    pub debug_view: DebugView,
}

impl Default for ParallaxOcclusionMaterial {
    fn default() -> Self {
        Self {
            base_color: Color::WHITE,
            base_color_texture: None,
            normal_map: None,
            height_map: None,
            height_convention: HeightConvention::Height,
            height_scale: 0.05,
            height_units: HeightUnits::Texture,
            min_samples: 8,
            max_samples: 50,
            lod_threshold: 4.0,
            lod_band: 1.0,
            shadows: ShadowMode::Soft,
            shadow_softening: 0.58,
            method: ParallaxMethod::Occlusion,
            depth_offset: false,
            lighting: LightingModel::Phong,
            specular_strength: 0.3,
            shininess: 32.0,
            roughness: 0.6,
            metallic: 0.0,
            normal_strength: 1.0,
            debug_view: DebugView::None,
        }
    }
}

/// A parameter of [`ParallaxOcclusionMaterial`] that is out of range.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum PomMaterialError {
    /// A number is NaN or infinite.
    #[error("{field} is {value}, which is not a finite number")]
    NotFinite {
        /// The field.
        field: &'static str,
        /// Its value.
        value: f32,
    },
    /// A number is below its minimum.
    #[error("{field} is {value} but must be at least {min}")]
    TooSmall {
        /// The field.
        field: &'static str,
        /// Its value.
        value: f32,
        /// The smallest allowed value.
        min: f32,
    },
    /// A number is above its maximum.
    #[error("{field} is {value} but must be at most {max}")]
    TooLarge {
        /// The field.
        field: &'static str,
        /// Its value.
        value: f32,
        /// The largest allowed value.
        max: f32,
    },
    /// The sample bounds are inverted.
    #[error("min_samples ({min}) is greater than max_samples ({max})")]
    SamplesInverted {
        /// min_samples.
        min: u32,
        /// max_samples.
        max: u32,
    },
}

struct Range {
    field: &'static str,
    min: f32,
    max: f32,
    fallback: f32,
}

impl Range {
    fn check(&self, value: f32) -> Result<(), PomMaterialError> {
        if !value.is_finite() {
            Err(PomMaterialError::NotFinite {
                field: self.field,
                value,
            })
        } else if value < self.min {
            Err(PomMaterialError::TooSmall {
                field: self.field,
                value,
                min: self.min,
            })
        } else if value > self.max {
            Err(PomMaterialError::TooLarge {
                field: self.field,
                value,
                max: self.max,
            })
        } else {
            Ok(())
        }
    }

    fn clamp(&self, value: f32) -> f32 {
        if value.is_finite() {
            value.clamp(self.min, self.max)
        } else {
            self.fallback
        }
    }
}

const HEIGHT_SCALE: Range = Range {
    field: "height_scale",
    min: 0.0,
    max: 10.0,
    fallback: 0.05,
};
const LOD_THRESHOLD: Range = Range {
    field: "lod_threshold",
    min: 0.0,
    max: 16.0,
    fallback: 4.0,
};
const LOD_BAND: Range = Range {
    field: "lod_band",
    min: 0.01,
    max: 16.0,
    fallback: 1.0,
};
const SHADOW_SOFTENING: Range = Range {
    field: "shadow_softening",
    min: 0.01,
    max: 100.0,
    fallback: 0.58,
};
const SPECULAR_STRENGTH: Range = Range {
    field: "specular_strength",
    min: 0.0,
    max: 100.0,
    fallback: 0.3,
};
const SHININESS: Range = Range {
    field: "shininess",
    min: 1.0,
    max: 10_000.0,
    fallback: 32.0,
};
const ROUGHNESS: Range = Range {
    field: "roughness",
    min: 0.0,
    max: 1.0,
    fallback: 0.6,
};
const METALLIC: Range = Range {
    field: "metallic",
    min: 0.0,
    max: 1.0,
    fallback: 0.0,
};
const NORMAL_STRENGTH: Range = Range {
    field: "normal_strength",
    min: 0.0,
    max: 100.0,
    fallback: 1.0,
};

impl ParallaxOcclusionMaterial {
    fn ranges(&self) -> [(&'static Range, f32); 9] {
        [
            (&HEIGHT_SCALE, self.height_scale),
            (&LOD_THRESHOLD, self.lod_threshold),
            (&LOD_BAND, self.lod_band),
            (&SHADOW_SOFTENING, self.shadow_softening),
            (&SPECULAR_STRENGTH, self.specular_strength),
            (&SHININESS, self.shininess),
            (&ROUGHNESS, self.roughness),
            (&METALLIC, self.metallic),
            (&NORMAL_STRENGTH, self.normal_strength),
        ]
    }

    /// Every parameter problem, in field order; empty when the material is valid.
    pub fn problems(&self) -> Vec<PomMaterialError> {
        let mut problems: Vec<PomMaterialError> = self
            .ranges()
            .iter()
            .filter_map(|(range, value)| range.check(*value).err())
            .collect();
        if self.min_samples == 0 {
            problems.push(PomMaterialError::TooSmall {
                field: "min_samples",
                value: 0.0,
                min: 1.0,
            });
        }
        if self.max_samples > MAX_SAMPLES_LIMIT {
            problems.push(PomMaterialError::TooLarge {
                field: "max_samples",
                value: self.max_samples as f32,
                max: MAX_SAMPLES_LIMIT as f32,
            });
        }
        if self.min_samples > self.max_samples {
            problems.push(PomMaterialError::SamplesInverted {
                min: self.min_samples,
                max: self.max_samples,
            });
        }
        if let ParallaxMethod::Relief { binary_steps } = self.method
            && !(1..=16).contains(&binary_steps)
        {
            problems.push(PomMaterialError::TooLarge {
                field: "method.binary_steps",
                value: binary_steps as f32,
                max: 16.0,
            });
        }
        for (field, color) in [("base_color", self.base_color)] {
            if let Some(value) = color.to_array().into_iter().find(|c| !c.is_finite()) {
                problems.push(PomMaterialError::NotFinite { field, value });
            }
        }
        problems
    }

    /// Checks every parameter; the first problem is the error.
    ///
    /// # Example
    /// ```
    /// let mut material = pom::ParallaxOcclusionMaterial::default();
    /// assert!(material.validate().is_ok());
    /// material.min_samples = 60;
    /// assert_eq!(
    ///     material.validate().unwrap_err().to_string(),
    ///     "min_samples (60) is greater than max_samples (50)"
    /// );
    /// ```
    pub fn validate(&self) -> Result<(), PomMaterialError> {
        match self.problems().into_iter().next() {
            Some(problem) => Err(problem),
            None => Ok(()),
        }
    }

    /// A copy with every parameter brought into range: NaN and ∞ become the default, numbers are
    /// clamped to their limits, zero samples become 1, inverted sample bounds are swapped. This
    /// is what the renderer draws; it logs [`Self::problems`] once per change.
    pub fn sanitized(&self) -> Self {
        let mut clean = self.clone();
        clean.height_scale = HEIGHT_SCALE.clamp(self.height_scale);
        clean.lod_threshold = LOD_THRESHOLD.clamp(self.lod_threshold);
        clean.lod_band = LOD_BAND.clamp(self.lod_band);
        clean.shadow_softening = SHADOW_SOFTENING.clamp(self.shadow_softening);
        clean.specular_strength = SPECULAR_STRENGTH.clamp(self.specular_strength);
        clean.shininess = SHININESS.clamp(self.shininess);
        clean.roughness = ROUGHNESS.clamp(self.roughness);
        clean.metallic = METALLIC.clamp(self.metallic);
        clean.normal_strength = NORMAL_STRENGTH.clamp(self.normal_strength);
        let min = self.min_samples.clamp(1, MAX_SAMPLES_LIMIT);
        let max = self.max_samples.clamp(1, MAX_SAMPLES_LIMIT);
        (clean.min_samples, clean.max_samples) = (min.min(max), min.max(max));
        if let ParallaxMethod::Relief { binary_steps } = self.method {
            clean.method = ParallaxMethod::Relief {
                binary_steps: binary_steps.clamp(1, 16),
            };
        }
        let finite_or =
            |value: f32, fallback: f32| if value.is_finite() { value } else { fallback };
        clean.base_color = Color {
            r: finite_or(self.base_color.r, 1.0),
            g: finite_or(self.base_color.g, 1.0),
            b: finite_or(self.base_color.b, 1.0),
            a: finite_or(self.base_color.a, 1.0),
        };
        clean
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn defaults_are_valid_and_the_seeds() {
        let material = ParallaxOcclusionMaterial::default();
        assert_eq!(material.validate(), Ok(()));
        assert_eq!((material.min_samples, material.max_samples), (8, 50));
        assert_eq!(material.lod_threshold, 4.0);
        assert_eq!(material.sanitized(), material);
    }

    #[test]
    fn each_bad_value_is_named_and_sanitized() {
        let bad = ParallaxOcclusionMaterial {
            height_scale: f32::NAN,
            lod_band: f32::INFINITY,
            shadow_softening: -1.0,
            min_samples: 0,
            max_samples: 1_000_000,
            roughness: 7.0,
            ..ParallaxOcclusionMaterial::default()
        };
        let messages: Vec<String> = bad.problems().iter().map(ToString::to_string).collect();
        assert_eq!(
            messages,
            [
                "height_scale is NaN, which is not a finite number",
                "lod_band is inf, which is not a finite number",
                "shadow_softening is -1 but must be at least 0.01",
                "roughness is 7 but must be at most 1",
                "min_samples is 0 but must be at least 1",
                "max_samples is 1000000 but must be at most 256",
            ]
        );
        let clean = bad.sanitized();
        assert_eq!(clean.problems(), []);
        assert_eq!(clean.height_scale, 0.05);
        assert_eq!(clean.lod_band, 1.0);
        assert_eq!(clean.shadow_softening, 0.01);
        assert_eq!(
            (clean.min_samples, clean.max_samples),
            (1, MAX_SAMPLES_LIMIT)
        );
    }

    #[test]
    fn inverted_sample_bounds_are_an_error_and_get_swapped() {
        let inverted = ParallaxOcclusionMaterial {
            min_samples: 40,
            max_samples: 10,
            ..ParallaxOcclusionMaterial::default()
        };
        assert_eq!(
            inverted.validate(),
            Err(PomMaterialError::SamplesInverted { min: 40, max: 10 })
        );
        let clean = inverted.sanitized();
        assert_eq!((clean.min_samples, clean.max_samples), (10, 40));
    }

    #[test]
    fn negative_height_scale_is_clamped_to_flat() {
        let material = ParallaxOcclusionMaterial {
            height_scale: -0.2,
            ..ParallaxOcclusionMaterial::default()
        };
        assert!(matches!(
            material.validate(),
            Err(PomMaterialError::TooSmall {
                field: "height_scale",
                ..
            })
        ));
        assert_eq!(material.sanitized().height_scale, 0.0);
    }
}
