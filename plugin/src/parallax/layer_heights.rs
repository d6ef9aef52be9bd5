//! The heights of a layered material's layers packed into the channels of one texture, so a
//! march step reads every layer's height with one fetch (where the layers tile alike).

use image::{Rgba, RgbaImage};

use crate::image::TextureKind;
use crate::{HeightField, Image};

/// Most layers one packed height texture holds: one per channel.
pub const MAX_LAYERS: usize = 4;

/// Why layers cannot be packed.
#[derive(Debug, thiserror::Error, PartialEq, Eq)]
#[non_exhaustive]
pub enum LayerError {
    /// More layers than one packed texture holds.
    #[error("{0} layers given: one packed height texture holds at most {MAX_LAYERS}")]
    TooMany(usize),
    /// No layer at all.
    #[error("no layers given: a layered material needs at least one")]
    NoLayers,
}

/// The heights of `layers` (1 to [`MAX_LAYERS`], Tatarchuk's convention: 1 the top) in one
/// 8-bit RGBA image, layer i in channel i. A layer without a height map is flat at the top, as
/// a parallax material without one (no relief); channels past the last layer hold 0 (a layer
/// that is not there weighs nothing, so never shows). The image takes the size of the layer
/// with the most texels (so it holds no more than that layer did, times four channels); the
/// others are resampled to it (bilinear, repeating, as they tile over the same coordinates).
///
/// # Errors
/// [`LayerError::NoLayers`] for none, [`LayerError::TooMany`] past [`MAX_LAYERS`].
pub fn pack_layer_heights(layers: &[Option<&HeightField>]) -> Result<Image, LayerError> {
    if layers.is_empty() {
        return Err(LayerError::NoLayers);
    }
    if layers.len() > MAX_LAYERS {
        return Err(LayerError::TooMany(layers.len()));
    }
    let (width, height) = layers
        .iter()
        .flatten()
        .map(|field| field.size())
        .max_by_key(|&(width, height)| u64::from(width) * u64::from(height))
        .unwrap_or((1, 1));
    let pixels = RgbaImage::from_fn(width, height, |x, y| {
        let (u, v) = (
            (x as f32 + 0.5) / width as f32,
            (y as f32 + 0.5) / height as f32,
        );
        let mut texel = [0u8; 4];
        for (channel, layer) in layers.iter().enumerate() {
            let value = match layer {
                // A field of this very size is read texel for texel, with no rounding on the way.
                Some(field) if field.size() == (width, height) => {
                    field.texel(i64::from(x), i64::from(y))
                }
                Some(field) => field.sample(u, v),
                None => 1.0,
            };
            texel[channel] = (value.clamp(0.0, 1.0) * 255.0).round() as u8;
        }
        Rgba(texel)
    });
    // Plain averages down the mips: the channels are data, not colour. `Image::new` fails only
    // for an empty image, and the size is a field's (at least 1×1) or 1×1.
    Ok(Image::new(pixels, TextureKind::Data).expect("the packed image is at least 1×1"))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn channel(image: &Image, x: u32, y: u32, channel: usize) -> u8 {
        image.to_rgba8().get_pixel(x, y).0[channel]
    }

    #[test]
    fn each_layer_fills_its_channel_and_missing_ones_are_flat_or_absent() {
        let ramp = HeightField::from_fn(4, 2, |u, _| u);
        let stripes = HeightField::from_fn(4, 2, |_, v| if v < 0.5 { 0.0 } else { 1.0 });
        let packed = pack_layer_heights(&[Some(&ramp), None, Some(&stripes)]).unwrap();
        assert_eq!(packed.size(), (4, 2));
        assert_eq!(packed.kind(), TextureKind::Data);
        for (x, y) in [(0, 0), (3, 0), (1, 1)] {
            let expected = (ramp.texel(i64::from(x), i64::from(y)) * 255.0).round() as u8;
            assert_eq!(channel(&packed, x, y, 0), expected);
            assert_eq!(
                channel(&packed, x, y, 1),
                255,
                "a layer without heights is the top"
            );
            assert_eq!(channel(&packed, x, y, 2), if y == 0 { 0 } else { 255 });
            assert_eq!(channel(&packed, x, y, 3), 0, "no fourth layer");
        }
    }

    #[test]
    fn the_layer_with_most_texels_sets_the_size() {
        let wide = HeightField::from_fn(64, 1, |_, _| 0.0);
        let tall = HeightField::from_fn(1, 16, |_, _| 0.0);
        let packed = pack_layer_heights(&[Some(&tall), Some(&wide)]).unwrap();
        assert_eq!(packed.size(), (64, 1));
        assert_eq!(pack_layer_heights(&[None]).unwrap().size(), (1, 1));
    }

    #[test]
    fn smaller_layers_are_resampled_to_the_largest() {
        let fine = HeightField::from_fn(8, 8, |_, _| 0.5);
        let coarse = HeightField::new(2, 2, vec![0.0, 1.0, 1.0, 0.0]).unwrap();
        let packed = pack_layer_heights(&[Some(&fine), Some(&coarse)]).unwrap();
        assert_eq!(packed.size(), (8, 8));
        for (x, y) in [(0, 0), (2, 1), (5, 6), (7, 7)] {
            let (u, v) = ((x as f32 + 0.5) / 8.0, (y as f32 + 0.5) / 8.0);
            let expected = (coarse.sample(u, v) * 255.0).round() as u8;
            assert_eq!(channel(&packed, x, y, 1), expected, "at {x},{y}");
            assert_eq!(channel(&packed, x, y, 0), 128);
        }
    }

    #[test]
    fn no_layers_or_more_than_four_are_errors_naming_the_limit() {
        assert_eq!(
            pack_layer_heights(&[]).unwrap_err().to_string(),
            "no layers given: a layered material needs at least one"
        );
        let field = HeightField::from_fn(2, 2, |_, _| 1.0);
        let five = [Some(&field); 5];
        assert_eq!(
            pack_layer_heights(&five).unwrap_err().to_string(),
            "5 layers given: one packed height texture holds at most 4"
        );
    }
}
