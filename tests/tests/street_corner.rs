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
