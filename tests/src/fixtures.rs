//! Procedural textures for tests: no files needed, same pixels everywhere.

use image::{Rgba, RgbaImage};
use pom::{Image, TextureKind};

/// A height field of round bumps on a `cells`×`cells` grid, 0 (floor) to 1 (bump top).
pub fn bump_height(u: f32, v: f32, cells: f32) -> f32 {
    let cell_u = (u * cells).fract() - 0.5;
    let cell_v = (v * cells).fract() - 0.5;
    let radius = (cell_u * cell_u + cell_v * cell_v).sqrt() / 0.4;
    if radius >= 1.0 {
        0.0
    } else {
        (1.0 - radius * radius).sqrt()
    }
}

/// A tangent-space normal map of [`bump_height`] made by the plugin's Sobel filter; `strength`
/// is the bump height in UV units.
pub fn bump_normal_map(size: u32, cells: f32, strength: f32) -> Image {
    let texel = 1.0 / size as f32;
    let heights: Vec<f32> = (0..size * size)
        .map(|i| {
            let (x, y) = (i % size, i / size);
            bump_height((x as f32 + 0.5) * texel, (y as f32 + 0.5) * texel, cells)
        })
        .collect();
    pom::normal_map_from_heights(&heights, size, size, strength).expect("size is not zero")
}

/// A two-colour checkerboard of `cells`×`cells` squares, sRGB.
pub fn checker_albedo(size: u32, cells: u32, a: [u8; 3], b: [u8; 3]) -> Image {
    let cell = (size / cells.max(1)).max(1);
    let pixels = RgbaImage::from_fn(size, size, |x, y| {
        let [r, g, bl] = if (x / cell + y / cell).is_multiple_of(2) {
            a
        } else {
            b
        };
        Rgba([r, g, bl, 255])
    });
    Image::new(pixels, TextureKind::Color).expect("size is not zero")
}
