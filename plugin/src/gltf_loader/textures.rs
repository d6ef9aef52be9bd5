//! glTF textures to [`Image`]s: samplers, and caches so that each file is read and decoded
//! once per load, and converted once per way it is used, within the load's memory budget.

use std::borrow::Cow;
use std::collections::HashMap;
use std::path::PathBuf;

use image::DynamicImage;

use super::{GltfError, Source, describe};
use crate::files::{MAX_IMAGE_FILE_BYTES, read_bounded};
use crate::image::{ImageBudget, decode_bytes};
use crate::{Assets, Channel, FilterMode, Handle, Image, ImageSampler, TextureKind, WrapMode};

/// Where a glTF image's bytes come from: a file (by its resolved path, so entries naming one
/// file share it), or the document itself (a buffer view or a `data:` URI, by image index).
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
enum Origin {
    File(PathBuf),
    Embedded(usize),
}

/// A decoded image, with its file's size for messages.
struct Decoded {
    image: DynamicImage,
    file_bytes: u64,
    name: String,
}

/// Decoded images by origin, and images by origin, kind, height channel and sampler.
#[derive(Default)]
pub(super) struct TextureCache {
    decoded: HashMap<Origin, Decoded>,
    images: HashMap<(Origin, TextureKind, Channel, ImageSampler), Handle<Image>>,
    /// Created at the first image, from the load's options.
    budget: Option<ImageBudget>,
}

/// Where `image`'s bytes come from (the file it names, resolved as the load's options allow).
fn origin(source: &Source, image: &gltf::Image<'_>) -> Result<Origin, String> {
    match image.source() {
        gltf::image::Source::Uri { uri, .. } if !uri.starts_with("data:") => {
            super::locate_uri(source.base.as_deref(), uri, source.options.file_access)
                .map(Origin::File)
        }
        _ => Ok(Origin::Embedded(image.index())),
    }
}

/// An image's encoded bytes, a name for messages, and the format its MIME type or extension gives.
type Encoded<'a> = (Cow<'a, [u8]>, String, Option<image::ImageFormat>);

/// `image`'s encoded bytes, a name for messages, and its format.
fn encoded<'a>(
    source: &'a Source,
    image: &gltf::Image<'_>,
    origin: &Origin,
) -> Result<Encoded<'a>, String> {
    let mime = |mime_type: Option<&str>| mime_type.and_then(image::ImageFormat::from_mime_type);
    match (image.source(), origin) {
        (gltf::image::Source::Uri { uri, mime_type }, Origin::File(path)) => {
            let bytes = read_bounded(path, MAX_IMAGE_FILE_BYTES)
                .map_err(|error| format!("uri {uri:?}: {error}"))?;
            let format = mime(mime_type).or_else(|| image::ImageFormat::from_path(path).ok());
            Ok((Cow::Owned(bytes), uri.to_owned(), format))
        }
        (gltf::image::Source::Uri { uri, mime_type }, Origin::Embedded(_)) => {
            let data = uri.strip_prefix("data:").unwrap_or(uri);
            let format = mime(mime_type).or_else(|| mime(data.split(';').next()));
            let name = describe(image.name(), image.index());
            Ok((Cow::Owned(super::decode_data_uri(data)?), name, format))
        }
        (gltf::image::Source::View { view, mime_type }, _) => {
            // The guards checked the view lies inside its buffer's declared length, and the
            // loader that the buffer holds at least that.
            let buffer = &source.buffers[view.buffer().index()].0;
            let bytes = &buffer[view.offset()..view.offset() + view.length()];
            let name = describe(image.name(), image.index());
            Ok((Cow::Borrowed(bytes), name, mime(Some(mime_type))))
        }
    }
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
        let name = describe(image.name(), image.index());
        let image_error = |reason: String| GltfError::Image {
            path: source.path.clone(),
            image: name.clone(),
            reason,
        };
        let origin = origin(source, &image).map_err(image_error)?;
        let key = (origin.clone(), kind, channel, sampler);
        if let Some(handle) = self.images.get(&key) {
            return Ok(handle.clone());
        }
        let budget = self
            .budget
            .get_or_insert_with(|| ImageBudget::new(source.options.image_memory_budget));
        if !self.decoded.contains_key(&origin) {
            let (bytes, file_name, format) =
                encoded(source, &image, &origin).map_err(image_error)?;
            let decoded = decode_bytes(
                &bytes,
                &file_name,
                (format, crate::image::TEXTURE_FORMATS),
                budget,
            )
            .map_err(|error| image_error(error.to_string()))?;
            self.decoded.insert(
                origin.clone(),
                Decoded {
                    image: decoded,
                    file_bytes: bytes.len() as u64,
                    name: file_name,
                },
            );
        }
        let decoded = &self.decoded[&origin];
        let loaded = Image::from_decoded_within(
            decoded.image.clone(),
            kind,
            channel,
            &decoded.name,
            decoded.file_bytes,
            budget,
        )
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
