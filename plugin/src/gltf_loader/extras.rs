//! The POM parameters a glTF material carries in its `extras`.
//!
//! ```json
//! "extras": { "pom": { "height_texture": 3, "height_scale": 0.05, "min_samples": 8 } }
//! ```
//! Five keys are glTF's own (`height_texture`, `height_in_normal_alpha`, `height_channel`, and
//! a layered material's `layers` and `layer_weights_texture`, see `layer_extras.rs`); every
//! other key is a parameter of [`ParallaxOcclusionMaterial`], by its declared name, with its one
//! spelling of enum values. Every key is optional except `height_texture` (or
//! `height_in_normal_alpha`, or `layers`); unknown keys are errors.

use serde_json::Value;

use super::layer_extras::{LayerExtras, parse_layers};

/// The keys of `extras.pom` that are glTF's own rather than material parameters.
const GLTF_KEYS: [&str; 5] = [
    "height_texture",
    "height_in_normal_alpha",
    "height_channel",
    "layers",
    "layer_weights_texture",
];

use crate::ParallaxOcclusionMaterial;
use crate::material::{ParamKind, ParamValue};

/// The `extras.pom` object of a glTF material. Missing parameters take the material's
/// defaults.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct PomExtras {
    /// Index into the file's `textures` of the height map. Required, unless
    /// `height_in_normal_alpha` is true.
    pub height_texture: Option<usize>,
    /// Read the height from the normal texture's alpha instead (McGuire's packing).
    pub height_in_normal_alpha: bool,
    /// Channel of the height texture: "r", "g", "b" or "a". Default "r".
    pub height_channel: Option<String>,
    /// A layered material's layers (`layers`), replacing the material's own maps.
    pub layers: Option<Vec<LayerExtras>>,
    /// Index into the file's `textures` of the layers' weight map (else the vertex colours).
    pub layer_weights_texture: Option<usize>,
    /// The material parameters given, in the file's order, checked against their declarations'
    /// types (not yet their limits: the material's `validate` does that).
    pub parameters: Vec<(&'static str, ParamValue)>,
}

impl PomExtras {
    /// Reads `extras.pom` from a material's raw extras JSON; `Ok(None)` when there is none.
    pub fn from_extras(raw: Option<&str>) -> Result<Option<Self>, String> {
        let Some(raw) = raw else {
            return Ok(None);
        };
        let value: Value = serde_json::from_str(raw).map_err(|e| e.to_string())?;
        let Some(pom) = value.get("pom") else {
            return Ok(None);
        };
        let Value::Object(keys) = pom else {
            return Err(format!(
                "extras.pom: invalid type: {}, expected an object",
                describe(pom)
            ));
        };
        let mut extras = PomExtras::default();
        for (key, value) in keys {
            match key.as_str() {
                "height_texture" => {
                    extras.height_texture = Some(
                        texture_index(value)
                            .ok_or_else(|| invalid_type(value, "a texture index"))?,
                    );
                }
                "height_in_normal_alpha" => {
                    extras.height_in_normal_alpha = value
                        .as_bool()
                        .ok_or_else(|| invalid_type(value, "a boolean"))?;
                }
                "height_channel" => {
                    extras.height_channel = Some(
                        value
                            .as_str()
                            .ok_or_else(|| invalid_type(value, "a string"))?
                            .to_owned(),
                    );
                }
                "layers" => extras.layers = Some(parse_layers(value)?),
                "layer_weights_texture" => {
                    extras.layer_weights_texture = Some(
                        texture_index(value)
                            .ok_or_else(|| invalid_type(value, "a texture index"))?,
                    );
                }
                name => extras.parameters.push(parameter(name, value)?),
            }
        }
        Ok(Some(extras))
    }

    /// Writes the parameters into `material`.
    pub fn apply(&self, material: &mut ParallaxOcclusionMaterial) -> Result<(), String> {
        for (name, value) in &self.parameters {
            let param = ParallaxOcclusionMaterial::PARAMETERS
                .iter()
                .find(|param| param.name == *name)
                .ok_or_else(|| format!("extras.pom: unknown field `{name}`"))?;
            (param.set)(material, *value).map_err(|error| format!("extras.pom.{error}"))?;
        }
        Ok(())
    }
}

/// The declared parameter `name` with its JSON value, of the declared type.
fn parameter(name: &str, value: &Value) -> Result<(&'static str, ParamValue), String> {
    let parameters = ParallaxOcclusionMaterial::PARAMETERS;
    let Some(param) = parameters.iter().find(|param| param.name == name) else {
        let names: Vec<&str> = GLTF_KEYS
            .into_iter()
            .chain(parameters.iter().map(|param| param.name))
            .collect();
        return Err(format!(
            "extras.pom: unknown field `{name}`, expected one of {}",
            names.join(", ")
        ));
    };
    let parsed = match param.spec.kind {
        ParamKind::Float { .. } => value
            .as_f64()
            .map(|number| ParamValue::Float(number as f32))
            .ok_or_else(|| invalid_type_of(name, value, "f32"))?,
        ParamKind::Integer { .. } => value
            .as_u64()
            .and_then(|number| u32::try_from(number).ok())
            .map(ParamValue::Integer)
            .ok_or_else(|| invalid_type_of(name, value, "u32"))?,
        ParamKind::Toggle => value
            .as_bool()
            .map(ParamValue::Toggle)
            .ok_or_else(|| invalid_type_of(name, value, "a boolean"))?,
        ParamKind::Choice(choices) => {
            let text = value
                .as_str()
                .ok_or_else(|| invalid_type_of(name, value, "a string"))?;
            let names: Vec<&str> = choices.iter().map(|choice| choice.name).collect();
            choices
                .iter()
                .find(|choice| choice.name == text)
                .map(|choice| ParamValue::Choice(choice.name))
                .ok_or_else(|| {
                    format!(
                        "extras.pom.{name} is {text:?}; expected one of {}",
                        names.join(", ")
                    )
                })?
        }
        ParamKind::Color => {
            // Every item must be a number: none is dropped silently.
            let components: Option<Vec<f32>> = value.as_array().and_then(|items| {
                items
                    .iter()
                    .map(|item| item.as_f64().map(|c| c as f32))
                    .collect()
            });
            match components.as_deref() {
                Some([r, g, b]) => ParamValue::Color([*r, *g, *b, 1.0]),
                Some([r, g, b, a]) => ParamValue::Color([*r, *g, *b, *a]),
                _ => return Err(invalid_type_of(name, value, "[r, g, b] or [r, g, b, a]")),
            }
        }
    };
    Ok((param.name, parsed))
}

/// A glTF texture index: a whole number that fits the platform's `usize`.
pub(super) fn texture_index(value: &Value) -> Option<usize> {
    value.as_u64().and_then(|index| usize::try_from(index).ok())
}

/// A type error of the parameter `name`.
fn invalid_type_of(name: &str, value: &Value, expected: &str) -> String {
    format!(
        "extras.pom.{name}: invalid type: {}, expected {expected}",
        describe(value)
    )
}

fn invalid_type(value: &Value, expected: &str) -> String {
    format!(
        "extras.pom: invalid type: {}, expected {expected}",
        describe(value)
    )
}

/// A JSON value as serde describes it in type errors: `string "many"`, `integer 3`.
pub(super) fn describe(value: &Value) -> String {
    match value {
        Value::Null => "null".into(),
        Value::Bool(value) => format!("boolean `{value}`"),
        Value::Number(number) if number.is_f64() => format!("floating point `{number}`"),
        Value::Number(number) => format!("integer `{number}`"),
        Value::String(text) => format!("string {text:?}"),
        Value::Array(_) => "sequence".into(),
        Value::Object(_) => "map".into(),
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
        assert_eq!(parsed.parameters, [("min_samples", ParamValue::Integer(4))]);
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
        assert_eq!(
            wrong_type,
            "extras.pom.min_samples: invalid type: string \"many\", expected u32"
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
