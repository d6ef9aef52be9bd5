//! No NaN at any angle, changes show in the next frame, bad parameters are clamped.

use pom::parallax::MaterialWarnings;
use pom::preview::PreviewView;
use pom::{
    Camera, DebugView, DirectionalLight, LightingModel, ParallaxMethod, ParallaxOcclusionMaterial,
    ShadowMode, TargetFormat, Transform, patterns,
};
use pom_tests::pom_scene::{HeightMaterial, preview_app};
use pom_tests::{render_and_capture, render_and_capture_f32};

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

fn set_material(app: &mut pom::App, change: impl Fn(&mut ParallaxOcclusionMaterial)) {
    for material in app.world.query_mut::<&mut ParallaxOcclusionMaterial>() {
        change(material);
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
        ParallaxMethod::Relief { binary_steps: 6 },
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
                    ][index % 3];
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
                let image = render_and_capture_f32(&mut app).unwrap();
                let bad = image
                    .pixels()
                    .filter(|p| p.0.iter().any(|c| !c.is_finite()))
                    .count();
                assert_eq!(
                    bad, 0,
                    "{method:?} {shadows:?} view {view_angle}° light {light_angle}° scale {height_scale}"
                );
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
    let changes: [MaterialEdit; 8] = [
        ("lighting (Blinn-Phong)", |m| {
            m.lighting = LightingModel::BlinnPhong
        }),
        ("lighting (Cook-Torrance)", |m| {
            m.lighting = LightingModel::CookTorrance
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
        let image = render_and_capture_f32(&mut app).unwrap();
        assert!(
            image.pixels().all(|p| p.0.iter().all(|c| c.is_finite())),
            "{what}: NaN"
        );
        let warned = app.resources.get::<MaterialWarnings>().unwrap();
        assert_eq!(
            warned.len(),
            1,
            "{what}: the clamp was not recorded for a warning"
        );
    }
}
