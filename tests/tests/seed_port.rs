//! The seed's shader (Tatarchuk's listing 2, ported for the bench) renders the cobblestones
//! cleanly and agrees with our parallax material where the two do the same thing.

use pom::preview::PreviewView;
use pom::{TargetFormat, patterns};
use pom_tests::pom_scene::{HeightMaterial, preview_app};
use pom_tests::{in_error_scopes, render_and_capture_f32};

/// The preview plane with our material, or with the port wearing the same textures.
fn render(view_angle: f32, port: bool) -> image::Rgba32FImage {
    let textures = HeightMaterial {
        field: patterns::cobblestones(256, 6),
        height_scale: 0.05,
    };
    let view = PreviewView {
        view_angle,
        ..PreviewView::default()
    };
    let mut app = preview_app(96, TargetFormat::Float32, &textures, &view, |m| m).unwrap();
    app.add_plugin(pom::seed_port::seed_port_plugin());
    app.finish().unwrap();
    if port {
        assert_eq!(
            pom::seed_port::replace_parallax_materials(&mut app.world),
            1
        );
    }
    in_error_scopes(&mut app, "warm-up", |app| Ok(app.update()?)).unwrap();
    render_and_capture_f32(&mut app).unwrap()
}

fn mean(image: &image::Rgba32FImage) -> f32 {
    let sum: f32 = image
        .pixels()
        .map(|p| (p.0[0] + p.0[1] + p.0[2]) / 3.0)
        .sum();
    sum / (image.width() * image.height()) as f32
}

#[test]
fn the_seed_port_renders_the_cobblestones_like_our_material() {
    for view_angle in [0.0, 45.0, 75.0] {
        let port = render(view_angle, true);
        assert!(
            port.pixels().all(|p| p.0.iter().all(|c| c.is_finite())),
            "NaN at {view_angle}°"
        );
        let ours = render(view_angle, false);
        let (port_mean, ours_mean) = (mean(&port), mean(&ours));
        eprintln!("{view_angle}°: mean {port_mean:.3} (port) vs {ours_mean:.3} (ours)");
        // Both are Phong with the same textures and light: close, not equal. The seed's shadow
        // term (× 0.6 + 0.4, on ambient light too) is brighter than ours: +34 % at 0°.
        assert!(port_mean > 0.05, "a black port at {view_angle}°");
        assert!(
            (port_mean - ours_mean).abs() < 0.5 * ours_mean,
            "{view_angle}°: {port_mean} vs {ours_mean}"
        );
    }
}
