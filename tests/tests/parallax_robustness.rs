//! No NaN at any angle, changes show in the next frame, bad parameters are clamped.

use pom::parallax::MaterialWarnings;
use pom::preview::PreviewView;
use pom::{
    Camera, DebugView, DirectionalLight, LightingModel, ParallaxMethod, ParallaxOcclusionMaterial,
    ShadowMode, TargetFormat, Transform, patterns,
};
use pom_tests::pom_scene::{HeightMaterial, preview_app, set_material};
use pom_tests::{render_and_capture, render_and_capture_finite};

/// A named edit of a material.
type MaterialEdit = (&'static str, fn(&mut ParallaxOcclusionMaterial));

fn bricks() -> HeightMaterial {
    HeightMaterial {
        field: patterns::bricks(64, 4.0, 8.0),
        height_scale: 0.05,
    }
}

fn set_view(app: &mut pom::App, view: &PreviewView) {
    let (camera, camera_transform) = view.camera(1.0);
    for (existing, transform) in app.world.query_mut::<(&mut Camera, &mut Transform)>() {
        *existing = camera;
        *transform = camera_transform;
    }
    for (_, transform) in app.world.query_mut::<(&DirectionalLight, &mut Transform)>() {
        *transform = view.light_transform();
    }
}

#[test]
fn every_method_and_shadow_mode_stays_finite_at_every_angle() {
    let mut app = preview_app(
        24,
        TargetFormat::Float32,
        &bricks(),
        &PreviewView::default(),
        |m| m,
    )
    .unwrap();
    let methods = [
        ParallaxMethod::NormalMapping,
        ParallaxMethod::ParallaxOffset,
        ParallaxMethod::Steep,
        ParallaxMethod::Occlusion,
        ParallaxMethod::Relief,
        ParallaxMethod::MaxMip,
    ];
    let view_angles = [0.0, 20.0, 45.0, 70.0, 85.0, 89.0, 89.9];
    // Including exactly the horizon (90) and below it.
    let light_angles = [0.0, 60.0, 89.0, 90.0, 120.0];
    let mut frames = 0;
    for method in methods {
        for shadows in [ShadowMode::Off, ShadowMode::Hard, ShadowMode::Soft] {
            for (index, view_angle) in view_angles.into_iter().enumerate() {
                let light_angle = light_angles[index % light_angles.len()];
                let height_scale = [0.05, 0.0, 10.0][index % 3];
                set_material(&mut app, |material| {
                    material.method = method;
                    material.shadows = shadows;
                    material.height_scale = height_scale;
                    material.lighting = [
                        LightingModel::Phong,
                        LightingModel::BlinnPhong,
                        LightingModel::CookTorrance,
                        LightingModel::GgxLambert,
                    ][index % 4];
                    material.debug_view =
                        [DebugView::None, DebugView::Lod, DebugView::Samples][index % 3];
                });
                set_view(
                    &mut app,
                    &PreviewView {
                        view_angle,
                        view_azimuth: 17.0 * index as f32,
                        light_angle,
                        light_azimuth: 40.0,
                        ..PreviewView::default()
                    },
                );
                if let Err(error) = render_and_capture_finite(&mut app) {
                    panic!(
                        "{method:?} {shadows:?} view {view_angle}° light {light_angle}° \
                         scale {height_scale}: {error}"
                    );
                }
                frames += 1;
            }
        }
    }
    eprintln!("{frames} frames, no NaN or ∞");
}

#[test]
fn changing_a_field_shows_in_the_next_frame() {
    let view = PreviewView {
        view_angle: 60.0,
        light_angle: 65.0,
        light_azimuth: 30.0,
        ..PreviewView::default()
    };
    let textures = HeightMaterial {
        field: patterns::bricks(128, 2.0, 4.0),
        height_scale: 0.05,
    };
    let mut app = preview_app(48, TargetFormat::Srgb8, &textures, &view, |m| m).unwrap();
    let first = render_and_capture(&mut app).unwrap();
    // assert! rather than assert_eq!: printing two images helps nobody.
    assert!(
        render_and_capture(&mut app).unwrap() == first,
        "nothing changed, yet the pixels did"
    );
    let changes: [MaterialEdit; 9] = [
        ("lighting (Blinn-Phong)", |m| {
            m.lighting = LightingModel::BlinnPhong
        }),
        ("lighting (Cook-Torrance)", |m| {
            m.lighting = LightingModel::CookTorrance
        }),
        ("lighting (GGX-Lambert)", |m| {
            m.lighting = LightingModel::GgxLambert
        }),
        ("metallic", |m| m.metallic = 1.0),
        ("roughness", |m| m.roughness = 0.2),
        ("height_scale", |m| m.height_scale = 0.12),
        ("method", |m| m.method = ParallaxMethod::Steep),
        ("shadows", |m| m.shadows = ShadowMode::Off),
        ("debug_view", |m| m.debug_view = DebugView::Samples),
    ];
    let mut previous = first;
    for (field, change) in changes {
        set_material(&mut app, change);
        let next = render_and_capture(&mut app).unwrap();
        assert!(
            next != previous,
            "changing {field} did not change the next frame"
        );
        previous = next;
    }
}

#[test]
fn invalid_parameters_are_clamped_with_a_warning_and_render_cleanly() {
    let bad_materials: [MaterialEdit; 7] = [
        ("NaN height", |m| m.height_scale = f32::NAN),
        ("infinite height", |m| m.height_scale = f32::INFINITY),
        ("negative height", |m| m.height_scale = -0.3),
        ("zero samples", |m| {
            m.min_samples = 0;
            m.max_samples = 0;
        }),
        ("min over max", |m| {
            m.min_samples = 60;
            m.max_samples = 4;
        }),
        ("absurd samples", |m| m.max_samples = u32::MAX),
        ("NaN softening", |m| m.shadow_softening = f32::NAN),
    ];
    let view = PreviewView {
        view_angle: 70.0,
        ..PreviewView::default()
    };
    for (what, spoil) in bad_materials {
        let mut app = preview_app(
            24,
            TargetFormat::Float32,
            &bricks(),
            &view,
            |mut material| {
                spoil(&mut material);
                assert!(material.validate().is_err(), "{what} should be invalid");
                material
            },
        )
        .unwrap();
        if let Err(error) = render_and_capture_finite(&mut app) {
            panic!("{what}: {error}");
        }
        let warned = app.resources.get::<MaterialWarnings>().unwrap();
        assert_eq!(
            warned.len(),
            1,
            "{what}: the clamp was not recorded for a warning"
        );
    }
}

/// Sets the sun's brightness and the camera's clear colour (which [`set_view`] resets).
fn set_sun_and_clear(app: &mut pom::App, intensity: f32, clear: pom::Color) {
    for light in app.world.query_mut::<&mut DirectionalLight>() {
        light.intensity = intensity;
    }
    for camera in app.world.query_mut::<&mut Camera>() {
        camera.clear_color = clear;
    }
}

/// Rec. 709 luminance of a linear pixel.
fn luminance(pixel: &image::Rgba<f32>) -> f32 {
    0.2126 * pixel.0[0] + 0.7152 * pixel.0[1] + 0.0722 * pixel.0[2]
}

/// The numerical sweep: every method × shadow mode, view angles 0° to 89.99°, sun angles from
/// overhead through exactly the horizon (90°) to below it (100°, 180°), height scale 0 and the
/// largest allowed (10 texture units), samples 1..1 and the maximum (`MAX_SAMPLES_LIMIT`), on one
/// 32² Float32 app whose parameters change between frames.
///
/// Every frame must be free of NaN and ±∞, in the HDR scene before tonemapping too. "Light
/// reaches" a pixel, precisely:
/// - A pixel is *on the surface* when it is not exactly the clear colour, pure blue (0, 0, 1):
///   the surface is grey-albedo and white-lit, so it cannot produce that colour.
/// - The scene has a white ambient light of 0.05, which reaches every surface pixel whatever
///   the relief, the shadows or the sun: no surface pixel may have zero (or negative) luminance.
/// - The sun reaches a surface pixel when it is above the horizon (angle < 90°) and nothing can
///   occlude it. That is known exactly for a height scale of 0 with the normal map's strength 0:
///   the relief is a flat plane, so a shadow ray from any point (as the CPU reference
///   `pom::reference::hard_shadow` marches it) meets no occluder, and
///   N·L = cos(sun angle) > 0. Those pixels must be strictly brighter than the same view lit
///   by the ambient light alone (rendered first, with the sun's intensity 0).
///
/// For the large height scale the relief may shadow any pixel, so only the first two rules apply.
#[test]
fn numerical_sweep_has_no_nan_and_no_black_where_light_reaches() {
    const SIZE: u32 = 32;
    let clear = pom::Color::linear_rgb(0.0, 0.0, 1.0);
    let is_clear = |p: &image::Rgba<f32>| p.0[..3] == [0.0, 0.0, 1.0];
    let mut app = preview_app(
        SIZE,
        TargetFormat::Float32,
        &bricks(),
        &PreviewView::default(),
        |m| m,
    )
    .unwrap();
    app.resources.insert(pom::AmbientLight {
        color: pom::Color::WHITE,
        intensity: 5_000.0,
    });
    let methods = [
        ParallaxMethod::NormalMapping,
        ParallaxMethod::ParallaxOffset,
        ParallaxMethod::Steep,
        ParallaxMethod::Occlusion,
        ParallaxMethod::Relief,
        ParallaxMethod::MaxMip,
    ];
    let view_angles = [0.0, 30.0, 60.0, 80.0, 89.0, pom::preview::MAX_VIEW_ANGLE];
    let sun_angles = [0.0, 45.0, 89.9, 90.0, 100.0, 180.0];
    let reliefs = [(0.0, 0.0), (10.0, 1.0)]; // (height_scale, normal_strength)
    let samples = [
        (1, 1),
        (
            pom::parallax::MAX_SAMPLES_LIMIT,
            pom::parallax::MAX_SAMPLES_LIMIT,
        ),
    ];
    let (mut frames, mut surface_pixels, mut sunlit_checked) = (0, 0_usize, 0_usize);
    for view_angle in view_angles {
        let view = |sun_angle| PreviewView {
            view_angle,
            view_azimuth: 20.0,
            light_angle: sun_angle,
            light_azimuth: 200.0,
            ..PreviewView::default()
        };
        // Ambient alone, flat relief: the floor each sunlit flat pixel must exceed.
        set_view(&mut app, &view(0.0));
        set_sun_and_clear(&mut app, 0.0, clear);
        set_material(&mut app, |m| {
            m.height_scale = 0.0;
            m.normal_strength = 0.0;
            m.shadows = ShadowMode::Off;
            m.method = ParallaxMethod::NormalMapping;
        });
        let ambient_only = render_and_capture_finite(&mut app)
            .unwrap_or_else(|error| panic!("ambient only, view {view_angle}°: {error}"));
        for sun_angle in sun_angles {
            set_view(&mut app, &view(sun_angle));
            set_sun_and_clear(&mut app, 100_000.0, clear);
            for method in methods {
                for shadows in [ShadowMode::Off, ShadowMode::Hard, ShadowMode::Soft] {
                    for (height_scale, normal_strength) in reliefs {
                        for (min_samples, max_samples) in samples {
                            set_material(&mut app, |m| {
                                m.method = method;
                                m.shadows = shadows;
                                m.height_scale = height_scale;
                                m.normal_strength = normal_strength;
                                m.min_samples = min_samples;
                                m.max_samples = max_samples;
                            });
                            let case = format!(
                                "{method:?} {shadows:?} view {view_angle}° sun {sun_angle}° \
                                 height {height_scale} samples {max_samples}"
                            );
                            let image = render_and_capture_finite(&mut app)
                                .unwrap_or_else(|error| panic!("{case}: {error}"));
                            frames += 1;
                            for ((x, y, pixel), floor) in
                                image.enumerate_pixels().zip(ambient_only.pixels())
                            {
                                if is_clear(pixel) {
                                    continue;
                                }
                                surface_pixels += 1;
                                assert!(
                                    luminance(pixel) > 0.0,
                                    "{case}: pixel ({x}, {y}) is black though ambient light reaches it"
                                );
                                if height_scale == 0.0 && sun_angle < 90.0 && !is_clear(floor) {
                                    sunlit_checked += 1;
                                    assert!(
                                        luminance(pixel) > luminance(floor),
                                        "{case}: pixel ({x}, {y}) has luminance {} but ambient \
                                         alone gives {}: the sun does not reach it",
                                        luminance(pixel),
                                        luminance(floor)
                                    );
                                }
                            }
                        }
                    }
                }
            }
        }
    }
    // The checks must have looked at something at every angle.
    assert!(
        surface_pixels > frames * 8,
        "{surface_pixels} surface pixels in {frames} frames"
    );
    assert!(sunlit_checked > 0);
    eprintln!(
        "{frames} frames: no NaN or ∞; {surface_pixels} surface pixels lit; \
         {sunlit_checked} flat sunlit pixels brighter than ambient alone"
    );
}
