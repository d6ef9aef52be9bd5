//! Material presets ([`PomPreset`]: every parameter of a [`ParallaxOcclusionMaterial`] without
//! its textures) saved and loaded as RON, and printed as a Rust struct literal. In RON every field
//! is optional (missing ones take the default, `lighting` too: `phong`), unknown ones are errors,
//! and a saved preset names every field; plugin/docs/authoring-materials.md documents the format:
//!
//! ```ron
//! (height_scale: 0.06, max_samples: 64, shadows: soft, method: relief, relief_binary_steps: 6)
//! ```

use std::path::Path;

use super::material::{ParallaxOcclusionMaterial, PomMaterialError, PomPreset};

/// Why a preset could not be read or written.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum PresetError {
    /// The file could not be read or written.
    #[error("{path}: {reason}")]
    Io {
        /// The file.
        path: String,
        /// What the file system said.
        reason: String,
    },
    /// The text is not a valid preset (syntax, wrong type, unknown field).
    #[error("{name}:{line}:{column}: {reason}")]
    Syntax {
        /// The file or source name.
        name: String,
        /// 1-based line.
        line: usize,
        /// 1-based column.
        column: usize,
        /// What the parser said.
        reason: String,
    },
    /// The values parse but are out of range.
    #[error("{name}: {source}")]
    Invalid {
        /// The file or source name.
        name: String,
        /// The first problem.
        source: PomMaterialError,
    },
    /// The layers a preset describes could not be built from its files.
    #[error("layers: {reason}")]
    Layers {
        /// The file and what is wrong with it, or the layers' problem.
        reason: String,
    },
}

impl From<crate::files::WriteError> for PresetError {
    fn from(error: crate::files::WriteError) -> Self {
        let reason = error.reason();
        let (crate::files::WriteError::Io { path, .. }
        | crate::files::WriteError::Encode { path, .. }) = error;
        PresetError::Io {
            path: path.display().to_string(),
            reason,
        }
    }
}

impl PomPreset {
    /// Parses RON text; `name` (a file name) appears in errors with the line and column. The
    /// values are validated like a material's.
    pub fn from_ron(text: &str, name: &str) -> Result<Self, PresetError> {
        let parser = ron::Options::default()
            .with_default_extension(ron::extensions::Extensions::IMPLICIT_SOME);
        let preset: PomPreset = parser.from_str(text).map_err(|error| PresetError::Syntax {
            name: name.to_owned(),
            line: error.span.start.line,
            column: error.span.start.col,
            reason: error.code.to_string(),
        })?;
        let mut material = ParallaxOcclusionMaterial::default();
        material.apply_preset(&preset);
        // The default material has no layers to take the preset's: they are checked apart.
        let problem = material
            .validate()
            .err()
            .or_else(|| preset.layers_problem());
        if let Some(source) = problem {
            return Err(PresetError::Invalid {
                name: name.to_owned(),
                source,
            });
        }
        Ok(preset)
    }

    /// Reads (a regular file, within [`crate::files::MAX_TEXT_FILE_BYTES`]) and parses a RON
    /// file.
    pub fn load(path: impl AsRef<Path>) -> Result<Self, PresetError> {
        let path = path.as_ref();
        let text = crate::files::read_text_bounded(path, crate::files::MAX_TEXT_FILE_BYTES)
            .map_err(|error| PresetError::Io {
                path: path.display().to_string(),
                reason: error.to_string(),
            })?;
        Self::from_ron(&text, &path.display().to_string())
    }

    /// Pretty RON text of every field.
    pub fn to_ron(&self) -> String {
        // Serialising plain numbers, booleans, strings and unit enums cannot fail.
        ron::ser::to_string_pretty(self, ron::ser::PrettyConfig::default())
            .expect("presets always serialise")
    }

    /// Writes the preset as RON with [`crate::files::write_file`]: a failed write or a crash
    /// never leaves half a file.
    pub fn save(&self, path: impl AsRef<Path>) -> Result<(), PresetError> {
        crate::files::write_file(path.as_ref(), self.to_ron().as_bytes()).map_err(PresetError::from)
    }

    /// The preset as a Rust struct literal to paste into game code.
    pub fn to_rust(&self) -> String {
        let mut rust = String::from("ParallaxOcclusionMaterial {\n");
        for (name, value) in self.rust_fields() {
            rust.push_str(&format!("    {name}: {value},\n"));
        }
        rust.push_str("    ..ParallaxOcclusionMaterial::default()\n}");
        rust
    }
}

#[cfg(test)]
mod tests {
    use super::super::material::{ParallaxMethod, ShadowMode};
    use super::*;
    use crate::LightingModel;

    #[test]
    fn presets_round_trip_through_ron() {
        let material = ParallaxOcclusionMaterial {
            height_scale: 0.07,
            method: ParallaxMethod::Relief,
            relief_binary_steps: 4,
            shadows: ShadowMode::Hard,
            ..ParallaxOcclusionMaterial::default()
        };
        let preset = material.preset();
        let parsed = PomPreset::from_ron(&preset.to_ron(), "test.ron").unwrap();
        assert_eq!(parsed, preset);
        let mut other = ParallaxOcclusionMaterial::default();
        other.apply_preset(&parsed);
        assert_eq!(other.preset(), preset);
    }

    #[test]
    fn partial_presets_keep_defaults() {
        let preset = PomPreset::from_ron("(height_scale: 0.02, method: steep)", "p.ron").unwrap();
        assert_eq!(preset.height_scale, 0.02);
        assert_eq!(preset.method, ParallaxMethod::Steep);
        assert_eq!(preset.max_samples, 50);
    }

    #[test]
    fn bad_presets_name_the_place_and_the_problem() {
        let syntax =
            PomPreset::from_ron("(height_scale: 0.02,\n  max_samples: )", "bad.ron").unwrap_err();
        assert!(syntax.to_string().starts_with("bad.ron:2:"), "{syntax}");
        let unknown = PomPreset::from_ron("(hieght_scale: 1.0)", "u.ron")
            .unwrap_err()
            .to_string();
        assert!(
            unknown.contains("u.ron:1:") && unknown.contains("hieght_scale"),
            "{unknown}"
        );
        let wrong_type = PomPreset::from_ron("(max_samples: \"many\")", "t.ron").unwrap_err();
        assert!(
            matches!(wrong_type, PresetError::Syntax { .. }),
            "{wrong_type}"
        );
        let invalid = PomPreset::from_ron("(min_samples: 90)", "i.ron")
            .unwrap_err()
            .to_string();
        assert!(
            invalid.contains("min_samples (90) is greater than max_samples (50)"),
            "{invalid}"
        );
        let missing = PomPreset::load("/nonexistent/preset.ron")
            .unwrap_err()
            .to_string();
        assert!(missing.contains("/nonexistent/preset.ron"), "{missing}");
    }

    #[test]
    fn saving_is_atomic_and_reloads() {
        let dir = std::env::temp_dir().join(format!("pom-preset-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("tuned.ron");
        let preset = PomPreset {
            height_scale: 0.03,
            ..PomPreset::default()
        };
        preset.save(&path).unwrap();
        assert_eq!(PomPreset::load(&path).unwrap(), preset);
        let leftovers = std::fs::read_dir(&dir).unwrap().count();
        assert_eq!(leftovers, 1, "no temporary file stays behind");
        std::fs::remove_dir_all(&dir).unwrap();
    }

    /// The example of the "Presets" section of plugin/docs/authoring-materials.md.
    fn documented_example() -> &'static str {
        let doc = include_str!("../../docs/authoring-materials.md");
        let (_, section) = doc
            .split_once("\n## Presets\n")
            .expect("authoring-materials.md has a Presets section");
        let (_, from_example) = section
            .split_once("```ron\n")
            .expect("the Presets section has a RON example");
        let (example, _) = from_example
            .split_once("```")
            .expect("the example's block is closed");
        example
    }

    #[test]
    fn the_documented_example_preset_loads() {
        let preset = PomPreset::from_ron(documented_example(), "authoring-materials.md").unwrap();
        assert_eq!(preset.lighting, LightingModel::GgxLambert);
        assert_eq!((preset.max_samples, preset.secant_steps), (64, 2));
        assert_eq!(preset.roughness, 0.75);
    }

    #[test]
    fn saved_presets_name_every_parameter_lighting_included() {
        let text = PomPreset::default().to_ron();
        for param in ParallaxOcclusionMaterial::PARAMETERS {
            assert!(
                text.contains(&format!("{}:", param.name)),
                "{} is missing from\n{text}",
                param.name
            );
        }
    }

    #[test]
    fn a_preset_without_lighting_is_phong_whatever_it_is_loaded_into() {
        let preset = PomPreset::from_ron("(height_scale: 0.03)", "partial.ron").unwrap();
        let mut material = ParallaxOcclusionMaterial {
            lighting: LightingModel::GgxLambert,
            ..ParallaxOcclusionMaterial::default()
        };
        material.apply_preset(&preset);
        assert_eq!(material.lighting, LightingModel::Phong);
    }

    #[test]
    fn the_rust_literal_names_every_field() {
        let rust = PomPreset::default().to_rust();
        for field in [
            "height_scale: 0.05",
            "max_samples: 50",
            "method: ParallaxMethod::Occlusion",
            "..ParallaxOcclusionMaterial::default()",
        ] {
            assert!(rust.contains(field), "{rust}");
        }
    }
}
