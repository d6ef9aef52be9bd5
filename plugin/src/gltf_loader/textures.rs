//! glTF textures to [`Image`]s: pixel formats, samplers, and a cache so that each image is
//! decoded once per way it is used.

use std::collections::HashMap;

use image::DynamicImage;

use super::{GltfError, Source, describe};
use crate::{Assets, Channel, FilterMode, Handle, Image, ImageSampler, TextureKind, WrapMode};

/// Decoded images by glTF image, kind, height channel and sampler.
#[derive(Default)]
pub(super) struct TextureCache {
    images: HashMap<(usize, TextureKind, Channel, ImageSampler), Handle<Image>>,
}

/// glTF's decoded pixels as an image of the same layout (`None` where they are fewer than the
/// size needs).
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

impl TextureCache {
    /// The image of `texture`, decoded for `kind` (and `channel` for heights), added to `images`.
    pub(super) fn texture(
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

    /// [`TextureCache::texture`] of a texture slot the material may leave empty (red channel:
    /// only height maps choose another).
    pub(super) fn optional_texture(
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
}
