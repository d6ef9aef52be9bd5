//! Procedural textures for tests: no files needed, same pixels everywhere.

use glam::Vec3;
use image::{Rgba, RgbaImage};
use pom::{ColorSpace, Image};

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

/// A tangent-space normal map (OpenGL convention: green up the image) of [`bump_height`].
pub fn bump_normal_map(size: u32, cells: f32, strength: f32) -> Image {
    let texel = 1.0 / size as f32;
    let pixels = RgbaImage::from_fn(size, size, |x, y| {
        let (u, v) = ((x as f32 + 0.5) * texel, (y as f32 + 0.5) * texel);
        // Height gradient per unit of UV; `strength` is the bump height in UV units.
        let du =
            (bump_height(u + texel, v, cells) - bump_height(u - texel, v, cells)) / (2.0 * texel);
        let dv =
            (bump_height(u, v + texel, cells) - bump_height(u, v - texel, cells)) / (2.0 * texel);
        // +v runs down the image while green points up it, hence the sign on y.
        let normal = Vec3::new(-du * strength, dv * strength, 1.0).normalize();
        let encode = |c: f32| ((c * 0.5 + 0.5) * 255.0).round() as u8;
        Rgba([encode(normal.x), encode(normal.y), encode(normal.z), 255])
    });
    Image::new(pixels, ColorSpace::Linear).expect("size is not zero")
}

/// A two-colour checkerboard of `cells`×`cells` squares, sRGB.
pub fn checker_albedo(size: u32, cells: u32, a: [u8; 3], b: [u8; 3]) -> Image {
    let cell = (size / cells.max(1)).max(1);
    let pixels = RgbaImage::from_fn(size, size, |x, y| {
        let [r, g, bl] = if (x / cell + y / cell) % 2 == 0 { a } else { b };
        Rgba([r, g, bl, 255])
    });
    Image::new(pixels, ColorSpace::Srgb).expect("size is not zero")
}
