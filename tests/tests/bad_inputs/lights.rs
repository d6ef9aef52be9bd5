//! More lights than the renderer takes: past `MAX_POINT_LIGHTS` point and spot lights the rest
//! are left out with one warning; past the shadow-map budget the rest cast no scene shadow,
//! with one warning. Every light up to the limits still shines.

use pom::render::lights::MAX_POINT_LIGHTS;
use pom::{LightShadows, ParallaxOcclusionMaterial, PointLight, Transform};

use super::{install_logger, material_app, renders_cleanly, warnings_containing};

#[test]
fn more_point_lights_than_the_frame_holds() {
    install_logger();
    let mut app = material_app(|_| ParallaxOcclusionMaterial::default());
    // Far below the plane and out of view: they cost the extraction, not the frame.
    let light = PointLight {
        range: 0.5,
        ..PointLight::default()
    };
    app.world.spawn_batch(
        (0..MAX_POINT_LIGHTS + 3).map(|_| (light, Transform::from_xyz(0.0, -1000.0, 0.0))),
    );
    for _ in 0..3 {
        renders_cleanly(&mut app);
    }
    let warnings = warnings_containing("(MAX_POINT_LIGHTS)");
    assert_eq!(warnings.len(), 1, "{warnings:?}");
    assert!(
        warnings[0].contains(&format!(
            "more than {MAX_POINT_LIGHTS} point and spot lights"
        )),
        "{warnings:?}"
    );
}

#[test]
fn more_shadow_maps_than_the_budget() {
    install_logger();
    let mut app = material_app(|_| ParallaxOcclusionMaterial::default());
    // Six faces each: 36 maps for a budget of MAX_SHADOW_VIEWS (32).
    for index in 0..6 {
        let light = PointLight {
            intensity: 1000.0,
            range: 5.0,
            ..PointLight::default()
        };
        let place = Transform::from_xyz(index as f32 * 0.3 - 0.75, 1.5, 0.0);
        app.world.spawn((light, LightShadows::default(), place));
    }
    for _ in 0..3 {
        renders_cleanly(&mut app);
    }
    let needle = format!(
        "more than {} shadow maps: the rest cast no scene shadow",
        pom::render::MAX_SHADOW_VIEWS
    );
    assert_eq!(warnings_containing(&needle).len(), 1);
}
