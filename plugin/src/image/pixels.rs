//! Pixel storage of an image: 8-bit RGBA, or one channel of 8 or 16 bits.

use image::{GrayImage, ImageBuffer, Luma, RgbaImage};

/// Pixel storage of an [`Image`](super::Image).
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub enum Pixels {
    /// Four 8-bit channels.
    Rgba8(RgbaImage),
    /// One 8-bit channel.
    Gray8(GrayImage),
    /// One 16-bit channel (16-bit height maps stay 16-bit on the GPU where it allows).
    Gray16(ImageBuffer<Luma<u16>, Vec<u16>>),
}

impl Pixels {
    /// Width and height.
    pub fn dimensions(&self) -> (u32, u32) {
        match self {
            Pixels::Rgba8(pixels) => pixels.dimensions(),
            Pixels::Gray8(pixels) => pixels.dimensions(),
            Pixels::Gray16(pixels) => pixels.dimensions(),
        }
    }

    /// Channels per pixel.
    pub fn channels(&self) -> usize {
        match self {
            Pixels::Rgba8(_) => 4,
            Pixels::Gray8(_) | Pixels::Gray16(_) => 1,
        }
    }

    /// The raw bytes, row by row (16-bit values little-endian, as GPUs expect).
    pub fn bytes(&self) -> Vec<u8> {
        match self {
            Pixels::Rgba8(pixels) => pixels.as_raw().clone(),
            Pixels::Gray8(pixels) => pixels.as_raw().clone(),
            Pixels::Gray16(pixels) => pixels
                .as_raw()
                .iter()
                .flat_map(|v| v.to_le_bytes())
                .collect(),
        }
    }

    /// Every value as 0..=1, row by row, `channels()` per pixel.
    pub fn to_unit_floats(&self) -> Vec<f32> {
        match self {
            Pixels::Rgba8(pixels) => pixels
                .as_raw()
                .iter()
                .map(|v| f32::from(*v) / 255.0)
                .collect(),
            Pixels::Gray8(pixels) => pixels
                .as_raw()
                .iter()
                .map(|v| f32::from(*v) / 255.0)
                .collect(),
            Pixels::Gray16(pixels) => pixels
                .as_raw()
                .iter()
                .map(|v| f32::from(*v) / 65535.0)
                .collect(),
        }
    }

    /// Pixels of `like`'s storage from 0..=1 values (`channels()` per pixel, row by row).
    pub(super) fn from_unit_floats(
        like: &Pixels,
        width: u32,
        height: u32,
        values: &[f32],
    ) -> Pixels {
        let to_u8 = |v: &f32| (v * 255.0).round().clamp(0.0, 255.0) as u8;
        let to_u16 = |v: &f32| (v * 65535.0).round().clamp(0.0, 65535.0) as u16;
        // Lengths follow from width × height × channels, which the callers compute.
        match like {
            Pixels::Rgba8(_) => Pixels::Rgba8(
                RgbaImage::from_raw(width, height, values.iter().map(to_u8).collect())
                    .expect("four values per pixel"),
            ),
            Pixels::Gray8(_) => Pixels::Gray8(
                GrayImage::from_raw(width, height, values.iter().map(to_u8).collect())
                    .expect("one value per pixel"),
            ),
            Pixels::Gray16(_) => Pixels::Gray16(
                ImageBuffer::from_raw(width, height, values.iter().map(to_u16).collect())
                    .expect("one value per pixel"),
            ),
        }
    }
}
