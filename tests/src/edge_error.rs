//! The edge error of an anti-aliased image: its mean difference from a reference rendered at
//! a multiple of the size and box-filtered down, over the reference's edges.

use image::RgbaImage;

fn decode(value: u8) -> f32 {
    pom::srgb_to_linear(f32::from(value) / 255.0)
}

/// `image` box-filtered down by `factor` in linear light (what a pixel's coverage averages).
pub fn box_filtered(image: &RgbaImage, factor: u32) -> RgbaImage {
    let (width, height) = (image.width() / factor, image.height() / factor);
    RgbaImage::from_fn(width, height, |x, y| {
        let mut sum = [0.0_f32; 4];
        for dy in 0..factor {
            for dx in 0..factor {
                let pixel = image.get_pixel(x * factor + dx, y * factor + dy).0;
                for c in 0..3 {
                    sum[c] += decode(pixel[c]);
                }
                sum[3] += f32::from(pixel[3]) / 255.0;
            }
        }
        let n = (factor * factor) as f32;
        let encode = |v: f32| (pom::linear_to_srgb(v / n) * 255.0).round() as u8;
        image::Rgba([
            encode(sum[0]),
            encode(sum[1]),
            encode(sum[2]),
            (sum[3] / n * 255.0).round() as u8,
        ])
    })
}

fn luma(image: &RgbaImage, x: i64, y: i64) -> f32 {
    let x = x.clamp(0, i64::from(image.width()) - 1) as u32;
    let y = y.clamp(0, i64::from(image.height()) - 1) as u32;
    let p = image.get_pixel(x, y).0;
    (0.299 * f32::from(p[0]) + 0.587 * f32::from(p[1]) + 0.114 * f32::from(p[2])) / 255.0
}

/// The pixels where the reference's Sobel gradient of luma is high: its edges.
pub fn edge_pixels(reference: &RgbaImage) -> Vec<(u32, u32)> {
    let mut edges = Vec::new();
    for y in 0..reference.height() {
        for x in 0..reference.width() {
            let (x, y) = (i64::from(x), i64::from(y));
            let l = |dx, dy| luma(reference, x + dx, y + dy);
            let gx = l(1, -1) + 2.0 * l(1, 0) + l(1, 1) - l(-1, -1) - 2.0 * l(-1, 0) - l(-1, 1);
            let gy = l(-1, 1) + 2.0 * l(0, 1) + l(1, 1) - l(-1, -1) - 2.0 * l(0, -1) - l(1, -1);
            if (gx * gx + gy * gy).sqrt() > 0.5 {
                edges.push((x as u32, y as u32));
            }
        }
    }
    edges
}

/// The mean absolute difference (0..1, per channel of the sRGB bytes) of `image` from
/// `reference` over `pixels`.
pub fn mean_error(image: &RgbaImage, reference: &RgbaImage, pixels: &[(u32, u32)]) -> f32 {
    let total: f32 = pixels
        .iter()
        .map(|&(x, y)| {
            let (a, b) = (image.get_pixel(x, y).0, reference.get_pixel(x, y).0);
            (0..3)
                .map(|c| (f32::from(a[c]) - f32::from(b[c])).abs() / 255.0)
                .sum::<f32>()
                / 3.0
        })
        .sum();
    total / pixels.len().max(1) as f32
}
