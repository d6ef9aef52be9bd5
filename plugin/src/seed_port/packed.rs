//! The one texture listing 2 reads for its relief: tNormalMap, RGBA8, the tangent-space normal
//! in RGB and the height in alpha, with Direct3D's green.

use image::RgbaImage;

use super::SeedPortError;
use crate::{Assets, HeightField, HeightSource, Image, ParallaxOcclusionMaterial};
use crate::{Channel, Pixels, TextureKind};

/// A flat normal's texel, where the material has no normal map.
const FLAT_NORMAL: [u8; 3] = [128, 128, 255];

/// `material`'s normal map and height packed as the listing reads them: the normal's red and
/// blue as they are, its green turned to Direct3D's (255 − green: ours points up the image, the
/// listing's down it, along +v), the height (1 = the polygon's surface, a depth map turned
/// over) in alpha, 8 bits as in the listing's RGBA8 maps. `None` when the material has neither
/// map (the default flat normal, alpha 1, then stands in). Keeps the normal map's sampler.
///
/// # Errors
/// [`SeedPortError::MissingImage`] when a map it names is not in `images`,
/// [`SeedPortError::SizeMismatch`] when the two maps differ in size.
pub fn packed_normal_height(
    material: &ParallaxOcclusionMaterial,
    images: &Assets<Image>,
) -> Result<Option<Image>, SeedPortError> {
    let lookup =
        |handle: &crate::Handle<Image>| images.get(handle.id()).ok_or(SeedPortError::MissingImage);
    let normal = material.normal_map.as_ref().map(lookup).transpose()?;
    let convention = material.height_convention;
    let height = match &material.height_map {
        Some(HeightSource::Texture(handle)) => Some(HeightField::from_image(
            lookup(handle)?,
            Channel::Red,
            convention,
        )),
        Some(HeightSource::NormalMapAlpha) => {
            normal.map(|normal| HeightField::from_image(normal, Channel::Alpha, convention))
        }
        None => None,
    };
    let size = match (normal, &height) {
        (Some(normal), Some(height)) if normal.size() != height.size() => {
            return Err(SeedPortError::SizeMismatch {
                normal: normal.size(),
                height: height.size(),
            });
        }
        (Some(normal), _) => normal.size(),
        (None, Some(height)) => height.size(),
        (None, None) => return Ok(None),
    };
    let normal_texels = normal.map(Image::to_rgba8);
    let packed = RgbaImage::from_fn(size.0, size.1, |x, y| {
        let [red, green, blue] = normal_texels.as_ref().map_or(FLAT_NORMAL, |texels| {
            let [r, g, b, _] = texels.get_pixel(x, y).0;
            [r, g, b]
        });
        let alpha = height
            .as_ref()
            .map_or(1.0, |field| field.texel(i64::from(x), i64::from(y)));
        image::Rgba([
            red,
            255 - green,
            blue,
            (alpha.clamp(0.0, 1.0) * 255.0).round() as u8,
        ])
    });
    let image = Image::from_pixels(Pixels::Rgba8(packed), TextureKind::Normal)?;
    Ok(Some(match normal {
        Some(normal) => image.with_sampler(normal.sampler()),
        None => image,
    }))
}
