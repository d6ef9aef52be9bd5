//! Mip chains: each level filtered from the one above in the space that suits the texture kind
//! (linear light for colour, unit vectors for normals, maxima for max-mip heights).

use super::{Pixels, TextureKind};
use crate::color::{linear_to_srgb, srgb_to_linear};

/// How a mip texel combines the texels it covers.
#[derive(Clone, Copy, PartialEq, Eq)]
pub(super) enum Reduce {
    /// Their mean (in the kind's filtering space).
    Average,
    /// Their maximum: a max-mip chain of heights.
    Max,
}

/// Stored 0..=1 values to the space mips are filtered in: linear light for colour, −1..=1 vectors
/// for normals (alpha stays as is). In place: a full-size level of floats is the chain's peak.
fn decode(kind: TextureKind, channels: usize, mut values: Vec<f32>) -> Vec<f32> {
    for (i, v) in values.iter_mut().enumerate() {
        *v = match (kind, i % channels) {
            (TextureKind::Color, 0..=2) => srgb_to_linear(*v),
            (TextureKind::Normal, 0..=2) if channels == 4 => *v * 2.0 - 1.0,
            _ => *v,
        };
    }
    values
}

fn encode(kind: TextureKind, channels: usize, values: &[f32]) -> Vec<f32> {
    values
        .iter()
        .enumerate()
        .map(|(i, v)| match (kind, i % channels) {
            (TextureKind::Color, 0..=2) => linear_to_srgb(*v),
            (TextureKind::Normal, 0..=2) if channels == 4 => v * 0.5 + 0.5,
            _ => *v,
        })
        .collect()
}

fn renormalize(rgba: &mut [f32]) {
    for texel in rgba.chunks_exact_mut(4) {
        let length = (texel[0] * texel[0] + texel[1] * texel[1] + texel[2] * texel[2]).sqrt();
        if length > 1e-6 {
            for component in &mut texel[..3] {
                *component /= length;
            }
        } else {
            texel[..3].copy_from_slice(&[0.0, 0.0, 1.0]);
        }
    }
}

fn reduce_level(
    width: u32,
    height: u32,
    channels: usize,
    values: &[f32],
    reduce: Reduce,
) -> (u32, u32, Vec<f32>) {
    let (next_width, next_height) = ((width / 2).max(1), (height / 2).max(1));
    let mut next = Vec::with_capacity(next_width as usize * next_height as usize * channels);
    for y in 0..next_height {
        // The source footprint: 2×2, or 3 wide/high at the last column/row of an odd-sized
        // level so no source texel is dropped.
        let y_end = if y + 1 == next_height {
            height
        } else {
            2 * y + 2
        };
        for x in 0..next_width {
            let x_end = if x + 1 == next_width {
                width
            } else {
                2 * x + 2
            };
            for channel in 0..channels {
                let mut accumulated = match reduce {
                    Reduce::Average => 0.0,
                    Reduce::Max => f32::MIN,
                };
                let mut count = 0.0;
                for sy in (2 * y).min(height - 1)..y_end {
                    for sx in (2 * x).min(width - 1)..x_end {
                        let value = values
                            [(sy as usize * width as usize + sx as usize) * channels + channel];
                        accumulated = match reduce {
                            Reduce::Average => accumulated + value,
                            Reduce::Max => accumulated.max(value),
                        };
                        count += 1.0;
                    }
                }
                next.push(match reduce {
                    Reduce::Average => accumulated / count,
                    Reduce::Max => accumulated,
                });
            }
        }
    }
    (next_width, next_height, next)
}

/// Every level from `pixels` down to 1×1, filtered for `kind` by `reduce`.
pub(super) fn chain(pixels: &Pixels, kind: TextureKind, reduce: Reduce) -> Vec<Pixels> {
    let channels = pixels.channels();
    let (mut width, mut height) = pixels.dimensions();
    let mut level = decode(kind, channels, pixels.to_unit_floats());
    let mut levels = vec![pixels.clone()];
    while width > 1 || height > 1 {
        let (next_width, next_height, next) = reduce_level(width, height, channels, &level, reduce);
        let mut next = next;
        if kind == TextureKind::Normal && channels == 4 {
            renormalize(&mut next);
        }
        levels.push(Pixels::from_unit_floats(
            pixels,
            next_width,
            next_height,
            &encode(kind, channels, &next),
        ));
        (width, height, level) = (next_width, next_height, next);
    }
    levels
}
