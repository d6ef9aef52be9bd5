//! A layered parallax material's layers in a glTF material's `extras.pom`:
//!
//! ```json
//! "layers": [
//!   { "base_color_texture": 0, "normal_texture": 1, "height_texture": 2, "height_scale": 1.0, "tiling": 8 },
//!   { "base_color_texture": 3, "height_texture": 4, "tiling": 16 }
//! ],
//! "layer_weights_texture": 5
//! ```
//! Every key of a layer is optional (textures as glTF texture indices: a missing map is white,
//! flat, or a flat height at the top; `height_scale` 1 and `tiling` 1); unknown keys are errors.
//! Without `layer_weights_texture` the mesh's vertex colours weigh the layers.

use serde_json::Value;

/// One layer of `extras.pom.layers`.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct LayerExtras {
    /// Texture index of the layer's colour map.
    pub base_color_texture: Option<usize>,
    /// Texture index of its normal map.
    pub normal_texture: Option<usize>,
    /// Texture index of its height map (red channel, white the top).
    pub height_texture: Option<usize>,
    /// Its depth as a share of the material's `height_scale`.
    pub height_scale: Option<f32>,
    /// Its repeats across the mesh's texture coordinates.
    pub tiling: Option<f32>,
}

/// The keys a layer may have.
const LAYER_KEYS: [&str; 5] = [
    "base_color_texture",
    "normal_texture",
    "height_texture",
    "height_scale",
    "tiling",
];

/// `extras.pom.layers`: a list of layer objects.
pub fn parse_layers(value: &Value) -> Result<Vec<LayerExtras>, String> {
    let Value::Array(list) = value else {
        return Err(format!(
            "extras.pom.layers: invalid type: {}, expected a list of layer objects",
            super::extras::describe(value)
        ));
    };
    list.iter()
        .enumerate()
        .map(|(index, layer)| parse_layer(index, layer))
        .collect()
}

fn parse_layer(index: usize, value: &Value) -> Result<LayerExtras, String> {
    let field = |key: &str| format!("extras.pom.layers[{index}].{key}");
    let Value::Object(keys) = value else {
        return Err(format!(
            "extras.pom.layers[{index}]: invalid type: {}, expected an object",
            super::extras::describe(value)
        ));
    };
    let mut layer = LayerExtras::default();
    for (key, value) in keys {
        let texture = || {
            super::extras::texture_index(value).ok_or_else(|| {
                format!(
                    "{}: invalid type: {}, expected a texture index",
                    field(key),
                    super::extras::describe(value)
                )
            })
        };
        let number = || {
            value.as_f64().map(|number| number as f32).ok_or_else(|| {
                format!(
                    "{}: invalid type: {}, expected f32",
                    field(key),
                    super::extras::describe(value)
                )
            })
        };
        match key.as_str() {
            "base_color_texture" => layer.base_color_texture = Some(texture()?),
            "normal_texture" => layer.normal_texture = Some(texture()?),
            "height_texture" => layer.height_texture = Some(texture()?),
            "height_scale" => layer.height_scale = Some(number()?),
            "tiling" => layer.tiling = Some(number()?),
            other => {
                return Err(format!(
                    "{}: unknown field `{other}`, expected one of {}",
                    field(other),
                    LAYER_KEYS.join(", ")
                ));
            }
        }
    }
    Ok(layer)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn layers_parse_with_every_key_optional() {
        let value: Value = serde_json::from_str(
            r#"[{"base_color_texture": 0, "normal_texture": 1, "height_texture": 2, "height_scale": 0.5, "tiling": 8}, {}]"#,
        )
        .unwrap();
        let layers = parse_layers(&value).unwrap();
        assert_eq!(
            layers[0],
            LayerExtras {
                base_color_texture: Some(0),
                normal_texture: Some(1),
                height_texture: Some(2),
                height_scale: Some(0.5),
                tiling: Some(8.0),
            }
        );
        assert_eq!(layers[1], LayerExtras::default());
    }

    #[test]
    fn bad_layers_name_the_layer_and_key() {
        let parse = |text: &str| parse_layers(&serde_json::from_str(text).unwrap()).unwrap_err();
        assert_eq!(
            parse(r#"{"tiling": 2}"#),
            "extras.pom.layers: invalid type: map, expected a list of layer objects"
        );
        assert_eq!(
            parse(r#"[{}, {"tiling": "x"}]"#),
            "extras.pom.layers[1].tiling: invalid type: string \"x\", expected f32"
        );
        assert_eq!(
            parse(r#"[{"height_texture": -1}]"#),
            "extras.pom.layers[0].height_texture: invalid type: integer `-1`, expected a texture index"
        );
        assert!(parse(r#"[{"colour": 1}]"#).starts_with(
            "extras.pom.layers[0].colour: unknown field `colour`, expected one of base_color_texture"
        ));
        assert_eq!(
            parse("[3]"),
            "extras.pom.layers[0]: invalid type: integer `3`, expected an object"
        );
    }
}
