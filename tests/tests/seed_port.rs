//! The seed's shader (Tatarchuk's listing 2, ported for the bench) renders the cobblestones
//! cleanly and agrees with our parallax material where the two do the same thing, and its
//! compute pass draws what its fragment pass draws (so the bench's compute figure times the
//! same work). The images are written to the temporary folder's `pom-seed-port/`.

use pom::preview::PreviewView;
use pom::seed_port::SeedPortMaterial;
use pom::{ParallaxOcclusionMaterial, ShadowMode, TargetFormat, patterns};
use pom_tests::pom_scene::{HeightMaterial, preview_app, set_material};
use pom_tests::{in_error_scopes, render_and_capture_finite};

/// Side of the rendered images, and of the square blocks whose luminance is compared.
const SIZE: u32 = 96;
const BLOCK: u32 = 12;

/// Least correlation of the two renderers' block luminances, with the light at 60° azimuth
/// (the test prints them): with or without the seed's shadows the two correlate almost
/// perfectly; with the normal map's green unflipped (as the port read it before it took
/// Direct3D's convention) they anticorrelate, and a flat-shaded plane does not correlate at
/// all. (At azimuth 0 light and view lie in the u–n plane, where the green channel never
/// shows.)
const MIN_CORRELATION: f32 = 0.95;

/// How far the port's mean brightness may stray from ours with the shadows off, where both are
/// the same Phong on the same march (they differ by a tenth of this or less; the listing's
/// normalize over all four channels, height included, would be several times it).
const SAME_BRIGHTNESS: f32 = 0.03;

/// The port's mean brightness over ours with the seed's shadows: its shadow term
/// `(1 − max(sh)) × 0.6 + 0.4` exceeds 1 wherever nothing occludes, on ambient light too.
const SEED_SHADOW_BRIGHTENING: std::ops::RangeInclusive<f32> = 1.25..=1.5;

/// Where the light stands around the normal, in degrees: off the u axis the view lies along, so
/// that the normal map's green channel (along v) shows in the shading.
const LIGHT_AZIMUTH: f32 = 60.0;

/// Who draws the plane.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Drawn {
    /// Our parallax material (POM).
    Ours,
    /// The seed port, wearing the same textures.
    Port,
    /// Our material with a flat normal map: flat shading over the same march.
    FlatShaded,
}

/// The preview plane drawn by `drawn`: first with shadows (ours soft, the port its seven taps),
/// then with them off.
fn render(view_angle: f32, drawn: Drawn) -> [image::Rgba32FImage; 2] {
    let textures = HeightMaterial {
        field: patterns::cobblestones(256, 6),
        height_scale: 0.05,
    };
    let view = PreviewView {
        view_angle,
        light_azimuth: LIGHT_AZIMUTH,
        ..PreviewView::default()
    };
    let mut app = preview_app(
        SIZE,
        TargetFormat::Float32,
        &textures,
        &view,
        |m| match drawn {
            Drawn::FlatShaded => ParallaxOcclusionMaterial {
                normal_map: None,
                ..m
            },
            _ => m,
        },
    )
    .unwrap();
    app.add_plugin(pom::seed_port::SeedPortPlugin);
    app.finish().unwrap();
    if drawn == Drawn::Port {
        let images = app.resources.get_mut::<pom::Assets<pom::Image>>().unwrap();
        assert_eq!(
            pom::seed_port::replace_parallax_materials(&mut app.world, images).unwrap(),
            1
        );
    }
    in_error_scopes(&mut app, "warm-up", |app| Ok(app.update()?)).unwrap();
    let frame = |app: &mut pom::App| {
        render_and_capture_finite(app)
            .unwrap_or_else(|error| panic!("{drawn:?}, {view_angle}°: {error}"))
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
        let [port_shadowed, port_unshadowed] = render(view_angle, Drawn::Port);
        let [ours_shadowed, ours_unshadowed] = render(view_angle, Drawn::Ours);
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

/// Most mean FLIP error between the compute pass's image and the fragment pass's (the same
/// listing on the same plane: they differ only in the last bits of the interpolation, far
/// below these bounds).
const COMPUTE_MEAN: f32 = 0.01;
/// Most FLIP error at the 99th percentile between the two.
const COMPUTE_P99: f32 = 0.1;

/// A linear image as display bytes: clamped to 0..1 and sRGB-encoded, the same for every image
/// compared (no tonemapping: both passes write the same pre-exposed scene).
fn display(image: &image::Rgba32FImage) -> image::RgbaImage {
    image::RgbaImage::from_fn(image.width(), image.height(), |x, y| {
        let pixel = image.get_pixel(x, y).0;
        let encode = |v: f32| (pom::linear_to_srgb(v.clamp(0.0, 1.0)) * 255.0).round() as u8;
        image::Rgba([encode(pixel[0]), encode(pixel[1]), encode(pixel[2]), 255])
    })
}

/// Writes `image` where a person can look at it, and says where.
fn keep(image: &image::RgbaImage, name: &str) {
    let dir = std::env::temp_dir().join("pom-seed-port");
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join(format!("{name}.png"));
    image.save(&path).unwrap();
    eprintln!("wrote {}", path.display());
}

/// The seed port's plane at `view_angle`, shadows on: the HDR scene its fragment pass drew,
/// then the one its compute pass wrote over it, rebuilding each pixel from `surface`.
fn fragment_and_compute(
    view_angle: f32,
    surface: pom::seed_port::SeedPortSurface,
) -> [image::Rgba32FImage; 2] {
    let textures = HeightMaterial {
        field: patterns::cobblestones(256, 6),
        height_scale: 0.05,
    };
    let view = PreviewView {
        view_angle,
        tiling: 2.0,
        ..PreviewView::default()
    };
    let mut app = preview_app(SIZE, TargetFormat::Float32, &textures, &view, |m| m).unwrap();
    app.add_plugin(pom::seed_port::SeedPortPlugin);
    app.finish().unwrap();
    let images = app.resources.get_mut::<pom::Assets<pom::Image>>().unwrap();
    pom::seed_port::replace_parallax_materials(&mut app.world, images).unwrap();
    in_error_scopes(&mut app, "fragment pass", |app| Ok(app.update()?)).unwrap();
    let fragment = pom::capture_scene(&app).unwrap();
    let compute = pom::seed_port::SeedPortCompute::on(&app.world, &app.resources, surface).unwrap();
    in_error_scopes(&mut app, "compute pass", |app| {
        Ok(compute.render(&mut app.resources)?)
    })
    .unwrap();
    [fragment, pom::capture_scene(&app).unwrap()]
}

#[test]
fn the_compute_pass_draws_what_the_fragment_pass_draws() {
    use pom::seed_port::SeedPortSurface;
    for (surface, name) in [
        (SeedPortSurface::Triangle, "compute"),
        (SeedPortSurface::AnalyticPlane, "analytic"),
    ] {
        for view_angle in [0.0, 45.0, 75.0] {
            let [fragment, compute] = fragment_and_compute(view_angle, surface);
            let (fragment, compute) = (display(&fragment), display(&compute));
            keep(&fragment, &format!("fragment-{view_angle}"));
            keep(&compute, &format!("{name}-{view_angle}"));
            let flip = pom::flip_compare(&fragment, &compute, 0.99).unwrap();
            keep(&flip.error_map, &format!("{name}-difference-{view_angle}"));
            eprintln!(
                "{view_angle}°: {surface:?} compute against fragment, FLIP mean {:.5}, p99 {:.5}",
                flip.mean, flip.at_percentile
            );
            assert!(
                flip.mean <= COMPUTE_MEAN && flip.at_percentile <= COMPUTE_P99,
                "{view_angle}°: the {surface:?} compute pass differs from the fragment pass by \
                 FLIP mean {} (at most {COMPUTE_MEAN}), p99 {} (at most {COMPUTE_P99})",
                flip.mean,
                flip.at_percentile
            );
        }
    }
}

/// Most mean FLIP error between the port's image and ours, shadows off (where both are Phong on
/// the same march), and the least by which a flat-shaded plane misses ours. The port stays
/// well under the first, flat shading and the port with the listing's four-channel normalize
/// miss ours by several times it (the test prints them).
const BESIDE_OURS_MEAN: f32 = 0.03;

#[test]
fn the_seed_port_looks_like_our_material_and_flat_shading_does_not() {
    for view_angle in [0.0, 45.0, 75.0] {
        let [_, port] = render(view_angle, Drawn::Port);
        let [_, ours] = render(view_angle, Drawn::Ours);
        let [_, flat] = render(view_angle, Drawn::FlatShaded);
        let (port, ours, flat) = (display(&port), display(&ours), display(&flat));
        keep(&port, &format!("port-{view_angle}"));
        keep(&ours, &format!("ours-{view_angle}"));
        keep(&flat, &format!("flat-{view_angle}"));
        let port_flip = pom::flip_compare(&ours, &port, 0.99).unwrap();
        let flat_flip = pom::flip_compare(&ours, &flat, 0.99).unwrap();
        eprintln!(
            "{view_angle}°: port against ours FLIP mean {:.4} p99 {:.4}; flat against ours {:.4} p99 {:.4}",
            port_flip.mean, port_flip.at_percentile, flat_flip.mean, flat_flip.at_percentile
        );
        assert!(port_flip.mean <= BESIDE_OURS_MEAN);
        assert!(flat_flip.mean > BESIDE_OURS_MEAN);
    }
}
