//! glTF materials and textures to [`LitMaterial`] and [`ParallaxOcclusionMaterial`].

use std::collections::HashMap;

use glam::{Affine2, Vec2};
use image::DynamicImage;

use super::extras::{PomExtras, choose};
use super::{GltfError, Source, describe};
use crate::{
    AlphaMode, Assets, Channel, Color, FilterMode, Handle, HeightSource, Image, ImageSampler,
    LightingModel, LitMaterial, ParallaxOcclusionMaterial, TextureKind, WrapMode,
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
    images: HashMap<(usize, TextureKind, Channel, ImageSampler), Handle<Image>>,
}

fn to_dynamic(data: gltf::image::Data) -> Option<DynamicImage> {
    use gltf::image::Format;
    let (width, height) = (data.width, data.height);
    let sixteen = |bytes: &[u8]| -> Vec<u16> {
        bytes
            .chunks_exact(2)
            .map(|pair| u16::from_ne_bytes([pair[0], pair[1]]))
            .collect()
    };
    let float = |bytes: &[u8]| -> Vec<f32> {
        bytes
            .chunks_exact(4)
            .map(|quad| f32::from_ne_bytes([quad[0], quad[1], quad[2], quad[3]]))
            .collect()
    };
    Some(match data.format {
        Format::R8 => {
            DynamicImage::ImageLuma8(image::ImageBuffer::from_raw(width, height, data.pixels)?)
        }
        Format::R8G8 => {
            DynamicImage::ImageLumaA8(image::ImageBuffer::from_raw(width, height, data.pixels)?)
        }
        Format::R8G8B8 => {
            DynamicImage::ImageRgb8(image::ImageBuffer::from_raw(width, height, data.pixels)?)
        }
        Format::R8G8B8A8 => {
            DynamicImage::ImageRgba8(image::ImageBuffer::from_raw(width, height, data.pixels)?)
        }
        Format::R16 => DynamicImage::ImageLuma16(image::ImageBuffer::from_raw(
            width,
            height,
            sixteen(&data.pixels),
        )?),
        Format::R16G16 => DynamicImage::ImageLumaA16(image::ImageBuffer::from_raw(
            width,
            height,
            sixteen(&data.pixels),
        )?),
        Format::R16G16B16 => DynamicImage::ImageRgb16(image::ImageBuffer::from_raw(
            width,
            height,
            sixteen(&data.pixels),
        )?),
        Format::R16G16B16A16 => DynamicImage::ImageRgba16(image::ImageBuffer::from_raw(
            width,
            height,
            sixteen(&data.pixels),
        )?),
        Format::R32G32B32FLOAT => DynamicImage::ImageRgb32F(image::ImageBuffer::from_raw(
            width,
            height,
            float(&data.pixels),
        )?),
        Format::R32G32B32A32FLOAT => DynamicImage::ImageRgba32F(image::ImageBuffer::from_raw(
            width,
            height,
            float(&data.pixels),
        )?),
    })
}

/// A glTF sampler as the renderer samples: wrap modes as given; no filter given is linear.
fn sampler_of(sampler: &gltf::texture::Sampler<'_>) -> ImageSampler {
    use gltf::texture::{MagFilter, MinFilter, WrappingMode};
    let wrap = |mode| match mode {
        WrappingMode::Repeat => WrapMode::Repeat,
        WrappingMode::MirroredRepeat => WrapMode::MirroredRepeat,
        WrappingMode::ClampToEdge => WrapMode::ClampToEdge,
    };
    let (min_filter, mipmap_filter) = match sampler.min_filter() {
        Some(MinFilter::Nearest | MinFilter::NearestMipmapNearest) => {
            (FilterMode::Nearest, FilterMode::Nearest)
        }
        Some(MinFilter::NearestMipmapLinear) => (FilterMode::Nearest, FilterMode::Linear),
        Some(MinFilter::LinearMipmapNearest) => (FilterMode::Linear, FilterMode::Nearest),
        Some(MinFilter::Linear | MinFilter::LinearMipmapLinear) | None => {
            (FilterMode::Linear, FilterMode::Linear)
        }
    };
    ImageSampler {
        wrap_u: wrap(sampler.wrap_s()),
        wrap_v: wrap(sampler.wrap_t()),
        mag_filter: match sampler.mag_filter() {
            Some(MagFilter::Nearest) => FilterMode::Nearest,
            Some(MagFilter::Linear) | None => FilterMode::Linear,
        },
        min_filter,
        mipmap_filter,
    }
}

impl MaterialCache {
    /// The image of `texture`, decoded for `kind` (and `channel` for heights), added to `images`.
    fn texture(
        &mut self,
        source: &Source,
        images: &mut Assets<Image>,
        texture: gltf::Texture<'_>,
        kind: TextureKind,
        channel: Channel,
    ) -> Result<Handle<Image>, GltfError> {
        let image = texture.source();
        let sampler = sampler_of(&texture.sampler());
        let key = (image.index(), kind, channel, sampler);
        if let Some(handle) = self.images.get(&key) {
            return Ok(handle.clone());
        }
        let name = describe(image.name(), image.index());
        let image_error = |reason: String| GltfError::Image {
            path: source.path.clone(),
            image: name.clone(),
            reason,
        };
        // A file the image names is reported by its URI and the path looked at.
        let location = match image.source() {
            gltf::image::Source::Uri { uri, .. } if !uri.starts_with("data:") => {
                let tried = source
                    .base
                    .as_deref()
                    .map(|base| base.join(super::percent_decode(uri)));
                Some(match tried {
                    Some(tried) => format!("{uri} (looked for {})", tried.display()),
                    None => uri.to_owned(),
                })
            }
            _ => None,
        };
        let data =
            gltf::image::Data::from_source(image.source(), source.base.as_deref(), &source.buffers)
                .map_err(|error| match &location {
                    Some(location) => image_error(format!("{location}: {error}")),
                    None => image_error(error.to_string()),
                })?;
        let decoded = to_dynamic(data)
            .ok_or_else(|| image_error("pixel data is shorter than its size".into()))?;
        let loaded = Image::from_decoded(decoded, kind, channel, &name)
            .map_err(|error| image_error(error.to_string()))?
            .with_sampler(sampler);
        let handle = images.add(loaded);
        self.images.insert(key, handle.clone());
        Ok(handle)
    }

    /// [`MaterialCache::texture`] of a texture slot the material may leave empty (red channel:
    /// only height maps choose another).
    fn optional_texture(
        &mut self,
        source: &Source,
        images: &mut Assets<Image>,
        texture: Option<gltf::Texture<'_>>,
        kind: TextureKind,
    ) -> Result<Option<Handle<Image>>, GltfError> {
        texture
            .map(|texture| self.texture(source, images, texture, kind, Channel::Red))
            .transpose()
    }

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
        let name = describe(material.name(), key.unwrap_or(usize::MAX));
        let material_error = |reason: String| GltfError::Material {
            path: source.path.clone(),
            material: name.clone(),
            reason,
        };
        let pbr = material.pbr_metallic_roughness();
        let [r, g, b, a] = pbr.base_color_factor();
        let base_color = Color { r, g, b, a };
        let base_info = pbr.base_color_texture();
        let base_texture = base_info.as_ref().map(|info| info.texture());
        let base_color_texture =
            self.optional_texture(source, images, base_texture, TextureKind::Color)?;
        let normal_info = material.normal_texture();
        let normal_map = self.optional_texture(
            source,
            images,
            normal_info.as_ref().map(|info| info.texture()),
            TextureKind::Normal,
        )?;
        let normal_strength = normal_info.as_ref().map_or(1.0, |info| info.scale());

        // The renderer samples every map of a material with the same coordinates, so the base
        // colour texture's transform (T · R · S, as the extension defines it) applies to all.
        let uv_transform = base_info
            .as_ref()
            .and_then(|info| info.texture_transform())
            .map_or(Affine2::IDENTITY, |t| {
                Affine2::from_scale_angle_translation(
                    Vec2::from(t.scale()),
                    t.rotation(),
                    Vec2::from(t.offset()),
                )
            });

        let emissive_texture = self.optional_texture(
            source,
            images,
            material.emissive_texture().map(|info| info.texture()),
            TextureKind::Color,
        )?;
        let occlusion_info = material.occlusion_texture();
        let occlusion_texture = self.optional_texture(
            source,
            images,
            occlusion_info.as_ref().map(|info| info.texture()),
            TextureKind::Data,
        )?;
        let occlusion_strength = occlusion_info
            .as_ref()
            .map_or(1.0, |info| info.strength().clamp(0.0, 1.0));
        let [er, eg, eb] = material.emissive_factor();
        let emissive = Color::linear_rgb(er, eg, eb);
        let emissive_strength = material.emissive_strength().unwrap_or(1.0);
        let unlit = material.unlit();
        let (alpha_mode, alpha_cutoff) = match material.alpha_mode() {
            gltf::material::AlphaMode::Mask => {
                let cutoff = material.alpha_cutoff().unwrap_or(0.5);
                if !(0.0..=1.0).contains(&cutoff) {
                    return Err(material_error(format!(
                        "alphaCutoff {cutoff} is outside 0..=1"
                    )));
                }
                (AlphaMode::Mask, cutoff)
            }
            gltf::material::AlphaMode::Blend => (AlphaMode::Blend, 0.5),
            gltf::material::AlphaMode::Opaque => (AlphaMode::Opaque, 0.5),
        };

        let metallic_roughness_info = pbr.metallic_roughness_texture();
        let extras = PomExtras::from_extras(material.extras().as_deref().map(|raw| raw.get()))
            .map_err(&material_error)?;
        let roughness = pbr.roughness_factor();
        let kind = match extras {
            None => MaterialComponent::Lit(LitMaterial {
                base_color,
                base_color_texture,
                normal_map,
                normal_strength,
                lighting: LightingModel::GgxLambert,
                roughness,
                metallic: pbr.metallic_factor(),
                metallic_roughness_texture: self.optional_texture(
                    source,
                    images,
                    metallic_roughness_info.map(|info| info.texture()),
                    TextureKind::Data,
                )?,
                double_sided: material.double_sided(),
                emissive_texture,
                occlusion_texture,
                occlusion_strength,
                emissive,
                emissive_strength,
                unlit,
                alpha_mode,
                alpha_cutoff,
                ..LitMaterial::default()
            }),
            Some(pom) => {
                let height_map = match (pom.height_in_normal_alpha, pom.height_texture) {
                    (true, _) => {
                        if normal_map.is_none() {
                            return Err(material_error(
                                "extras.pom.height_in_normal_alpha needs a normal texture".into(),
                            ));
                        }
                        HeightSource::NormalMapAlpha
                    }
                    (false, Some(index)) => {
                        let texture = source.document.textures().nth(index).ok_or_else(|| {
                            material_error(format!(
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
                        .map_err(&material_error)?;
                        HeightSource::Texture(self.texture(
                            source,
                            images,
                            texture,
                            TextureKind::Height,
                            channel,
                        )?)
                    }
                    (false, None) => {
                        return Err(material_error(
                            "extras.pom needs height_texture (or height_in_normal_alpha: true)"
                                .into(),
                        ));
                    }
                };
                let mut material = ParallaxOcclusionMaterial {
                    base_color,
                    base_color_texture,
                    normal_map,
                    height_map: Some(height_map),
                    // glTF's own BRDF, driven by the roughness and metallic factors, unless
                    // the extras say otherwise.
                    lighting: LightingModel::GgxLambert,
                    roughness,
                    metallic: pbr.metallic_factor(),
                    normal_strength,
                    double_sided: material.double_sided(),
                    ..ParallaxOcclusionMaterial::default()
                };
                // What the parallax material does not have yet is said, not dropped silently.
                if emissive_texture.is_some() || emissive != Color::linear_rgb(0.0, 0.0, 0.0) {
                    warnings.push(format!(
                        "material {name}: emission is not supported on parallax materials; ignored"
                    ));
                }
                if metallic_roughness_info.is_some() {
                    warnings.push(format!(
                        "material {name}: metallicRoughnessTexture is not supported on parallax materials; its roughness and metallic factors are used"
                    ));
                }
                if alpha_mode != AlphaMode::Opaque || unlit {
                    warnings.push(format!(
                        "material {name}: alpha mask, alpha blend and unlit are not supported on parallax materials; drawn opaque and lit"
                    ));
                }
                pom.apply(&mut material).map_err(&material_error)?;
                material
                    .validate()
                    .map_err(|problem| material_error(format!("extras.pom: {problem}")))?;
                MaterialComponent::Parallax(material)
            }
        };
        let loaded = LoadedMaterial { kind, uv_transform };
        self.materials.insert(key, loaded.clone());
        Ok(loaded)
    }
}
