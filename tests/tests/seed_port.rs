//! The seed's shader (Tatarchuk's listing 2, ported for the bench) renders the cobblestones
//! cleanly and agrees with our parallax material where the two do the same thing.

use pom::preview::PreviewView;
use pom::seed_port::SeedPortMaterial;
use pom::{ShadowMode, TargetFormat, patterns};
use pom_tests::pom_scene::{HeightMaterial, preview_app, set_material};
use pom_tests::{in_error_scopes, render_and_capture_finite};

/// Side of the rendered images, and of the square blocks whose luminance is compared.
const SIZE: u32 = 96;
const BLOCK: u32 = 12;

/// Least correlation of the two renderers' block luminances. Measured on lavapipe: 0.98 to 0.93
/// with the seed's shadows, 1.00 to 0.96 without (0°, 45°, 75°); against a flat-shaded plane 0,
/// a port with a flat normal 0.71 (its shadow term still varies), a port without its parallax
/// offset 0.43 at 45°, ours without it 0.60 at 45° and 0.12 at 75°.
const MIN_CORRELATION: f32 = 0.85;

/// How far the port's mean brightness may stray from ours with the shadows off, where both are
/// the same Phong on the same march (measured: 0.0 %, 0.1 %, 0.7 %; flat shading is +10 %).
const SAME_BRIGHTNESS: f32 = 0.03;

/// The port's mean brightness over ours with the seed's shadows: its shadow term
/// `(1 − max(sh)) × 0.6 + 0.4` exceeds 1 wherever nothing occludes, on ambient light too
/// (measured: 1.34, 1.34, 1.39).
const SEED_SHADOW_BRIGHTENING: std::ops::RangeInclusive<f32> = 1.25..=1.5;

/// The preview plane with our material, or with the port wearing the same textures: first with
/// shadows (ours soft, the port its seven taps), then with them off.
fn render(view_angle: f32, port: bool) -> [image::Rgba32FImage; 2] {
    let textures = HeightMaterial {
        field: patterns::cobblestones(256, 6),
        height_scale: 0.05,
    };
    let view = PreviewView {
        view_angle,
        ..PreviewView::default()
    };
    let mut app = preview_app(SIZE, TargetFormat::Float32, &textures, &view, |m| m).unwrap();
    app.add_plugin(pom::seed_port::seed_port_plugin());
    app.finish().unwrap();
    if port {
        let images = app.resources.get_mut::<pom::Assets<pom::Image>>().unwrap();
        assert_eq!(
            pom::seed_port::replace_parallax_materials(&mut app.world, images).unwrap(),
            1
        );
    }
    in_error_scopes(&mut app, "warm-up", |app| Ok(app.update()?)).unwrap();
    let renderer = if port {
        "the seed port"
    } else {
        "our material"
    };
    let frame = |app: &mut pom::App| {
        render_and_capture_finite(app)
            .unwrap_or_else(|error| panic!("{renderer}, {view_angle}°: {error}"))
    };
    let shadowed = frame(&mut app);
    set_material(&mut app, |material| material.shadows = ShadowMode::Off);
    for material in app.world.query_mut::<&mut SeedPortMaterial>() {
        material.shadows = false;
    }
    [shadowed, frame(&mut app)]
}

/// Rec. 709 luminance of a linear pixel.
fn luminance(pixel: &image::Rgba<f32>) -> f32 {
    0.2126 * pixel.0[0] + 0.7152 * pixel.0[1] + 0.0722 * pixel.0[2]
}

fn mean(values: &[f32]) -> f32 {
    values.iter().sum::<f32>() / values.len() as f32
}

/// Mean luminance of each `BLOCK`² block, row by row.
fn block_luminances(image: &image::Rgba32FImage) -> Vec<f32> {
    let blocks = image.width() / BLOCK;
    (0..blocks * blocks)
        .map(|index| {
            let (left, top) = (index % blocks * BLOCK, index / blocks * BLOCK);
            let block: Vec<f32> = (0..BLOCK * BLOCK)
                .map(|i| luminance(image.get_pixel(left + i % BLOCK, top + i / BLOCK)))
                .collect();
            mean(&block)
        })
        .collect()
}

/// Pearson correlation of two equally long lists (NaN when either is constant).
fn correlation(a: &[f32], b: &[f32]) -> f32 {
    let (mean_a, mean_b) = (mean(a), mean(b));
    let (mut ab, mut aa, mut bb) = (0.0, 0.0, 0.0);
    for (x, y) in a.iter().zip(b) {
        ab += (x - mean_a) * (y - mean_b);
        aa += (x - mean_a) * (x - mean_a);
        bb += (y - mean_b) * (y - mean_b);
    }
    ab / (aa * bb).sqrt()
}

#[test]
fn the_seed_port_renders_the_cobblestones_like_our_material() {
    for view_angle in [0.0, 45.0, 75.0] {
        let [port_shadowed, port_unshadowed] = render(view_angle, true);
        let [ours_shadowed, ours_unshadowed] = render(view_angle, false);
        let same_brightness = 1.0 - SAME_BRIGHTNESS..=1.0 + SAME_BRIGHTNESS;
        for (shadows, port, ours, expected) in [
            (
                "shadows",
                &port_shadowed,
                &ours_shadowed,
                SEED_SHADOW_BRIGHTENING,
            ),
            (
                "no shadows",
                &port_unshadowed,
                &ours_unshadowed,
                same_brightness,
            ),
        ] {
            let (port_blocks, ours_blocks) = (block_luminances(port), block_luminances(ours));
            let (port_mean, ours_mean) = (mean(&port_blocks), mean(&ours_blocks));
            let ratio = port_mean / ours_mean;
            let agreement = correlation(&port_blocks, &ours_blocks);
            eprintln!(
                "{view_angle}°, {shadows}: mean luminance {port_mean:.4} (port) vs \
                 {ours_mean:.4} (ours), ratio {ratio:.3}, block correlation {agreement:.3}"
            );
            // Where the relief shades the stones, both must shade the same stones.
            assert!(
                agreement >= MIN_CORRELATION,
                "{view_angle}°, {shadows}: the two relief patterns correlate by {agreement} \
                 (at least {MIN_CORRELATION})"
            );
            assert!(
                expected.contains(&ratio),
                "{view_angle}°, {shadows}: the port is {ratio} times as bright as ours \
                 (expected {expected:?})"
            );
        }
    }
}
