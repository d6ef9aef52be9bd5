//! Height fields on the CPU: sampling, conversion to and from images, and procedural patterns.

use image::{GrayImage, ImageBuffer, Luma};

use crate::{Channel, Image, ImageError, Pixels, TextureKind};

crate::choice_enum! {
    /// What the height texture's values mean.
    pub enum HeightConvention: "CONVENTION" {
        /// White is the top (the polygon's surface), black the deepest point (Tatarchuk).
        Height = "height",
        /// White is the deepest point: LearnOpenGL's and Bevy's depth maps.
        Depth = "depth",
    }
}

impl Default for HeightConvention {
    /// Tatarchuk's: white is the top.
    fn default() -> Self {
        Self::Height
    }
}

/// A grid of heights in 0..=1 (1 = top), sampled with wrapping like a repeating texture.
#[derive(Clone, Debug, PartialEq)]
pub struct HeightField {
    width: u32,
    height: u32,
    values: Vec<f32>,
}

impl HeightField {
    /// A field from row-major values, each clamped to 0..=1 (NaN becomes 0).
    pub fn new(width: u32, height: u32, values: Vec<f32>) -> Result<Self, ImageError> {
        if width == 0 || height == 0 {
            return Err(ImageError::Empty { width, height });
        }
        let expected = width as usize * height as usize;
        if values.len() != expected {
            return Err(ImageError::WrongLength {
                width,
                height,
                expected,
                found: values.len(),
            });
        }
        let values = values
            .into_iter()
            .map(|v| if v.is_nan() { 0.0 } else { v.clamp(0.0, 1.0) })
            .collect();
        Ok(Self {
            width,
            height,
            values,
        })
    }

    /// A `width`×`height` field of `f(u, v)` at texel centres, u and v in 0..1 (a side of 0 is
    /// taken as 1: a field always has a texel).
    pub fn from_fn(width: u32, height: u32, f: impl Fn(f32, f32) -> f32) -> Self {
        let (width, height) = (width.max(1), height.max(1));
        let values = (0..height)
            .flat_map(|y| (0..width).map(move |x| (x, y)))
            .map(|(x, y)| {
                let value = f(
                    (x as f32 + 0.5) / width as f32,
                    (y as f32 + 0.5) / height as f32,
                );
                if value.is_nan() {
                    0.0
                } else {
                    value.clamp(0.0, 1.0)
                }
            })
            .collect();
        Self {
            width,
            height,
            values,
        }
    }

    /// Width and height in texels.
    pub fn size(&self) -> (u32, u32) {
        (self.width, self.height)
    }

    /// The values, row by row.
    pub fn values(&self) -> &[f32] {
        &self.values
    }

    /// The texel at integer coordinates, wrapping around the edges.
    pub fn texel(&self, x: i64, y: i64) -> f32 {
        let x = x.rem_euclid(i64::from(self.width)) as usize;
        let y = y.rem_euclid(i64::from(self.height)) as usize;
        self.values[y * self.width as usize + x]
    }

    /// Bilinear sample at texture coordinate (u, v) with repeat wrapping, texel centres at
    /// (i + 0.5) / size — what a GPU's linear filter does at mip level 0.
    pub fn sample(&self, u: f32, v: f32) -> f32 {
        let x = u * self.width as f32 - 0.5;
        let y = v * self.height as f32 - 0.5;
        let (x0, y0) = (x.floor(), y.floor());
        let (fx, fy) = (x - x0, y - y0);
        let (x0, y0) = (x0 as i64, y0 as i64);
        let top = self.texel(x0, y0) * (1.0 - fx) + self.texel(x0 + 1, y0) * fx;
        let bottom = self.texel(x0, y0 + 1) * (1.0 - fx) + self.texel(x0 + 1, y0 + 1) * fx;
        top * (1.0 - fy) + bottom * fy
    }

    /// The field stored in `channel` of an image, whose values mean what `convention` says
    /// (a depth map's are flipped, so that 1 is the top).
    pub fn from_image(image: &Image, channel: Channel, convention: HeightConvention) -> Self {
        let depth = convention == HeightConvention::Depth;
        let (width, height) = image.size();
        let pixels = image.pixels();
        // Grey images hold the height in their only channel, whichever was asked for.
        let (stride, offset) = match pixels.channels() {
            1 => (1, 0),
            channels => (channels, channel.index().min(channels - 1)),
        };
        let values = pixels
            .to_unit_floats()
            .iter()
            .skip(offset)
            .step_by(stride)
            .map(|value| if depth { 1.0 - value } else { *value })
            .collect();
        Self {
            width,
            height,
            values,
        }
    }

    /// An 8-bit, one-channel height image of the field.
    pub fn to_image(&self) -> Image {
        let pixels = GrayImage::from_fn(self.width, self.height, |x, y| {
            Luma([(self.texel(i64::from(x), i64::from(y)) * 255.0).round() as u8])
        });
        // The size was checked when the field was made.
        Image::from_pixels(Pixels::Gray8(pixels), TextureKind::Height)
            .expect("height field is not empty")
    }

    /// A 16-bit, one-channel height image of the field.
    pub fn to_image_16(&self) -> Image {
        let pixels = ImageBuffer::from_fn(self.width, self.height, |x, y| {
            Luma([(self.texel(i64::from(x), i64::from(y)) * 65535.0).round() as u16])
        });
        Image::from_pixels(Pixels::Gray16(pixels), TextureKind::Height)
            .expect("height field is not empty")
    }

    /// The field as an 8-bit image stores it: every value rounded to a multiple of 1/255, as the
    /// GPU sees it.
    pub fn quantized(&self) -> Self {
        Self {
            values: self
                .values
                .iter()
                .map(|v| (v * 255.0).round() / 255.0)
                .collect(),
            ..self.clone()
        }
    }

    /// A tangent-space normal map of this field (see [`crate::normal_map_from_heights`]).
    pub fn normal_map(&self, height_scale: f32) -> Image {
        // The field is non-empty and its length matches, so this cannot fail.
        crate::normal_map_from_heights(&self.values, self.width, self.height, height_scale)
            .expect("height field is consistent")
    }
}

/// Procedural height fields for tests, demos and the shipped assets.
pub mod patterns {
    use super::HeightField;

    /// Running-bond bricks: `columns` × `rows` bricks per tile, mortar lines at 0 with a short
    /// bevel up to the brick faces at 1.
    pub fn bricks(size: u32, columns: f32, rows: f32) -> HeightField {
        HeightField::from_fn(size, size, |u, v| {
            let row = (v * rows).floor();
            let shift = if row.rem_euclid(2.0) == 0.0 { 0.0 } else { 0.5 };
            let across = (u * columns + shift).fract();
            let down = (v * rows).fract();
            let to_edge_u = across.min(1.0 - across) / columns;
            let to_edge_v = down.min(1.0 - down) / rows;
            // Mortar half-width and bevel width, in tile units.
            ((to_edge_u.min(to_edge_v) - 0.01) / 0.015).clamp(0.0, 1.0)
        })
    }

    fn hash(x: i32, y: i32) -> (f32, f32) {
        let mut h = (x as u32).wrapping_mul(0x8da6_b343) ^ (y as u32).wrapping_mul(0xd816_3841);
        h ^= h >> 13;
        h = h.wrapping_mul(0x85eb_ca6b);
        h ^= h >> 16;
        let a = (h & 0xffff) as f32 / 65535.0;
        let b = (h >> 16) as f32 / 65535.0;
        (a, b)
    }

    /// Cobblestones: a `cells`×`cells` periodic Voronoi pattern of stones with rounded tops and
    /// grout at 0.08, like Tatarchuk's sidewalk.
    pub fn cobblestones(size: u32, cells: i32) -> HeightField {
        let cells = cells.max(1);
        HeightField::from_fn(size, size, |u, v| {
            let (px, py) = (u * cells as f32, v * cells as f32);
            let (cx, cy) = (px.floor() as i32, py.floor() as i32);
            let (mut nearest, mut second) = (f32::MAX, f32::MAX);
            for dy in -1..=1 {
                for dx in -1..=1 {
                    let (gx, gy) = (cx + dx, cy + dy);
                    let (jx, jy) = hash(gx.rem_euclid(cells), gy.rem_euclid(cells));
                    let fx = gx as f32 + 0.2 + 0.6 * jx - px;
                    let fy = gy as f32 + 0.2 + 0.6 * jy - py;
                    let distance = (fx * fx + fy * fy).sqrt();
                    if distance < nearest {
                        second = nearest;
                        nearest = distance;
                    } else if distance < second {
                        second = distance;
                    }
                }
            }
            // Distance to the border between the two nearest stones, rounded into a dome.
            let edge = ((second - nearest) * 0.5 / 0.35).clamp(0.0, 1.0);
            0.08 + 0.92 * (1.0 - (1.0 - edge) * (1.0 - edge)).sqrt()
        })
    }

    /// Sharp cones (T Fig. 13b): `cells`×`cells` cones whose tips reach 1, on a floor at 0.
    pub fn cones(size: u32, cells: f32) -> HeightField {
        HeightField::from_fn(size, size, |u, v| {
            let (x, y) = ((u * cells).fract() - 0.5, (v * cells).fract() - 0.5);
            (1.0 - (x * x + y * y).sqrt() / 0.45).max(0.0)
        })
    }

    /// Thin spikes: one texel at the top every `spacing` texels (at offset `spacing` / 2 on
    /// both axes), on a floor at `floor`: blockers a march with long steps walks past.
    pub fn spikes(size: u32, spacing: u32, floor: f32) -> HeightField {
        let spacing = spacing.max(1);
        let texel = move |coordinate: f32| (coordinate * size as f32) as u32;
        HeightField::from_fn(size, size, move |u, v| {
            let on_spike = |texel: u32| texel % spacing == spacing / 2;
            if on_spike(texel(u)) && on_spike(texel(v)) {
                1.0
            } else {
                floor
            }
        })
    }

    /// Value noise, 0..1, at `(x, y)` in lattice cells, repeating every `period` cells: the
    /// hashed corners of the cell, mixed with a smooth step.
    fn value_noise(x: f32, y: f32, period: i32) -> f32 {
        let (cx, cy) = (x.floor(), y.floor());
        let smooth = |t: f32| t * t * (3.0 - 2.0 * t);
        let (tx, ty) = (smooth(x - cx), smooth(y - cy));
        let corner = |dx: i32, dy: i32| {
            hash(
                (cx as i32 + dx).rem_euclid(period),
                (cy as i32 + dy).rem_euclid(period),
            )
            .0
        };
        let top = corner(0, 0) + (corner(1, 0) - corner(0, 0)) * tx;
        let bottom = corner(0, 1) + (corner(1, 1) - corner(0, 1)) * tx;
        top + (bottom - top) * ty
    }

    /// Weathered rock: ridged value noise (sharp creases where the noise crosses its middle)
    /// over five octaves from `cells` × `cells` cells across the tile, repeating, stretched to
    /// span 0..1 (the whole depth the material gives it).
    pub fn rock(size: u32, cells: u32) -> HeightField {
        let cells = cells.clamp(1, 1 << 20) as i32;
        let field = HeightField::from_fn(size, size, move |u, v| {
            let (mut height, mut amplitude) = (0.0, 0.5);
            for octave in 0..5 {
                let period = cells << octave;
                let noise = value_noise(u * period as f32, v * period as f32, period);
                let ridge = 1.0 - (2.0 * noise - 1.0).abs();
                height += amplitude * ridge * ridge;
                amplitude *= 0.5;
            }
            height
        });
        let (low, high) = field
            .values()
            .iter()
            .fold((f32::MAX, f32::MIN), |(low, high), &v| {
                (low.min(v), high.max(v))
            });
        let range = (high - low).max(1e-6);
        HeightField::from_fn(size, size, |u, v| (field.sample(u, v) - low) / range)
    }

    /// One square block of side `side` (in tile units) centred in the tile, at height 1, on a
    /// floor at 0: for measuring parallax and shadows.
    pub fn raised_block(size: u32, side: f32) -> HeightField {
        HeightField::from_fn(size, size, |u, v| {
            let half = side * 0.5;
            if (u - 0.5).abs() < half && (v - 0.5).abs() < half {
                1.0
            } else {
                0.0
            }
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bilinear_sampling_wraps_and_hits_texel_centres() {
        let field = HeightField::new(2, 1, vec![0.0, 1.0]).unwrap();
        assert_eq!(field.sample(0.25, 0.5), 0.0);
        assert_eq!(field.sample(0.75, 0.5), 1.0);
        assert_eq!(field.sample(0.5, 0.5), 0.5);
        // Past the right edge it blends back towards the first texel.
        assert!((field.sample(1.0, 0.5) - 0.5).abs() < 1e-6);
        assert!((field.sample(-0.25, 0.5) - 1.0).abs() < 1e-6);
    }

    #[test]
    fn bad_fields_are_errors_and_values_are_clamped() {
        assert!(HeightField::new(0, 1, vec![]).is_err());
        assert!(HeightField::new(2, 2, vec![0.0; 3]).is_err());
        let clamped = HeightField::new(3, 1, vec![-1.0, f32::NAN, 2.0]).unwrap();
        assert_eq!(clamped.values(), [0.0, 0.0, 1.0]);
    }

    #[test]
    fn patterns_span_the_range() {
        for field in [
            patterns::bricks(64, 4.0, 8.0),
            patterns::cobblestones(64, 4),
            patterns::cones(64, 4.0),
            patterns::rock(64, 4),
            patterns::raised_block(64, 0.5),
        ] {
            let (min, max) = field
                .values()
                .iter()
                .fold((1.0_f32, 0.0_f32), |(lo, hi), v| (lo.min(*v), hi.max(*v)));
            // Sharp tips fall between texel centres, so cones peak a little under 1.
            assert!(min < 0.1 && max > 0.85, "{min}..{max}");
        }
    }

    #[test]
    fn rock_repeats_across_its_tile_and_differs_cell_to_cell() {
        let rock = patterns::rock(64, 4);
        // The step from the last column to the first is a step like any other: the noise
        // wraps (unwrapped noise would jump there by about its whole range).
        let step = |a: i64, b: i64| {
            (0..64)
                .map(|y| (rock.texel(a, y) - rock.texel(b, y)).abs())
                .sum::<f32>()
                / 64.0
        };
        let across_edge = step(63, 0);
        let inside = (0..63).map(|x| step(x, x + 1)).sum::<f32>() / 63.0;
        assert!(across_edge < 3.0 * inside, "{across_edge} against {inside}");
        let cell = |x: i64| rock.texel(x, 8);
        assert!((0..4).any(|c| (cell(c * 16 + 8) - cell(8)).abs() > 0.05));
    }
}
