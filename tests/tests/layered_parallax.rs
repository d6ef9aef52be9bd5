//! The layered parallax material on the GPU: the march meets the blended height field exactly
//! where the CPU reference (`reference::blended_height`) puts it, a tall layer casts its
//! self-shadow onto a low one across a weight boundary, and both paths agree.

use glam::{Vec2, Vec4};
use image::{Rgba, Rgba32FImage, RgbaImage};
use pom::preview::{PreviewView, spawn_preview};
use pom::reference::blended_height;
use pom::{
    App, Assets, DebugView, HeightField, Image, LayerWeights, ParallaxLayer, ParallaxLayers,
    ParallaxMethod, ParallaxOcclusionMaterial, RenderPath, ShadowMode, TargetFormat, TextureKind,
};
use pom_tests::pom_scene::pom_app;
use pom_tests::{render_both_paths, render_on_path_f32};

const SIZE: u32 = 128;
const HEIGHT_SCALE: f32 = 0.05;
/// Texels across the weight map.
const WEIGHT_TEXELS: u32 = 128;

/// A weight map across the plane: the top layer's weight `top(u)` in red, the floor's the rest
/// in green, as 8-bit texels (what the GPU reads).
fn weight_map(top: impl Fn(f32) -> f32) -> RgbaImage {
    RgbaImage::from_fn(WEIGHT_TEXELS, 4, |x, _| {
        let top =
            (top((x as f32 + 0.5) / WEIGHT_TEXELS as f32).clamp(0.0, 1.0) * 255.0).round() as u8;
        Rgba([top, 255 - top, 0, 255])
    })
}

/// The blended height at `u` as the CPU reference has it: the 8-bit weights sampled bilinearly
/// (clamped to the map's texel centres, as the shader samples them), the top layer at 1 and
/// the floor at 0.
fn reference_height(weights: &RgbaImage, contrast: f32, u: f32) -> f32 {
    let x = (u * WEIGHT_TEXELS as f32 - 0.5).clamp(0.0, WEIGHT_TEXELS as f32 - 1.0);
    let (left, t) = (x.floor() as u32, x.fract());
    let right = (left + 1).min(WEIGHT_TEXELS - 1);
    let weight = |x: u32, channel: usize| f32::from(weights.get_pixel(x, 0).0[channel]) / 255.0;
    let mix = |channel| weight(left, channel) * (1.0 - t) + weight(right, channel) * t;
    blended_height(
        Vec4::new(1.0, 0.0, 1.0, 1.0),
        Vec4::new(mix(0), mix(1), 0.0, 0.0),
        contrast,
    )
}

/// A preview app of the two-layer material (top flat at 1, floor at 0, mixed by `weights`),
/// seen from `view`, with `configure` applied.
fn layered_app(
    weights: &RgbaImage,
    contrast: f32,
    view: &PreviewView,
    format: TargetFormat,
    configure: impl FnOnce(ParallaxOcclusionMaterial) -> ParallaxOcclusionMaterial,
) -> App {
    let mut app = pom_app(SIZE, format).expect("app");
    let images = app.resources.get_mut::<Assets<Image>>().expect("images");
    let solid = |rgba| Image::solid(rgba, TextureKind::Color);
    let (top_colour, floor_colour) = (
        images.add(solid([200, 120, 60, 255])),
        images.add(solid([60, 140, 200, 255])),
    );
    let weight_image = images.add(Image::new(weights.clone(), TextureKind::Data).expect("weights"));
    let (top, floor) = (
        HeightField::from_fn(4, 4, |_, _| 1.0),
        HeightField::from_fn(4, 4, |_, _| 0.0),
    );
    let layer = |colour| ParallaxLayer {
        base_color_texture: Some(colour),
        ..ParallaxLayer::default()
    };
    let layers = ParallaxLayers::new(
        images,
        vec![
            (layer(top_colour), Some(&top)),
            (layer(floor_colour), Some(&floor)),
        ],
        LayerWeights::Texture(weight_image),
    )
    .expect("layers");
    let material = configure(ParallaxOcclusionMaterial {
        layers: Some(layers),
        height_scale: HEIGHT_SCALE,
        layer_blend_contrast: contrast,
        min_samples: 64,
        max_samples: 128,
        secant_steps: 8,
        lod_threshold: 16.0,
        ..ParallaxOcclusionMaterial::default()
    });
    spawn_preview(&mut app, material, view).expect("preview");
    app
}

/// The raw uv view of `method` on `path`.
fn uv_view(
    weights: &RgbaImage,
    contrast: f32,
    view: &PreviewView,
    method: ParallaxMethod,
    path: RenderPath,
) -> Rgba32FImage {
    let mut app = layered_app(weights, contrast, view, TargetFormat::Float32, |material| {
        ParallaxOcclusionMaterial {
            method,
            debug_view: DebugView::Uv,
            shadows: ShadowMode::Off,
            ..material
        }
    });
    render_on_path_f32(&mut app, path).expect("render")
}

/// Top layer for u < 0.25, floor past 0.75, a linear ramp between.
fn ramp(u: f32) -> f32 {
    (0.75 - u) / 0.5
}

#[test]
fn the_march_meets_the_blended_height_field_of_the_reference() {
    let view = PreviewView {
        view_angle: 60.0,
        ..PreviewView::default()
    };
    let weights = weight_map(ramp);
    let full_shift = HEIGHT_SCALE * 60_f32.to_radians().tan();
    for path in [RenderPath::Forward, RenderPath::Deferred] {
        for contrast in [0.0, 0.5, 0.9] {
            let entry = uv_view(
                &weights,
                contrast,
                &view,
                ParallaxMethod::NormalMapping,
                path,
            );
            let seen = uv_view(&weights, contrast, &view, ParallaxMethod::Occlusion, path);
            let mut worst_texels = 0.0_f32;
            let (mut top_shifts, mut floor_shifts) = (Vec::new(), Vec::new());
            let mut checked = 0;
            // The direction of the parallax shift (the offset vector P, whose length is the
            // shift at the deepest height): the pixels' mean on the floor.
            let pixels: Vec<(Vec2, Vec2)> = (0..SIZE * SIZE)
                .map(|i| (i % SIZE, i / SIZE))
                .filter(|&(x, y)| seen.get_pixel(x, y).0[2] == 1.0)
                .map(|(x, y)| {
                    let (e, s) = (entry.get_pixel(x, y).0, seen.get_pixel(x, y).0);
                    (Vec2::new(e[0], e[1]), Vec2::new(s[0], s[1]))
                })
                // The view shows fract(uv): a ray that crossed an edge of the texture is left out.
                .filter(|(entered, hit)| (*hit - *entered).length() <= 1.01 * full_shift)
                .collect();
            let direction = pixels
                .iter()
                .filter(|(entered, _)| entered.x > 0.8)
                .map(|(entered, hit)| *hit - *entered)
                .sum::<Vec2>()
                .normalize();
            let offset = direction * full_shift;
            for (entered, hit) in &pixels {
                let shift = (*hit - *entered).length();
                if entered.x < 0.2 && hit.x < 0.2 {
                    top_shifts.push(shift);
                }
                if entered.x > 0.8 && hit.x > 0.8 {
                    floor_shifts.push(shift);
                }
                // The exact crossing of the ray (height 1 − t at entered + t · P) with the
                // reference's blended surface: the first sign change, then bisection.
                let gap = |t: f32| {
                    (1.0 - t) - reference_height(&weights, contrast, (*entered + offset * t).x)
                };
                let steps = 4000;
                let Some(i) = (1..=steps).find(|&i| gap(i as f32 / steps as f32) <= 0.0) else {
                    continue;
                };
                let (mut low, mut high) = ((i - 1) as f32 / steps as f32, i as f32 / steps as f32);
                for _ in 0..30 {
                    let middle = 0.5 * (low + high);
                    if gap(middle) <= 0.0 {
                        high = middle
                    } else {
                        low = middle
                    }
                }
                let expected = *entered + offset * high;
                worst_texels = worst_texels.max((*hit - expected).length() * WEIGHT_TEXELS as f32);
                checked += 1;
            }
            let mean = |shifts: &[f32]| shifts.iter().sum::<f32>() / shifts.len().max(1) as f32;
            eprintln!(
                "{path:?}, contrast {contrast}: {checked} pixels, worst distance from the reference's hit {worst_texels:.4} texels; shift where the top wins {:.5} ({} pixels), where the floor wins {:.5} ({} pixels; expected {full_shift:.5})",
                mean(&top_shifts),
                top_shifts.len(),
                mean(&floor_shifts),
                floor_shifts.len()
            );
            assert!(checked > 2000, "{checked}");
            assert!(top_shifts.len() > 100 && floor_shifts.len() > 100);
            assert!(
                top_shifts.iter().all(|shift| *shift < 1e-6),
                "the top layer does not shift"
            );
            assert!(
                (mean(&floor_shifts) - full_shift).abs() <= 0.02 * full_shift,
                "the floor shifts by height_scale · tan θ"
            );
            assert!(worst_texels <= 0.1, "{worst_texels} texels");
        }
    }
}

#[test]
fn a_tall_layer_casts_its_shadow_onto_a_low_one_across_the_weight_boundary() {
    // Top below u = 0.5, floor above it; the light comes from the −u side, 60° from the normal.
    let weights = weight_map(|u| if u < 0.5 { 1.0 } else { 0.0 });
    let view = PreviewView {
        light_angle: 60.0,
        ..PreviewView::default()
    };
    let expected_width = HEIGHT_SCALE * 60_f32.to_radians().tan();
    for path in [RenderPath::Forward, RenderPath::Deferred] {
        let uv = uv_view(&weights, 0.9, &view, ParallaxMethod::Occlusion, path);
        let mut app = layered_app(&weights, 0.9, &view, TargetFormat::Float32, |material| {
            ParallaxOcclusionMaterial {
                debug_view: DebugView::Shadow,
                shadows: ShadowMode::Hard,
                ..material
            }
        });
        let shadow = render_on_path_f32(&mut app, path).expect("render");
        // Down the middle column (along u): the shadowed band on the floor, next to the boundary.
        let x = SIZE / 2;
        let samples: Vec<(f32, f32)> = (0..SIZE)
            .map(|y| (uv.get_pixel(x, y).0[0], shadow.get_pixel(x, y).0[0]))
            .filter(|(u, _)| *u > 0.51 && *u < 0.98)
            .collect();
        let lit_edge = samples
            .iter()
            .filter(|(_, visibility)| *visibility < 0.5)
            .map(|(u, _)| *u)
            .fold(f32::NEG_INFINITY, f32::max);
        let width = lit_edge - 0.5;

        let pixel = 1.0 / SIZE as f32;
        eprintln!("{path:?}: shadow on the floor {width:.4} wide (expected {expected_width:.4})");
        assert!(
            samples
                .iter()
                .any(|(u, visibility)| *u > 0.7 && *visibility == 1.0),
            "the floor away from the boundary is lit"
        );
        assert!(
            (width - expected_width).abs() <= 1.5 * pixel,
            "{width} vs {expected_width}"
        );
    }
}

#[test]
fn the_layered_ramp_looks_the_same_on_both_paths() {
    let view = PreviewView {
        view_angle: 50.0,
        light_angle: 50.0,
        ..PreviewView::default()
    };
    let mut app = layered_app(
        &weight_map(ramp),
        0.5,
        &view,
        TargetFormat::Srgb8,
        |material| material,
    );
    let image = render_both_paths(&mut app, "layered_ramp").expect("paths agree");
    assert!(
        image.pixels().any(|p| p.0[0] > p.0[2] + 40),
        "the top layer shows"
    );
    assert!(
        image.pixels().any(|p| p.0[2] > p.0[0] + 40),
        "the floor shows"
    );
}

#[test]
fn golden_cobbles_giving_way_to_bumps_by_height_on_both_paths() {
    // Cobblestones on the left, rounder and shallower bumps on the right, a weight ramp between:
    // across it the stones' tops stand out of the bumps before the bumps cover their grout.
    let view = PreviewView {
        view_angle: 45.0,
        light_angle: 55.0,
        ..PreviewView::default()
    };
    let mut app = pom_app(192, TargetFormat::Srgb8).expect("app");
    let images = app.resources.get_mut::<Assets<Image>>().expect("images");
    let cobbles = pom::patterns::cobblestones(128, 4);
    let bumps = pom::patterns::cones(128, 6.0);
    let (stone, moss) = (
        images.add(Image::solid([170, 160, 150, 255], TextureKind::Color)),
        images.add(Image::solid([90, 140, 70, 255], TextureKind::Color)),
    );
    let layers = vec![
        (
            ParallaxLayer {
                base_color_texture: Some(stone),
                normal_map: Some(images.add(cobbles.normal_map(0.05))),
                tiling: 2.0,
                height_scale: 1.0,
            },
            Some(&cobbles),
        ),
        (
            ParallaxLayer {
                base_color_texture: Some(moss),
                normal_map: Some(images.add(bumps.normal_map(0.03))),
                tiling: 3.0,
                height_scale: 0.6,
            },
            Some(&bumps),
        ),
    ];
    let weights = images.add(Image::new(weight_map(ramp), TextureKind::Data).expect("weights"));
    let layers =
        ParallaxLayers::new(images, layers, LayerWeights::Texture(weights)).expect("layers");
    let material = ParallaxOcclusionMaterial {
        layers: Some(layers),
        height_scale: 0.05,
        layer_blend_contrast: 0.6,
        ..ParallaxOcclusionMaterial::default()
    };
    spawn_preview(&mut app, material, &view).expect("preview");
    let image = render_both_paths(&mut app, "layered_cobbles_bumps").expect("paths agree");
    pom_tests::check_golden(
        "layered_cobbles_bumps",
        &image,
        pom_tests::FlipTolerance::default(),
    )
    .expect("matches the reference");
}
