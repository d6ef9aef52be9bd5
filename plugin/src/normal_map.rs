//! Tangent-space normal maps derived from height fields.

use image::{Rgba, RgbaImage};

use crate::{Image, ImageError, TextureKind};

/// A normal map of a height field by a 3×3 Sobel filter (Tatarchuk 2006 §5.5), wrapping at the
/// edges so tiling textures stay seamless.
///
/// `heights` holds `width × height` values, row by row, 0 = lowest, 1 = highest. `height_scale`
/// is the height of 1.0 measured in UV units (the same number a parallax material uses), so the
/// shading slopes match the parallax. The result uses the OpenGL convention: red = +u,
/// green = up the image (−v), blue = out of the surface.
pub fn normal_map_from_heights(
    heights: &[f32],
    width: u32,
    height: u32,
    height_scale: f32,
) -> Result<Image, ImageError> {
    let expected = width as usize * height as usize;
    if width == 0 || height == 0 {
        return Err(ImageError::Empty { width, height });
    }
    if heights.len() != expected {
        return Err(ImageError::WrongLength {
            width,
            height,
            expected,
            found: heights.len(),
        });
    }
    let at = |x: i64, y: i64| {
        let x = x.rem_euclid(i64::from(width)) as usize;
        let y = y.rem_euclid(i64::from(height)) as usize;
        heights[y * width as usize + x]
    };
    let pixels = RgbaImage::from_fn(width, height, |x, y| {
        let (x, y) = (i64::from(x), i64::from(y));
        // Sobel weights sum to 8 over a 2-texel baseline: divide by 8 for height per texel.
        let per_texel_u = (at(x + 1, y - 1) + 2.0 * at(x + 1, y) + at(x + 1, y + 1)
            - at(x - 1, y - 1)
            - 2.0 * at(x - 1, y)
            - at(x - 1, y + 1))
            / 8.0;
        let per_texel_v = (at(x - 1, y + 1) + 2.0 * at(x, y + 1) + at(x + 1, y + 1)
            - at(x - 1, y - 1)
            - 2.0 * at(x, y - 1)
            - at(x + 1, y - 1))
            / 8.0;
        let slope_u = per_texel_u * width as f32 * height_scale;
        let slope_v = per_texel_v * height as f32 * height_scale;
        // Up the image is −v, so the green component is +dh/dv.
        let normal = glam::Vec3::new(-slope_u, slope_v, 1.0).normalize_or(glam::Vec3::Z);
        let encode = |c: f32| ((c * 0.5 + 0.5) * 255.0).round().clamp(0.0, 255.0) as u8;
        Rgba([encode(normal.x), encode(normal.y), encode(normal.z), 255])
    });
    Image::new(pixels, TextureKind::Normal)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_ramp_rising_along_u_tilts_normals_towards_minus_u() {
        let (width, height) = (8, 4);
        // Rises by 1/8 per texel along u (the wrap seam aside).
        let heights: Vec<f32> = (0..height)
            .flat_map(|_| (0..width).map(|x| x as f32 / width as f32))
            .collect();
        let map = normal_map_from_heights(&heights, width, height, 1.0).unwrap();
        // Slope 1 per UV unit at scale 1: the normal is (−1, 0, 1)/√2.
        assert_eq!(map.to_rgba8().get_pixel(3, 1).0, [37, 128, 218, 255]);
    }

    #[test]
    fn flat_fields_give_flat_normals_and_bad_sizes_are_errors() {
        let map = normal_map_from_heights(&[0.5; 6], 3, 2, 10.0).unwrap();
        assert!(map.to_rgba8().pixels().all(|p| p.0 == [128, 128, 255, 255]));
        assert!(normal_map_from_heights(&[0.0; 5], 3, 2, 1.0).is_err());
        assert!(normal_map_from_heights(&[], 0, 2, 1.0).is_err());
    }
}
