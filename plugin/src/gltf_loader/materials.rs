//! glTF materials to [`LitMaterial`] and [`ParallaxOcclusionMaterial`].

use std::collections::HashMap;

use glam::{Affine2, Vec2};

use super::extras::{PomExtras, choose};
use super::layer_extras::LayerExtras;
use super::textures::TextureCache;
use super::{GltfError, Source, describe};
use crate::parallax::MAX_LAYERS;
use crate::{
    AlphaMode, Assets, Channel, Color, Handle, HeightConvention, HeightField, HeightSource, Image,
    LayerWeights, LightingModel, LitMaterial, ParallaxLayer, ParallaxLayers,
    ParallaxOcclusionMaterial, TextureKind,
};

/// A material as loaded: one of the two kinds the renderer draws, plus the texture-coordinate
/// transform (`KHR_texture_transform`) to bake into the meshes that use it.
#[derive(Clone, Debug)]
pub(super) struct LoadedMaterial {
    pub kind: MaterialComponent,
    pub uv_transform: Affine2,
}

#[derive(Clone, Debug)]
pub(super) enum MaterialComponent {
    Lit(LitMaterial),
    Parallax(ParallaxOcclusionMaterial),
}

/// Materials and decoded images by index, so each is loaded once.
#[derive(Default)]
pub(super) struct MaterialCache {
    materials: HashMap<Option<usize>, LoadedMaterial>,
    textures: TextureCache,
}

impl MaterialCache {
    /// The material of a primitive (`None` = glTF's default material).
    pub fn material(
        &mut self,
        source: &Source,
        images: &mut Assets<Image>,
        material: gltf::Material<'_>,
        warnings: &mut Vec<String>,
    ) -> Result<LoadedMaterial, GltfError> {
        let key = material.index();
        if let Some(loaded) = self.materials.get(&key) {
            return Ok(loaded.clone());
        }
        let mut conversion = Conversion {
            source,
            images,
            textures: &mut self.textures,
            name: describe(material.name(), key.unwrap_or(usize::MAX)),
        };
        let loaded = conversion.convert(&material, warnings)?;
        self.materials.insert(key, loaded.clone());
        Ok(loaded)
    }
}

/// What both kinds of material take from a glTF material.
struct Surface {
    base_color: Color,
    base_color_texture: Option<Handle<Image>>,
    normal_map: Option<Handle<Image>>,
    normal_strength: f32,
    roughness: f32,
    metallic: f32,
    double_sided: bool,
}

/// What only a [`LitMaterial`] draws (a parallax material warns that it leaves it out).
struct LitOnly {
    emissive_texture: Option<Handle<Image>>,
    emissive: Color,
    emissive_strength: f32,
    occlusion_texture: Option<Handle<Image>>,
    occlusion_strength: f32,
    alpha_mode: AlphaMode,
    alpha_cutoff: f32,
    unlit: bool,
}

/// The largest texture-coordinate scale or offset `KHR_texture_transform` may give: 2²⁴, past
/// which an `f32` coordinate has no fraction left, so every pixel would read one texel.
const MAX_UV_TRANSFORM: f32 = 16_777_216.0;

/// The renderer samples every map of a material with the same coordinates, so the base colour
/// texture's transform (T · R · S, as the extension defines it) applies to all. A value that
/// is not finite, or a scale or offset over [`MAX_UV_TRANSFORM`], is named in the error.
fn uv_transform_of(material: &gltf::Material<'_>) -> Result<Affine2, String> {
    let Some(transform) = material
        .pbr_metallic_roughness()
        .base_color_texture()
        .and_then(|info| info.texture_transform())
    else {
        return Ok(Affine2::IDENTITY);
    };
    for (field, values) in [("scale", transform.scale()), ("offset", transform.offset())] {
        if !values.iter().all(|v| v.abs() <= MAX_UV_TRANSFORM) {
            return Err(format!(
                "KHR_texture_transform {field} {values:?} is not finite or beyond ±{MAX_UV_TRANSFORM}"
            ));
        }
    }
    if !transform.rotation().is_finite() {
        return Err(format!(
            "KHR_texture_transform rotation {} is not finite",
            transform.rotation()
        ));
    }
    Ok(Affine2::from_scale_angle_translation(
        Vec2::from(transform.scale()),
        transform.rotation(),
        Vec2::from(transform.offset()),
    ))
}

/// One glTF material being converted: the file, the image store and cache its textures go to,
/// and its name for messages. Textures load in the order the material's parts are read.
struct Conversion<'a> {
    source: &'a Source,
    images: &'a mut Assets<Image>,
    textures: &'a mut TextureCache,
    name: String,
}

impl Conversion<'_> {
    /// A problem of this material.
    fn error(&self, reason: String) -> GltfError {
        GltfError::Material {
            path: self.source.path.clone(),
            material: self.name.clone(),
            reason,
        }
    }

    /// The image of a texture slot the material may leave empty.
    fn optional_texture(
        &mut self,
        texture: Option<gltf::Texture<'_>>,
        kind: TextureKind,
    ) -> Result<Option<Handle<Image>>, GltfError> {
        self.textures
            .optional_texture(self.source, self.images, texture, kind)
    }

    /// The surface and lit-only parts, then the kind the material's extras ask for.
    fn convert(
        &mut self,
        material: &gltf::Material<'_>,
        warnings: &mut Vec<String>,
    ) -> Result<LoadedMaterial, GltfError> {
        let surface = self.surface(material)?;
        let uv_transform = uv_transform_of(material).map_err(|reason| self.error(reason))?;
        let lit_only = self.lit_only(material)?;
        let extras = PomExtras::from_extras(material.extras().as_deref().map(|raw| raw.get()))
            .map_err(|reason| self.error(reason))?;
        let kind = match extras {
            None => MaterialComponent::Lit(self.lit(material, surface, lit_only)?),
            Some(pom) => MaterialComponent::Parallax(
                self.parallax(material, &pom, surface, &lit_only, warnings)?,
            ),
        };
        Ok(LoadedMaterial { kind, uv_transform })
    }

    /// Base colour and normal map (loaded in this order) and the factors both kinds use.
    fn surface(&mut self, material: &gltf::Material<'_>) -> Result<Surface, GltfError> {
        let pbr = material.pbr_metallic_roughness();
        let [r, g, b, a] = pbr.base_color_factor();
        let base_color_texture = self.optional_texture(
            pbr.base_color_texture().map(|info| info.texture()),
            TextureKind::Color,
        )?;
        let normal_info = material.normal_texture();
        let normal_map = self.optional_texture(
            normal_info.as_ref().map(|info| info.texture()),
            TextureKind::Normal,
        )?;
        Ok(Surface {
            base_color: Color { r, g, b, a },
            base_color_texture,
            normal_map,
            normal_strength: normal_info.as_ref().map_or(1.0, |info| info.scale()),
            roughness: pbr.roughness_factor(),
            metallic: pbr.metallic_factor(),
            double_sided: material.double_sided(),
        })
    }

    /// Emission and occlusion (loaded in this order), alpha mode and unlit.
    fn lit_only(&mut self, material: &gltf::Material<'_>) -> Result<LitOnly, GltfError> {
        let emissive_texture = self.optional_texture(
            material.emissive_texture().map(|info| info.texture()),
            TextureKind::Color,
        )?;
        let occlusion_info = material.occlusion_texture();
        let occlusion_texture = self.optional_texture(
            occlusion_info.as_ref().map(|info| info.texture()),
            TextureKind::Data,
        )?;
        let (alpha_mode, alpha_cutoff) = self.alpha(material)?;
        let [er, eg, eb] = material.emissive_factor();
        Ok(LitOnly {
            emissive_texture,
            emissive: Color::linear_rgb(er, eg, eb),
            emissive_strength: material.emissive_strength().unwrap_or(1.0),
            occlusion_texture,
            occlusion_strength: occlusion_info
                .as_ref()
                .map_or(1.0, |info| info.strength().clamp(0.0, 1.0)),
            alpha_mode,
            alpha_cutoff,
            unlit: material.unlit(),
        })
    }

    /// The alpha mode, and the cutoff of a mask (which must lie in 0..=1).
    fn alpha(&self, material: &gltf::Material<'_>) -> Result<(AlphaMode, f32), GltfError> {
        Ok(match material.alpha_mode() {
            gltf::material::AlphaMode::Mask => {
                let cutoff = material.alpha_cutoff().unwrap_or(0.5);
                if !(0.0..=1.0).contains(&cutoff) {
                    return Err(self.error(format!("alphaCutoff {cutoff} is outside 0..=1")));
                }
                (AlphaMode::Mask, cutoff)
            }
            gltf::material::AlphaMode::Blend => (AlphaMode::Blend, 0.5),
            gltf::material::AlphaMode::Opaque => (AlphaMode::Opaque, 0.5),
        })
    }

    /// A material without POM extras: lit, with its metallic-roughness texture loaded last.
    fn lit(
        &mut self,
        material: &gltf::Material<'_>,
        surface: Surface,
        lit: LitOnly,
    ) -> Result<LitMaterial, GltfError> {
        let metallic_roughness = material
            .pbr_metallic_roughness()
            .metallic_roughness_texture();
        Ok(LitMaterial {
            base_color: surface.base_color,
            base_color_texture: surface.base_color_texture,
            normal_map: surface.normal_map,
            normal_strength: surface.normal_strength,
            lighting: LightingModel::GgxLambert,
            roughness: surface.roughness,
            metallic: surface.metallic,
            metallic_roughness_texture: self.optional_texture(
                metallic_roughness.map(|info| info.texture()),
                TextureKind::Data,
            )?,
            double_sided: surface.double_sided,
            emissive_texture: lit.emissive_texture,
            occlusion_texture: lit.occlusion_texture,
            occlusion_strength: lit.occlusion_strength,
            emissive: lit.emissive,
            emissive_strength: lit.emissive_strength,
            unlit: lit.unlit,
            alpha_mode: lit.alpha_mode,
            alpha_cutoff: lit.alpha_cutoff,
            ..LitMaterial::default()
        })
    }

    /// A material with POM extras: its height map, the extras' parameters, validated.
    fn parallax(
        &mut self,
        material: &gltf::Material<'_>,
        pom: &PomExtras,
        surface: Surface,
        lit: &LitOnly,
        warnings: &mut Vec<String>,
    ) -> Result<ParallaxOcclusionMaterial, GltfError> {
        let (height_map, layers) = match &pom.layers {
            Some(list) => (None, Some(self.layers(list, pom.layer_weights_texture)?)),
            None => (
                Some(self.height_map(pom, surface.normal_map.is_some())?),
                None,
            ),
        };
        let mut parallax = ParallaxOcclusionMaterial {
            base_color: surface.base_color,
            base_color_texture: surface.base_color_texture,
            normal_map: surface.normal_map,
            height_map,
            layers,
            // glTF's own BRDF, driven by the roughness and metallic factors, unless the extras
            // say otherwise.
            lighting: LightingModel::GgxLambert,
            roughness: surface.roughness,
            metallic: surface.metallic,
            normal_strength: surface.normal_strength,
            double_sided: surface.double_sided,
            ..ParallaxOcclusionMaterial::default()
        };
        self.warn_left_out(material, lit, warnings);
        pom.apply(&mut parallax)
            .map_err(|reason| self.error(reason))?;
        parallax
            .validate()
            .map_err(|problem| self.error(format!("extras.pom: {problem}")))?;
        Ok(parallax)
    }

    /// Where a parallax material's heights come from: the normal map's alpha, or a channel of
    /// the texture the extras name.
    fn height_map(
        &mut self,
        pom: &PomExtras,
        has_normal_map: bool,
    ) -> Result<HeightSource, GltfError> {
        let source = self.source;
        match (pom.height_in_normal_alpha, pom.height_texture) {
            (true, _) if !has_normal_map => {
                Err(self.error("extras.pom.height_in_normal_alpha needs a normal texture".into()))
            }
            (true, _) => Ok(HeightSource::NormalMapAlpha),
            (false, Some(index)) => {
                let texture = source.document.textures().nth(index).ok_or_else(|| {
                    self.error(format!(
                        "extras.pom.height_texture is {index} but the file has {} textures",
                        source.document.textures().len()
                    ))
                })?;
                let channel = choose(
                    "height_channel",
                    &pom.height_channel,
                    &[
                        ("r", Channel::Red),
                        ("g", Channel::Green),
                        ("b", Channel::Blue),
                        ("a", Channel::Alpha),
                    ],
                    Channel::Red,
                )
                .map_err(|reason| self.error(reason))?;
                let height = self.textures.texture(
                    source,
                    self.images,
                    texture,
                    TextureKind::Height,
                    channel,
                )?;
                Ok(HeightSource::Texture(height))
            }
            (false, None) => Err(self
                .error("extras.pom needs height_texture (or height_in_normal_alpha: true)".into())),
        }
    }

    /// The file's texture `index`, decoded for `kind`; `key` names it in errors.
    fn indexed_texture(
        &mut self,
        key: &str,
        index: usize,
        kind: TextureKind,
    ) -> Result<Handle<Image>, GltfError> {
        let source = self.source;
        let texture = source.document.textures().nth(index).ok_or_else(|| {
            self.error(format!(
                "extras.pom.{key} is {index} but the file has {} textures",
                source.document.textures().len()
            ))
        })?;
        self.textures
            .texture(source, self.images, texture, kind, Channel::Red)
    }

    /// A layered material's layers: each one's maps, their heights packed, and the weight map
    /// (the vertex colours without one).
    fn layers(
        &mut self,
        list: &[LayerExtras],
        weights: Option<usize>,
    ) -> Result<ParallaxLayers, GltfError> {
        if list.is_empty() || list.len() > MAX_LAYERS {
            return Err(self.error(format!(
                "extras.pom.layers has {} layers; a layered material has 1 to {MAX_LAYERS}",
                list.len()
            )));
        }
        let mut layers = Vec::with_capacity(list.len());
        let mut fields = Vec::with_capacity(list.len());
        for (index, layer) in list.iter().enumerate() {
            let mut map = |key: &str, texture: Option<usize>, kind| {
                texture
                    .map(|texture| {
                        self.indexed_texture(&format!("layers[{index}].{key}"), texture, kind)
                    })
                    .transpose()
            };
            let base_color_texture = map(
                "base_color_texture",
                layer.base_color_texture,
                TextureKind::Color,
            )?;
            let normal_map = map("normal_texture", layer.normal_texture, TextureKind::Normal)?;
            let height = map("height_texture", layer.height_texture, TextureKind::Height)?;
            fields.push(height.and_then(|height| {
                let image = self.images.get(&height)?;
                Some(HeightField::from_image(
                    image,
                    Channel::Red,
                    HeightConvention::Height,
                ))
            }));
            let defaults = ParallaxLayer::default();
            layers.push(ParallaxLayer {
                base_color_texture,
                normal_map,
                tiling: layer.tiling.unwrap_or(defaults.tiling),
                height_scale: layer.height_scale.unwrap_or(defaults.height_scale),
            });
        }
        let weights = match weights {
            Some(index) => LayerWeights::Texture(self.indexed_texture(
                "layer_weights_texture",
                index,
                TextureKind::Data,
            )?),
            None => LayerWeights::VertexColors,
        };
        let layers = layers
            .into_iter()
            .zip(fields.iter().map(Option::as_ref))
            .collect();
        ParallaxLayers::new(self.images, layers, weights)
            .map_err(|error| self.error(format!("extras.pom.layers: {error}")))
    }

    /// What the parallax material does not have yet is said, not dropped silently.
    fn warn_left_out(
        &self,
        material: &gltf::Material<'_>,
        lit: &LitOnly,
        warnings: &mut Vec<String>,
    ) {
        let name = &self.name;
        if lit.emissive_texture.is_some() || lit.emissive != Color::linear_rgb(0.0, 0.0, 0.0) {
            warnings.push(format!(
                "material {name}: emission is not supported on parallax materials; ignored"
            ));
        }
        if material
            .pbr_metallic_roughness()
            .metallic_roughness_texture()
            .is_some()
        {
            warnings.push(format!(
                "material {name}: metallicRoughnessTexture is not supported on parallax materials; its roughness and metallic factors are used"
            ));
        }
        if lit.alpha_mode != AlphaMode::Opaque || lit.unlit {
            warnings.push(format!(
                "material {name}: alpha mask, alpha blend and unlit are not supported on parallax materials; drawn opaque and lit"
            ));
        }
    }
}
