//! The GPU march matches the CPU reference, and the methods rank as Tatarchuk's text claims.

use glam::{Vec2, Vec3};
use pom::preview::PreviewView;
use pom::reference::{self, mean_error_in_texels};
use pom::{HeightField, ParallaxMethod, patterns};
use pom_tests::pom_scene::{HeightMaterial, uv_view, wrapped};

const IMAGE: u32 = 64;
const HEIGHT_SCALE: f32 = 0.04;

/// Renders the `uv` debug view of `method` seen `angle` degrees from the normal (azimuth 0,
/// orthographic, so every pixel has the same view vector and the texture is never minified).
fn gpu_uv(textures: &HeightMaterial, method: ParallaxMethod, angle: f32) -> image::Rgba32FImage {
    let view = PreviewView {
        view_angle: angle,
        ..PreviewView::default()
    };
    uv_view(IMAGE, textures, &view, method).unwrap()
}

#[test]
fn gpu_march_matches_the_cpu_reference_within_a_quarter_texel() {
    let field = patterns::cobblestones(64, 4).quantized();
    let size = Vec2::splat(64.0);
    let pyramid = reference::MaxPyramid::new(&field);
    let textures = HeightMaterial {
        field: field.clone(),
        height_scale: HEIGHT_SCALE,
    };
    let mut report = Vec::new();
    for angle in [0.0_f32, 30.0, 60.0, 80.0, 88.0] {
        let entry = gpu_uv(&textures, ParallaxMethod::NormalMapping, angle);
        let radians = angle.to_radians();
        let to_eye_ts = Vec3::new(-radians.sin(), 0.0, radians.cos());
        let steps = reference::view_steps(to_eye_ts, HEIGHT_SCALE, size, 8, 50);
        for method in [
            ParallaxMethod::Steep,
            ParallaxMethod::Occlusion,
            ParallaxMethod::Relief,
            ParallaxMethod::MaxMip,
        ] {
            let gpu = gpu_uv(&textures, method, angle);
            let (mut total, mut count) = (0.0, 0);
            for (x, y, entry_pixel) in entry.enumerate_pixels() {
                let uv0 = Vec2::new(entry_pixel.0[0], entry_pixel.0[1]);
                let cpu = if method == ParallaxMethod::MaxMip {
                    reference::march_max_mip(&pyramid, uv0, to_eye_ts, HEIGHT_SCALE).uv
                } else {
                    reference::march_view(&field, method, uv0, to_eye_ts, HEIGHT_SCALE, steps).uv
                };
                let gpu_pixel = gpu.get_pixel(x, y).0;
                assert_eq!(gpu_pixel[2], 1.0, "the full march ran at ({x}, {y})");
                let difference =
                    Vec2::new(wrapped(gpu_pixel[0] - cpu.x), wrapped(gpu_pixel[1] - cpu.y));
                total += (difference * size).length();
                count += 1;
            }
            let mean = total / count as f32;
            report.push(format!(
                "{angle:>4}° {method:?}: mean |GPU − CPU| = {mean:.4} texel"
            ));
            assert!(mean <= 0.25, "{angle}° {method:?}: {mean} texels");
        }
    }
    eprintln!("{}", report.join("\n"));
}

fn error_table(name: &str, field: &HeightField) -> Vec<(u32, f32, f32, f32)> {
    let mut rows = Vec::new();
    for steps in [8, 16, 32, 64] {
        let error = |method| mean_error_in_texels(field, method, 70.0, HEIGHT_SCALE, steps, 32);
        let row = (
            steps,
            error(ParallaxMethod::Steep),
            error(ParallaxMethod::Occlusion),
            error(ParallaxMethod::Relief),
        );
        eprintln!(
            "{name:>12} {:>3} samples: steep {:.3}  POM {:.3}  relief {:.3} texels",
            row.0, row.1, row.2, row.3
        );
        rows.push(row);
    }
    rows
}

#[test]
fn pom_is_more_accurate_than_steep_at_equal_samples() {
    // T Fig. 4-5: the piecewise-linear intersection beats the first-sample-below answer.
    let cobbles = error_table("cobblestone", &patterns::cobblestones(128, 4).quantized());
    let cones = error_table("cones", &patterns::cones(128, 4.0).quantized());
    for (steps, steep, pom, _) in cobbles.iter().chain(&cones) {
        assert!(pom < steep, "{steps} samples: POM {pom} ≥ steep {steep}");
    }
    // More samples help every method.
    for table in [&cobbles, &cones] {
        assert!(table[3].1 < table[0].1 && table[3].2 < table[0].2);
    }
}
