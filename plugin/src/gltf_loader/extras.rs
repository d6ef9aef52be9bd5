//! The POM parameters a glTF material carries in its `extras`.
//!
//! ```json
//! "extras": { "pom": { "height_texture": 3, "height_scale": 0.05, "min_samples": 8 } }
//! ```
//! Every key is optional except `height_texture`; unknown keys are errors.

use serde::Deserialize;

/// The `extras.pom` object of a glTF material. Missing keys take the material's defaults.
#[derive(Clone, Debug, Default, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PomExtras {
    /// Index into the file's `textures` of the height map. Required, unless
    /// `height_in_normal_alpha` is true.
    pub height_texture: Option<usize>,
    /// Read the height from the normal texture's alpha instead (McGuire's packing).
    #[serde(default)]
    pub height_in_normal_alpha: bool,
    /// Channel of the height texture: "r", "g", "b" or "a". Default "r".
    pub height_channel: Option<String>,
    /// "height" (white = top, default) or "depth" (white = deepest).
    pub height_convention: Option<String>,
    /// Depth of the relief from white to black.
    pub height_scale: Option<f32>,
    /// "texture" (default) or "world".
    pub height_units: Option<String>,
    /// Samples looking straight on.
    pub min_samples: Option<u32>,
    /// Samples at grazing angles.
    pub max_samples: Option<u32>,
    /// Mip level past which only normal mapping runs.
    pub lod_threshold: Option<f32>,
    /// Width of the LOD fade band, in mip levels.
    pub lod_band: Option<f32>,
    /// "off", "hard" or "soft".
    pub shadows: Option<String>,
    /// Penumbra width of soft shadows.
    pub shadow_softening: Option<f32>,
    /// "normal", "offset", "steep", "pom" or "relief".
    pub method: Option<String>,
    /// Bisection steps of "relief".
    pub relief_binary_steps: Option<u32>,
    /// Write the displaced depth.
    pub depth_offset: Option<bool>,
    /// "phong", "blinn-phong" or "cook-torrance".
    pub lighting: Option<String>,
    /// Phong / Blinn-Phong highlight weight.
    pub specular_strength: Option<f32>,
    /// Phong / Blinn-Phong exponent.
    pub shininess: Option<f32>,
}

impl PomExtras {
    /// Reads `extras.pom` from a material's raw extras JSON; `Ok(None)` when there is none.
    pub fn from_extras(raw: Option<&str>) -> Result<Option<Self>, String> {
        let Some(raw) = raw else {
            return Ok(None);
        };
        let value: serde_json::Value = serde_json::from_str(raw).map_err(|e| e.to_string())?;
        match value.get("pom") {
            None => Ok(None),
            Some(pom) => serde_json::from_value(pom.clone())
                .map(Some)
                .map_err(|e| format!("extras.pom: {e}")),
        }
    }
}

/// Looks a string option up in `choices`, with an error listing them.
pub fn choose<T: Copy>(
    key: &str,
    value: &Option<String>,
    choices: &[(&str, T)],
    default: T,
) -> Result<T, String> {
    let Some(value) = value else {
        return Ok(default);
    };
    choices
        .iter()
        .find(|(name, _)| name == value)
        .map(|(_, choice)| *choice)
        .ok_or_else(|| {
            let names: Vec<&str> = choices.iter().map(|(name, _)| *name).collect();
            format!(
                "extras.pom.{key} is {value:?}; expected one of {}",
                names.join(", ")
            )
        })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_known_keys_and_rejects_unknown_ones() {
        let parsed =
            PomExtras::from_extras(Some(r#"{"pom": {"height_texture": 3, "min_samples": 4}}"#))
                .unwrap()
                .unwrap();
        assert_eq!(parsed.height_texture, Some(3));
        assert_eq!(parsed.min_samples, Some(4));
        assert_eq!(PomExtras::from_extras(Some(r#"{"other": 1}"#)), Ok(None));
        assert_eq!(PomExtras::from_extras(None), Ok(None));
        let unknown =
            PomExtras::from_extras(Some(r#"{"pom": {"hieght_scale": 0.1}}"#)).unwrap_err();
        assert!(
            unknown.contains("unknown field `hieght_scale`"),
            "{unknown}"
        );
        let wrong_type =
            PomExtras::from_extras(Some(r#"{"pom": {"min_samples": "many"}}"#)).unwrap_err();
        assert!(
            wrong_type.contains("min_samples") || wrong_type.contains("invalid type"),
            "{wrong_type}"
        );
    }

    #[test]
    fn choices_name_the_alternatives() {
        let choices = [("off", 0), ("on", 1)];
        assert_eq!(choose("shadows", &None, &choices, 1), Ok(1));
        assert_eq!(choose("shadows", &Some("off".into()), &choices, 1), Ok(0));
        assert_eq!(
            choose("shadows", &Some("maybe".into()), &choices, 1),
            Err("extras.pom.shadows is \"maybe\"; expected one of off, on".into())
        );
    }
}
