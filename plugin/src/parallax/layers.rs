//! The layers of a layered parallax material: up to four surfaces (rock, grass, earth,
//! cobbles), each with its base colour, normal and height maps, tiling and depth, mixed by a
//! weight map or the vertex colours with height-based blending (`reference::layer_shares`).
//!
//! A mode of [`ParallaxOcclusionMaterial`](super::ParallaxOcclusionMaterial) rather than a
//! material of its own: the march, its LOD, shadows, silhouettes, depth offset and TAA are the
//! same code reading a different height field, and every place a material is described (the
//! sandbox, presets, scripts, glTF) already describes this one.

use super::layer_heights::MAX_LAYERS;
use crate::{Handle, HeightField, Image};

/// Fewest and most repeats of a layer's maps across the mesh's texture coordinates 0..1.
pub const LAYER_TILING_LIMITS: (f32, f32) = (1.0 / 1024.0, 1024.0);
/// Shallowest and deepest a layer's relief may be, as a share of the material's `height_scale`.
const LAYER_DEPTH_LIMITS: (f32, f32) = (0.0, 1.0);

/// One layer of a layered parallax material.
#[derive(Clone, Debug, PartialEq)]
pub struct ParallaxLayer {
    /// sRGB colour texture (white when absent).
    pub base_color_texture: Option<Handle<Image>>,
    /// Tangent-space normal map, OpenGL convention (flat when absent).
    pub normal_map: Option<Handle<Image>>,
    /// Repeats of the layer's maps across the mesh's texture coordinates 0..1.
    pub tiling: f32,
    /// The layer's relief depth as a share of the material's `height_scale` (0..1): a lower
    /// share keeps the layer nearer the top, so it stands higher in the blend.
    pub height_scale: f32,
}

impl Default for ParallaxLayer {
    fn default() -> Self {
        Self {
            base_color_texture: None,
            normal_map: None,
            tiling: 1.0,
            height_scale: 1.0,
        }
    }
}

/// Where a layered material's weights (one a layer, red = the first) come from.
#[derive(Clone, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum LayerWeights {
    /// An RGBA image across the mesh's texture coordinates 0..1 (not tiled), linear data.
    Texture(Handle<Image>),
    /// The mesh's vertex colours (RGBA), read where the view ray enters the surface: the march
    /// cannot interpolate them anywhere else.
    VertexColors,
}

/// The layers of a layered parallax material, their packed heights and their weights.
#[derive(Clone, Debug, PartialEq)]
pub struct ParallaxLayers {
    /// One to four layers, in the order of the weights' channels.
    pub layers: Vec<ParallaxLayer>,
    /// Every layer's heights, layer i in channel i ([`pack_layer_heights`](super::pack_layer_heights)):
    /// a march step reads them all with one fetch where the layers tile alike.
    pub heights: Handle<Image>,
    /// The weights that mix them.
    pub weights: LayerWeights,
}

impl ParallaxLayers {
    /// `layers` with their heights packed into one image (added to `images`): a layer without
    /// a height field is flat at the top.
    ///
    /// # Errors
    /// [`LayerError`](super::LayerError) for no layers or more than [`MAX_LAYERS`].
    pub fn new(
        images: &mut crate::Assets<Image>,
        layers: Vec<(ParallaxLayer, Option<&HeightField>)>,
        weights: LayerWeights,
    ) -> Result<Self, super::LayerError> {
        let fields: Vec<Option<&HeightField>> = layers.iter().map(|(_, field)| *field).collect();
        let packed = super::pack_layer_heights(&fields)?;
        Ok(Self {
            layers: layers.into_iter().map(|(layer, _)| layer).collect(),
            heights: images.add(packed),
            weights,
        })
    }

    /// The layers the material draws: the first [`MAX_LAYERS`].
    pub fn drawn(&self) -> &[ParallaxLayer] {
        &self.layers[..self.layers.len().min(MAX_LAYERS)]
    }
}

/// A problem of a material's layers.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum LayersError {
    /// More layers than the material mixes.
    #[error(
        "{count} layers given: a layered material mixes at most {MAX_LAYERS} (the rest are left out)"
    )]
    TooMany {
        /// How many were given.
        count: usize,
    },
    /// A list of no layers.
    #[error("layers is an empty list: a layered material needs at least one layer")]
    Empty,
    /// A layer's value is not finite or out of its range.
    #[error("layers[{layer}].{field} is {value} but must be within {min}..={max}")]
    OutOfRange {
        /// The layer's index.
        layer: usize,
        /// `tiling` or `height_scale`.
        field: &'static str,
        /// Its value.
        value: f32,
        /// The smallest allowed.
        min: f32,
        /// The largest allowed.
        max: f32,
    },
}

/// Each layer field's name, value and limits, for a layer of `tiling` and depth share
/// `height_scale`.
fn layer_values(tiling: f32, height_scale: f32) -> [(&'static str, f32, f32, f32); 2] {
    let (fewest, most) = LAYER_TILING_LIMITS;
    [
        ("tiling", tiling, fewest, most),
        (
            "height_scale",
            height_scale,
            LAYER_DEPTH_LIMITS.0,
            LAYER_DEPTH_LIMITS.1,
        ),
    ]
}

/// Every problem of `layers`, in order.
pub(super) fn layer_problems(layers: &ParallaxLayers) -> Vec<LayersError> {
    let values: Vec<(f32, f32)> = layers
        .layers
        .iter()
        .map(|layer| (layer.tiling, layer.height_scale))
        .collect();
    layer_value_problems(&values)
}

/// Every problem of a list of layers given as their (tiling, depth share), in order: its
/// length, then the values of the first [`MAX_LAYERS`].
pub(super) fn layer_value_problems(layers: &[(f32, f32)]) -> Vec<LayersError> {
    let mut problems = Vec::new();
    if layers.is_empty() {
        problems.push(LayersError::Empty);
    }
    if layers.len() > MAX_LAYERS {
        problems.push(LayersError::TooMany {
            count: layers.len(),
        });
    }
    for (index, &(tiling, height_scale)) in layers.iter().take(MAX_LAYERS).enumerate() {
        for (field, value, min, max) in layer_values(tiling, height_scale) {
            if !(min..=max).contains(&value) {
                problems.push(LayersError::OutOfRange {
                    layer: index,
                    field,
                    value,
                    min,
                    max,
                });
            }
        }
    }
    problems
}

/// Whether `layers` has no problem (no allocation).
pub(super) fn layers_are_valid(layers: &ParallaxLayers) -> bool {
    (1..=MAX_LAYERS).contains(&layers.layers.len())
        && layers.layers.iter().all(|layer| {
            layer_values(layer.tiling, layer.height_scale)
                .iter()
                .all(|(_, value, min, max)| (*min..=*max).contains(value))
        })
}

/// `layers` drawable: the first four, each value clamped (NaN the default).
pub(super) fn sanitized_layers(layers: &ParallaxLayers) -> ParallaxLayers {
    let defaults = ParallaxLayer::default();
    let clamp = |value: f32, default: f32, min: f32, max: f32| {
        if value.is_nan() {
            default
        } else {
            value.clamp(min, max)
        }
    };
    let ((fewest, most), (shallowest, deepest)) = (LAYER_TILING_LIMITS, LAYER_DEPTH_LIMITS);
    ParallaxLayers {
        layers: layers
            .drawn()
            .iter()
            .map(|layer| ParallaxLayer {
                tiling: clamp(layer.tiling, defaults.tiling, fewest, most),
                height_scale: clamp(
                    layer.height_scale,
                    defaults.height_scale,
                    shallowest,
                    deepest,
                ),
                ..layer.clone()
            })
            .collect(),
        heights: layers.heights.clone(),
        weights: layers.weights.clone(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Assets, HeightField};

    fn layers(count: usize) -> ParallaxLayers {
        let mut images = Assets::<Image>::default();
        let field = HeightField::from_fn(2, 2, |u, _| u);
        ParallaxLayers::new(
            &mut images,
            vec![(ParallaxLayer::default(), Some(&field))],
            LayerWeights::VertexColors,
        )
        .map(|mut one| {
            one.layers = vec![ParallaxLayer::default(); count];
            one
        })
        .unwrap()
    }

    #[test]
    fn more_than_four_layers_is_an_error_and_the_first_four_are_drawn() {
        let five = layers(5);
        assert_eq!(
            layer_problems(&five)
                .iter()
                .map(ToString::to_string)
                .collect::<Vec<_>>(),
            ["5 layers given: a layered material mixes at most 4 (the rest are left out)"]
        );
        assert!(!layers_are_valid(&five));
        let clean = sanitized_layers(&five);
        assert_eq!(clean.layers.len(), 4);
        assert!(layers_are_valid(&clean));
    }

    #[test]
    fn no_layers_is_an_error() {
        let none = layers(0);
        assert_eq!(layer_problems(&none), [LayersError::Empty]);
        assert!(!layers_are_valid(&none));
    }

    #[test]
    fn out_of_range_or_nan_layer_values_are_named_and_clamped() {
        let mut bad = layers(3);
        bad.layers[1].tiling = 0.0;
        bad.layers[2].height_scale = f32::NAN;
        let messages: Vec<String> = layer_problems(&bad)
            .iter()
            .map(ToString::to_string)
            .collect();
        assert_eq!(
            messages,
            [
                "layers[1].tiling is 0 but must be within 0.0009765625..=1024",
                "layers[2].height_scale is NaN but must be within 0..=1",
            ]
        );
        let clean = sanitized_layers(&bad);
        assert_eq!(clean.layers[1].tiling, LAYER_TILING_LIMITS.0);
        assert_eq!(clean.layers[2].height_scale, 1.0);
        assert!(layers_are_valid(&clean));
    }
}
