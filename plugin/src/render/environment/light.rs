//! [`EnvironmentLight`], the resource that says which environment lights the world and how:
//! its source, and its [`EnvironmentSettings`], each declared once like every parameter (the
//! command line, scripts and the sandbox read the same table).

use std::path::Path;

use super::{EnvironmentError, EnvironmentSource, EquirectImage, Sky};
use crate::parameters::ParamSpec;

/// Largest side of the radiance cube [`EnvironmentSettings::resolution`] may ask for.
pub const MAX_ENVIRONMENT_RESOLUTION: u32 = 2048;

crate::settings_parameters! {
    /// How an environment lights the scene. Each parameter is declared once, in
    /// [`EnvironmentSettings::PARAMETERS`]; values outside their limits are clamped.
    #[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
    #[serde(default, deny_unknown_fields)]
    pub struct EnvironmentSettings {
        /// Multiplies the environment's radiance: 1 is as its source gives it, in cd/m².
        intensity: f32 = 1.0, ParamSpec::float(0.0, 1_000_000.0).editor(0.0, 4.0);
        /// The environment's turn about the vertical axis, in degrees.
        rotation: f32 = 0.0, ParamSpec::float(-360.0, 360.0);
        /// Texels along a side of the radiance cube's largest mip (rounded up to a power of
        /// two): sharper mirror reflections, longer prefiltering.
        resolution: u32 = 256, ParamSpec::integer(16, MAX_ENVIRONMENT_RESOLUTION);
        /// Draw the environment behind the scene (else the camera's clear colour stays there).
        background: bool = true, ParamSpec::toggle();
        /// Give rough surfaces' specular back the energy a single scattering loses
        /// (multiple-scattering compensation): a rough metal is then as bright as a smooth one.
        energy_compensation: bool = true, ParamSpec::toggle();
    }
}

/// The light arriving from all around the scene, and whether it is drawn behind it. A resource:
/// one environment lights the whole world (every material's group 0 binds the same maps), as
/// the world has one sky; a camera does not carry its own.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct EnvironmentLight {
    /// Where its radiance comes from ([`EnvironmentSource::Off`] by default: none).
    pub source: EnvironmentSource,
    /// How bright, turned how far, and how it is drawn.
    pub settings: EnvironmentSettings,
}

impl EnvironmentLight {
    /// The default sky (Preetham, its sun at the first directional light).
    pub fn sky() -> Self {
        Self {
            source: EnvironmentSource::Sky(Sky::default()),
            ..Self::default()
        }
    }

    /// The same `radiance` (linear RGB, cd/m²) from every direction.
    pub fn uniform(radiance: [f32; 3]) -> Self {
        Self {
            source: EnvironmentSource::Uniform(radiance),
            ..Self::default()
        }
    }

    /// An equirectangular `.hdr` or `.exr` image read from `path` ([`EquirectImage::read`]).
    pub fn from_file(path: impl AsRef<Path>) -> Result<Self, EnvironmentError> {
        Ok(Self {
            source: EnvironmentSource::Equirect(std::sync::Arc::new(EquirectImage::read(
                path.as_ref(),
            )?)),
            ..Self::default()
        })
    }

    /// The same light with `settings`.
    pub fn with_settings(self, settings: EnvironmentSettings) -> Self {
        Self { settings, ..self }
    }
}
