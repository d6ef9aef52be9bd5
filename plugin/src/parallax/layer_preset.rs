//! A layered material's layers in a RON preset, by glTF's keys: `layers`, a list of each layer's
//! `tiling` and `height_scale` (its depth share) and, optionally, its maps' files
//! (`base_color_texture`, `normal_texture`, `height_texture`), and `layer_weights_texture`, the
//! weight map's file. Applying a preset sets the tiling and depth of the layers a material has
//! (the sandbox saves and loads those); [`PomPreset::read_layer_files`] reads the layers' maps
//! from the files, relative to the preset's folder, and [`LayerFiles::into_layers`] makes the
//! layers of them (`sandbox render --preset`, scene scripts).
//!
//! ```ron
//! (height_scale: 0.06, layer_blend_contrast: 0.6,
//!  layers: [(base_color_texture: "rock.png", height_texture: "rock_height.png", tiling: 8),
//!           (base_color_texture: "grass.png", height_texture: "grass_height.png", tiling: 16, height_scale: 0.5)],
//!  layer_weights_texture: "weights.png")
//! ```

use std::path::Path;

use serde::{Deserialize, Serialize};

use super::layers::layer_value_problems;
use super::material::{ParallaxOcclusionMaterial, PomMaterialError, PomPreset};
use super::{LayerWeights, ParallaxLayer, ParallaxLayers, PresetError};
use crate::files::{FileAccess, resolve_inside};
use crate::material::PresetExtras;
use crate::{Assets, Channel, HeightConvention, HeightField, Image, TextureKind};

/// One layer of a preset: its tiling and depth share, and the files of its maps (relative to
/// the preset's folder; absent: none).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct LayerPreset {
    /// The layer's colour map (sRGB).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub base_color_texture: Option<String>,
    /// The layer's normal map (OpenGL convention).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub normal_texture: Option<String>,
    /// The layer's height map (red channel, white the top).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub height_texture: Option<String>,
    /// Repeats of the layer's maps across the mesh's texture coordinates 0..1.
    pub tiling: f32,
    /// The layer's relief depth as a share of the material's `height_scale` (0..=1).
    pub height_scale: f32,
}

impl Default for LayerPreset {
    fn default() -> Self {
        let layer = ParallaxLayer::default();
        Self {
            base_color_texture: None,
            normal_texture: None,
            height_texture: None,
            tiling: layer.tiling,
            height_scale: layer.height_scale,
        }
    }
}

impl PresetExtras<PomPreset> for ParallaxOcclusionMaterial {
    /// The layers' tiling and depth shares (their maps are handles: no file to name).
    fn write_extras(&self, preset: &mut PomPreset) {
        preset.layers = self.layers.as_ref().map(|layers| {
            layers
                .layers
                .iter()
                .map(|layer| LayerPreset {
                    tiling: layer.tiling,
                    height_scale: layer.height_scale,
                    ..LayerPreset::default()
                })
                .collect()
        });
        preset.layer_weights_texture = None;
    }

    /// Each layer the material has takes the tiling and depth share of the preset's layer at
    /// its place; its maps stay.
    fn read_extras(&mut self, preset: &PomPreset) {
        if let (Some(layers), Some(presets)) = (self.layers.as_mut(), preset.layers.as_ref()) {
            for (layer, preset) in layers.layers.iter_mut().zip(presets) {
                layer.tiling = preset.tiling;
                layer.height_scale = preset.height_scale;
            }
        }
    }
}

impl PomPreset {
    /// The first problem of the preset's layers (their count, tiling and depth shares).
    pub(super) fn layers_problem(&self) -> Option<PomMaterialError> {
        let values: Vec<(f32, f32)> = self
            .layers
            .as_ref()?
            .iter()
            .map(|layer| (layer.tiling, layer.height_scale))
            .collect();
        layer_value_problems(&values)
            .into_iter()
            .next()
            .map(PomMaterialError::from)
    }

    /// Whether the preset names any file of layers.
    fn names_layer_files(&self) -> bool {
        self.layer_weights_texture.is_some()
            || self.layers.iter().flatten().any(|layer| {
                layer.base_color_texture.is_some()
                    || layer.normal_texture.is_some()
                    || layer.height_texture.is_some()
            })
    }

    /// [`PomPreset::read_layer_files`] relative to the folder of `path`, the preset's own file
    /// (the current folder for a bare file name).
    ///
    /// # Errors
    /// As [`PomPreset::read_layer_files`].
    pub fn read_layer_files_beside(
        &self,
        path: &Path,
        access: FileAccess,
    ) -> Result<Option<LayerFiles>, PresetError> {
        let folder = path
            .parent()
            .filter(|parent| !parent.as_os_str().is_empty())
            .unwrap_or(Path::new("."));
        self.read_layer_files(folder, access)
    }

    /// The layers the preset describes, their maps decoded from the files it names (relative
    /// to `folder`, the preset's; with [`FileAccess::InsideFolder`] each a regular file inside
    /// it); weighed by the weight map it names, else the vertex colours. `None` when it names
    /// no file (its layers' tiling and depth then apply to the layers a material has, through
    /// `apply_preset`). Nothing touches the GPU: [`LayerFiles::into_layers`] adds them.
    ///
    /// # Errors
    /// [`PresetError::Layers`] naming the file that is outside `folder`, missing or not an
    /// image.
    pub fn read_layer_files(
        &self,
        folder: &Path,
        access: FileAccess,
    ) -> Result<Option<LayerFiles>, PresetError> {
        let Some(presets) = self.layers.as_ref().filter(|_| self.names_layer_files()) else {
            return Ok(None);
        };
        let read =
            |name: &Option<String>, kind: TextureKind| -> Result<Option<Image>, PresetError> {
                let Some(name) = name.as_deref() else {
                    return Ok(None);
                };
                let fail = |reason: String| PresetError::Layers {
                    reason: format!("{name:?}: {reason}"),
                };
                let path = resolve_inside(folder, Path::new(name), access)
                    .map_err(|error| fail(error.to_string()))?;
                let image = match kind {
                    TextureKind::Height => Image::load_height(&path, Channel::Red),
                    _ => Image::load(&path, kind),
                };
                image.map(Some).map_err(|error| fail(error.to_string()))
            };
        let mut layers = Vec::new();
        for preset in presets {
            let height = read(&preset.height_texture, TextureKind::Height)?;
            layers.push(LayerFile {
                color: read(&preset.base_color_texture, TextureKind::Color)?,
                normal: read(&preset.normal_texture, TextureKind::Normal)?,
                height: height.map(|image| {
                    HeightField::from_image(&image, Channel::Red, HeightConvention::Height)
                }),
                tiling: preset.tiling,
                height_scale: preset.height_scale,
            });
        }
        Ok(Some(LayerFiles {
            layers,
            weights: read(&self.layer_weights_texture, TextureKind::Data)?,
        }))
    }
}

/// One layer's maps as a preset's files gave them.
#[derive(Debug)]
struct LayerFile {
    color: Option<Image>,
    normal: Option<Image>,
    height: Option<HeightField>,
    tiling: f32,
    height_scale: f32,
}

/// The layers a preset describes with their maps decoded from its files
/// ([`PomPreset::read_layer_files`]), not yet added to an app's images.
#[derive(Debug)]
pub struct LayerFiles {
    layers: Vec<LayerFile>,
    weights: Option<Image>,
}

impl LayerFiles {
    /// The layers, their maps and packed heights added to `images`.
    ///
    /// # Errors
    /// [`LayerError`](super::LayerError) for no layers or more than four (a preset that
    /// loaded has neither).
    pub fn into_layers(
        self,
        images: &mut Assets<Image>,
    ) -> Result<ParallaxLayers, super::LayerError> {
        let mut fields = Vec::new();
        let mut layers = Vec::new();
        for file in self.layers {
            layers.push(ParallaxLayer {
                base_color_texture: file.color.map(|image| images.add(image)),
                normal_map: file.normal.map(|image| images.add(image)),
                tiling: file.tiling,
                height_scale: file.height_scale,
            });
            fields.push(file.height);
        }
        let weights = match self.weights {
            Some(image) => LayerWeights::Texture(images.add(image)),
            None => LayerWeights::VertexColors,
        };
        let list = layers
            .into_iter()
            .zip(fields.iter().map(Option::as_ref))
            .collect();
        ParallaxLayers::new(images, list, weights)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn layered(count: usize) -> ParallaxOcclusionMaterial {
        let mut images = Assets::<Image>::default();
        let field = HeightField::from_fn(2, 2, |u, _| u);
        let layers = (0..count)
            .map(|_| (ParallaxLayer::default(), Some(&field)))
            .collect();
        ParallaxOcclusionMaterial {
            layers: ParallaxLayers::new(&mut images, layers, LayerWeights::VertexColors).ok(),
            ..ParallaxOcclusionMaterial::default()
        }
    }

    #[test]
    fn a_layered_materials_tiling_and_depths_round_trip_through_ron() {
        let mut material = layered(2);
        if let Some(layers) = material.layers.as_mut() {
            layers.layers[0].tiling = 8.0;
            layers.layers[1].height_scale = 0.4;
        }
        let text = material.preset().to_ron();
        assert!(text.contains("layers:"), "{text}");
        let preset = PomPreset::from_ron(&text, "layers.ron").unwrap();
        let mut other = layered(2);
        other.apply_preset(&preset);
        assert_eq!(other.layers, material.layers);
        // A preset without layers leaves a material's layers as they are.
        other.apply_preset(&PomPreset::default());
        assert_eq!(other.layers, material.layers);
        assert!(!PomPreset::default().to_ron().contains("layers"));
    }

    #[test]
    fn bad_layers_in_a_preset_are_named() {
        for (text, message) in [
            (
                "(layers: [(tiling: 0)])",
                "layers[0].tiling is 0 but must be within",
            ),
            (
                "(layers: [(height_scale: 1.5)])",
                "layers[0].height_scale is 1.5 but must be within 0..=1",
            ),
            ("(layers: [])", "layers is an empty list"),
            (
                "(layers: [(), (), (), (), ()])",
                "5 layers given: a layered material mixes at most 4",
            ),
        ] {
            let error = PomPreset::from_ron(text, "bad.ron")
                .unwrap_err()
                .to_string();
            assert!(
                error.starts_with("bad.ron: ") && error.contains(message),
                "{error}"
            );
        }
        let unknown = PomPreset::from_ron("(layers: [(tilling: 2)])", "u.ron")
            .unwrap_err()
            .to_string();
        assert!(unknown.contains("tilling"), "{unknown}");
    }

    #[test]
    fn layers_are_built_from_the_files_a_preset_names_inside_its_folder() {
        let dir = std::env::temp_dir().join(format!("pom-layer-preset-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let height = image::GrayImage::from_fn(8, 8, |x, _| image::Luma([(x * 32) as u8]));
        height.save(dir.join("height.png")).unwrap();
        let weights = image::RgbaImage::from_pixel(4, 4, image::Rgba([255, 0, 0, 0]));
        weights.save(dir.join("weights.png")).unwrap();
        let preset = PomPreset::from_ron(
            "(layers: [(height_texture: \"height.png\", tiling: 4), (tiling: 2)], \
             layer_weights_texture: \"weights.png\")",
            "p.ron",
        )
        .unwrap();
        let mut images = Assets::<Image>::default();
        let layers = preset
            .read_layer_files(&dir, FileAccess::InsideFolder)
            .unwrap()
            .unwrap()
            .into_layers(&mut images)
            .unwrap();
        assert_eq!(layers.layers.len(), 2);
        assert_eq!(
            (layers.layers[0].tiling, layers.layers[1].tiling),
            (4.0, 2.0)
        );
        assert!(matches!(layers.weights, LayerWeights::Texture(_)));
        // Only tiling and depths: nothing to build, they apply to a material's own layers.
        let tilings = PomPreset::from_ron("(layers: [(tiling: 4)])", "t.ron").unwrap();
        assert!(
            tilings
                .read_layer_files(&dir, FileAccess::InsideFolder)
                .unwrap()
                .is_none()
        );
        for (name, rule) in [
            ("../height.png", "`..` leads out of it"),
            ("missing.png", "missing.png"),
        ] {
            let outside =
                PomPreset::from_ron(&format!("(layers: [(height_texture: {name:?})])"), "o.ron")
                    .unwrap();
            let error = outside
                .read_layer_files(&dir, FileAccess::InsideFolder)
                .unwrap_err()
                .to_string();
            assert!(error.contains(name) && error.contains(rule), "{error}");
        }
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
