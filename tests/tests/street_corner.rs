//! The shipped street-corner scene, loaded from assets/ and rendered from its own camera.

use std::path::Path;

use pom::render::Renderer;
use pom::{App, PomPlugin, RenderPath, RenderPlugin, load_gltf};
use pom_tests::{FlipTolerance, check_golden, render_both_paths, render_on_path};

#[test]
fn the_shipped_street_corner_matches_its_reference() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets/street_corner.glb");
    let mut app = App::new();
    app.add_plugin(RenderPlugin::new(384, 216))
        .add_plugin(PomPlugin);
    let scene = load_gltf(&mut app, &path).unwrap();
    assert!(scene.warnings.is_empty(), "{:?}", scene.warnings);
    assert_eq!((scene.cameras.len(), scene.lights.len()), (1, 1));
    let image = render_both_paths(&mut app, "street_corner").unwrap();
    check_golden("street_corner", &image, FlipTolerance::default()).unwrap();
    // Every opaque draw of the scene (lit and parallax) shades in the compute resolve: a
    // deferred frame runs no opaque raster pass.
    render_on_path(&mut app, RenderPath::Deferred).unwrap();
    let renderer = app.resources.get::<Renderer>().unwrap();
    assert!(renderer.runs_deferred() && !renderer.ran_opaque_pass());
}

/// The same scene with its sun casting scene shadows: the ball and the crate stand on the
/// cobblestones, and the relief's own shadow map agrees with its self-shadowing.
#[test]
fn the_street_corner_with_scene_shadows_matches_its_reference() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets/street_corner.glb");
    let mut app = App::new();
    app.add_plugin(RenderPlugin::new(384, 216))
        .add_plugin(PomPlugin);
    let scene = load_gltf(&mut app, &path).unwrap();
    for &light in &scene.lights {
        app.world
            .insert_one(light, pom::LightShadows::default())
            .unwrap();
    }
    let image = render_both_paths(&mut app, "street_corner_shadows").unwrap();
    check_golden("street_corner_shadows", &image, FlipTolerance::default()).unwrap();
}

/// The street corner at `file` (under assets/) as a 384 × 216 app.
fn shipped(file: &str) -> (App, pom::GltfScene) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../assets")
        .join(file);
    let mut app = App::new();
    app.add_plugin(RenderPlugin::new(384, 216))
        .add_plugin(PomPlugin);
    let scene = load_gltf(&mut app, &path).unwrap();
    assert!(scene.warnings.is_empty(), "{:?}", scene.warnings);
    (app, scene)
}

/// By day under the sky: the sky behind the wall follows the sun, and its light (the
/// environment, not a constant ambient) fills the shade on both paths.
#[test]
fn the_street_corner_under_the_sky_matches_its_reference() {
    let (mut app, _) = shipped("street_corner.glb");
    app.insert_resource(pom::EnvironmentLight::sky());
    let image = render_both_paths(&mut app, "street_corner_sky").unwrap();
    check_golden("street_corner_sky", &image, FlipTolerance::default()).unwrap();
}

/// At night: the sun has set (the sky is dark), and the street lamps, the sign's lamp, the lamp
/// post and a string of 24 bulbs light the scene, more lights than the renderer once took,
/// with the camera's own night exposure from the file.
#[test]
fn the_street_corner_at_night_matches_its_reference() {
    let (mut app, scene) = shipped("street_corner_night.glb");
    assert_eq!(scene.lights.len(), 29);
    let camera = scene.cameras[0];
    assert_eq!(
        app.world
            .get::<&pom::Exposure>(camera)
            .map(|e| e.ev100)
            .ok(),
        Some(6.5)
    );
    app.insert_resource(pom::EnvironmentLight::sky());
    let image = render_both_paths(&mut app, "street_corner_night").unwrap();
    check_golden("street_corner_night", &image, FlipTolerance::default()).unwrap();
}
