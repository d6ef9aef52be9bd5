//! What an environment is made from ([`EnvironmentSource`]): a constant radiance, the sky, or
//! an equirectangular image read from a Radiance `.hdr` or OpenEXR file, and how the GPU reads
//! it (`SourceParams`, environment_source.wgsl).

use std::path::{Path, PathBuf};
use std::sync::Arc;

use super::sky::Sky;

/// Where the environment's radiance comes from.
#[derive(Clone, Debug, Default, PartialEq)]
pub enum EnvironmentSource {
    /// No environment: materials light with the [`crate::AmbientLight`] alone, and the clear
    /// colour stays behind the scene.
    #[default]
    Off,
    /// The same radiance from every direction, linear RGB in cd/m² (a furnace, for tests).
    Uniform([f32; 3]),
    /// Preetham's daylight sky, its sun where the scene's first directional light shines from.
    Sky(Sky),
    /// An equirectangular image (longitude across, the zenith at the top), values in cd/m²
    /// times the light's intensity; the image's centre lies along −Z.
    Equirect(Arc<EquirectImage>),
}

/// An environment as a command line or a script names it: `off`, `sky`, `uniform:R,G,B` (a
/// constant radiance in cd/m², linear; one value for grey) or the path of an equirectangular
/// `.hdr` / `.exr` file. Parsed with [`str::parse`]; [`EnvironmentChoice::load`] reads a file.
#[derive(Clone, Debug, PartialEq)]
pub enum EnvironmentChoice {
    /// No environment.
    Off,
    /// The default sky.
    Sky,
    /// A constant radiance.
    Uniform([f32; 3]),
    /// An image file.
    File(PathBuf),
}

/// Most a uniform environment's radiance may be, cd/m² (the sun's disc is about 1.6e9).
pub const MAX_UNIFORM_RADIANCE: f32 = 1e10;

impl std::str::FromStr for EnvironmentChoice {
    type Err = EnvironmentError;

    fn from_str(text: &str) -> Result<Self, Self::Err> {
        match text.trim() {
            "off" => return Ok(Self::Off),
            "sky" => return Ok(Self::Sky),
            "" => {
                return Err(EnvironmentError::BadChoice {
                    text: text.to_owned(),
                    reason: "it is empty".into(),
                });
            }
            _ => {}
        }
        let Some(values) = text.trim().strip_prefix("uniform:") else {
            return Ok(Self::File(PathBuf::from(text)));
        };
        let bad = |reason: String| EnvironmentError::BadChoice {
            text: text.to_owned(),
            reason,
        };
        let parsed: Vec<f32> = values
            .split(',')
            .map(|value| {
                let value: f32 = value
                    .trim()
                    .parse()
                    .map_err(|_| bad(format!("{value:?} is not a number")))?;
                if value.is_finite() && (0.0..=MAX_UNIFORM_RADIANCE).contains(&value) {
                    Ok(value)
                } else {
                    Err(bad(format!(
                        "{value} is not a radiance in 0..={MAX_UNIFORM_RADIANCE} cd/m²"
                    )))
                }
            })
            .collect::<Result<_, _>>()?;
        match parsed[..] {
            [grey] => Ok(Self::Uniform([grey; 3])),
            [r, g, b] => Ok(Self::Uniform([r, g, b])),
            _ => Err(bad(format!(
                "uniform takes one value or three (R,G,B), not {}",
                parsed.len()
            ))),
        }
    }
}

impl EnvironmentChoice {
    /// The source this names, a file read ([`EquirectImage::read`]) where it names one.
    pub fn load(&self) -> Result<EnvironmentSource, EnvironmentError> {
        Ok(match self {
            Self::Off => EnvironmentSource::Off,
            Self::Sky => EnvironmentSource::Sky(Sky::default()),
            Self::Uniform(radiance) => EnvironmentSource::Uniform(*radiance),
            Self::File(path) => EnvironmentSource::Equirect(Arc::new(EquirectImage::read(path)?)),
        })
    }
}

/// Why an environment file was not loaded.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum EnvironmentError {
    /// The file could not be read or decoded (named in the message).
    #[error("environment {path}: {source}")]
    Image {
        /// The file.
        path: PathBuf,
        /// What went wrong.
        source: crate::ImageError,
    },
    /// An environment's name is none of `off`, `sky`, `uniform:R,G,B` or a file.
    #[error(
        "environment {text:?}: {reason} (expected off, sky, uniform:R,G,B or a .hdr/.exr file)"
    )]
    BadChoice {
        /// What was given.
        text: String,
        /// What is wrong with it.
        reason: String,
    },
    /// The texels do not fill the size given (or the size is empty).
    #[error("environment {name}: {texels} texels for {width} × {height}")]
    WrongSize {
        /// The image.
        name: String,
        /// Its width.
        width: u32,
        /// Its height.
        height: u32,
        /// How many texels were given.
        texels: usize,
    },
    /// The image holds a value that is not a finite, non-negative radiance.
    #[error("environment {path}: pixel ({x}, {y}) holds {value}, not a finite radiance ≥ 0")]
    BadRadiance {
        /// The file.
        path: PathBuf,
        /// Its column.
        x: u32,
        /// Its row.
        y: u32,
        /// The value.
        value: f32,
    },
}

/// A decoded equirectangular environment: linear RGB radiance, row by row from the top.
#[derive(Clone, Debug, PartialEq)]
pub struct EquirectImage {
    name: String,
    width: u32,
    height: u32,
    texels: Vec<[f32; 3]>,
    brightest: f32,
}

impl EquirectImage {
    /// Reads `path` (a regular file within [`crate::files::MAX_IMAGE_FILE_BYTES`]; a Radiance
    /// `.hdr` or an OpenEXR image, whatever its name says) and decodes it within
    /// [`crate::IMAGE_MEMORY_BUDGET`]. A negative, NaN or infinite value is an error naming
    /// its pixel.
    pub fn read(path: &Path) -> Result<Self, EnvironmentError> {
        let image_error = |source| EnvironmentError::Image {
            path: path.to_owned(),
            source,
        };
        let name = path.display().to_string();
        let bytes = crate::files::read_bounded(path, crate::files::MAX_IMAGE_FILE_BYTES).map_err(
            |error| {
                image_error(crate::ImageError::Load {
                    path: name.clone().into(),
                    reason: error.to_string(),
                })
            },
        )?;
        let mut budget = crate::image::ImageBudget::new(crate::IMAGE_MEMORY_BUDGET);
        let decoded = crate::image::decode_bytes(
            &bytes,
            &name,
            (
                image::ImageFormat::from_path(path).ok(),
                crate::image::ENVIRONMENT_FORMATS,
            ),
            &mut budget,
        )
        .map_err(image_error)?
        .into_rgb32f();
        let (width, height) = decoded.dimensions();
        let texels: Vec<[f32; 3]> = decoded.pixels().map(|pixel| pixel.0).collect();
        Self::new(name, width, height, texels).map_err(|error| match error {
            EnvironmentError::BadRadiance { x, y, value, .. } => EnvironmentError::BadRadiance {
                path: path.to_owned(),
                x,
                y,
                value,
            },
            other => other,
        })
    }

    /// An image named `name` of `width × height` radiances, row by row from the top: each
    /// component finite and ≥ 0, and as many texels as the size says (else an error naming the
    /// first bad pixel, or the size).
    pub fn new(
        name: impl Into<String>,
        width: u32,
        height: u32,
        texels: Vec<[f32; 3]>,
    ) -> Result<Self, EnvironmentError> {
        let name = name.into();
        let expected = u64::from(width) * u64::from(height);
        if expected == 0 || texels.len() as u64 != expected {
            return Err(EnvironmentError::WrongSize {
                name,
                width,
                height,
                texels: texels.len(),
            });
        }
        if let Some((index, value)) = texels
            .iter()
            .enumerate()
            .flat_map(|(index, texel)| texel.iter().map(move |value| (index, *value)))
            .find(|(_, value)| !(value.is_finite() && *value >= 0.0))
        {
            return Err(EnvironmentError::BadRadiance {
                path: PathBuf::from(name),
                x: index as u32 % width,
                y: index as u32 / width,
                value,
            });
        }
        let brightest = texels
            .iter()
            .flatten()
            .fold(0.0_f32, |max, value| max.max(*value));
        Ok(Self {
            name,
            width,
            height,
            texels,
            brightest,
        })
    }

    /// Where it was read from, for messages.
    pub fn name(&self) -> &str {
        &self.name
    }

    /// Texels across (360° of longitude) and down (180° of latitude).
    pub fn size(&self) -> (u32, u32) {
        (self.width, self.height)
    }

    /// Its largest component.
    pub fn brightest(&self) -> f32 {
        self.brightest
    }

    /// The image and its mip chain (each level the 2 × 2 average of the one above, down to one
    /// texel a side), the first level at most `max_side` texels a side, as RGBA half floats
    /// (values over half precision's largest clamped to it).
    pub(crate) fn mip_chain(&self, max_side: u32) -> Vec<(u32, u32, Vec<half::f16>)> {
        let mut level: (u32, u32, Vec<[f32; 3]>) = (self.width, self.height, self.texels.clone());
        let mut levels = Vec::new();
        loop {
            let (width, height, texels) = &level;
            if *width <= max_side.max(1) && *height <= max_side.max(1) {
                let encoded = texels
                    .iter()
                    .flat_map(|[r, g, b]| [*r, *g, *b, 1.0])
                    .map(|value| half::f16::from_f32(value.min(f32::from(half::f16::MAX))))
                    .collect();
                levels.push((*width, *height, encoded));
            }
            if *width == 1 && *height == 1 {
                return levels;
            }
            level = halved(*width, *height, texels);
        }
    }
}

/// The 2 × 2 average of `texels` (a side of 1 stays 1).
fn halved(width: u32, height: u32, texels: &[[f32; 3]]) -> (u32, u32, Vec<[f32; 3]>) {
    let (half_width, half_height) = ((width / 2).max(1), (height / 2).max(1));
    let at = |x: u32, y: u32| texels[(y.min(height - 1) * width + x.min(width - 1)) as usize];
    let texels = (0..half_height)
        .flat_map(|y| (0..half_width).map(move |x| (x, y)))
        .map(|(x, y)| {
            let (x, y) = (x * 2, y * 2);
            let corners = [at(x, y), at(x + 1, y), at(x, y + 1), at(x + 1, y + 1)];
            std::array::from_fn(|c| corners.iter().map(|texel| texel[c]).sum::<f32>() * 0.25)
        })
        .collect();
    (half_width, half_height, texels)
}

/// Which source the GPU reads (`SOURCE_*` in environment_source.wgsl).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(u32)]
pub(crate) enum SourceKind {
    Uniform = 0,
    Sky = 1,
    Equirect = 2,
}

/// Mirrors `SourceParams` in environment_source.wgsl.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub(crate) struct SourceParams {
    /// rgb: the constant radiance (a uniform source).
    pub uniform_radiance: [f32; 4],
    /// x: the [`SourceKind`]; yzw unused.
    pub kind: [u32; 4],
}

crate::wgsl_layout!(SourceParams {
    uniform_radiance,
    kind
});

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_mip_chain_averages_down_to_one_texel_within_the_side_limit() {
        let image = EquirectImage::new(
            "test",
            8,
            4,
            (0..32).map(|i| [i as f32, 1.0, 1e9]).collect(),
        )
        .unwrap();
        let chain = image.mip_chain(4);
        let sizes: Vec<(u32, u32)> = chain.iter().map(|(w, h, _)| (*w, *h)).collect();
        assert_eq!(sizes, [(4, 2), (2, 1), (1, 1)]);
        let (_, _, last) = &chain[2];
        assert_eq!(last[0].to_f32(), 15.5);
        assert_eq!(last[2], half::f16::MAX);
    }

    #[test]
    fn an_environment_is_named_as_off_sky_uniform_or_a_file() {
        let parse = |text: &str| text.parse::<EnvironmentChoice>();
        assert_eq!(parse("off").unwrap(), EnvironmentChoice::Off);
        assert_eq!(parse(" sky ").unwrap(), EnvironmentChoice::Sky);
        assert_eq!(
            parse("uniform:1,2.5,3").unwrap(),
            EnvironmentChoice::Uniform([1.0, 2.5, 3.0])
        );
        assert_eq!(
            parse("uniform:7").unwrap(),
            EnvironmentChoice::Uniform([7.0; 3])
        );
        assert_eq!(
            parse("skies/noon.hdr").unwrap(),
            EnvironmentChoice::File("skies/noon.hdr".into())
        );
        for (bad, says) in [
            ("uniform:1,2", "one value or three"),
            ("uniform:-1", "not a radiance"),
            ("uniform:nan,1,1", "not a radiance"),
            ("uniform:1e11", "not a radiance"),
            ("uniform:red", "not a number"),
            ("", "empty"),
        ] {
            let message = parse(bad).unwrap_err().to_string();
            assert!(
                message.contains(says) && message.contains("expected off, sky"),
                "{bad}: {message}"
            );
        }
    }

    #[test]
    fn an_image_with_a_negative_or_nan_radiance_or_the_wrong_size_is_refused() {
        let bad = EquirectImage::new("sky.hdr", 2, 1, vec![[1.0; 3], [1.0, f32::NAN, 0.0]]);
        let message = bad.unwrap_err().to_string();
        assert!(
            message.contains("sky.hdr") && message.contains("(1, 0)"),
            "{message}"
        );
        let negative = EquirectImage::new("sky.hdr", 1, 1, vec![[-1.0, 0.0, 0.0]]);
        assert!(matches!(
            negative,
            Err(EnvironmentError::BadRadiance { .. })
        ));
        let short = EquirectImage::new("sky.hdr", 2, 2, vec![[1.0; 3]]);
        assert!(
            short
                .unwrap_err()
                .to_string()
                .contains("1 texels for 2 × 2")
        );
    }
}
