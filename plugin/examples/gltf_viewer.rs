//! Any glTF file in a window, with an orbit camera (left drag orbits, right drag pans, the
//! wheel zooms, arrows and W/A/S/D move) and the file's own lights, or a sun where it has none.
//!
//! `cargo run --release -p parallax-occlusion --example gltf_viewer --features window -- assets/street_corner.glb`

use pom::prelude::*;

fn main() -> AppExit {
    let Some(path) = std::env::args().nth(1) else {
        eprintln!("usage: gltf_viewer PATH.glb|PATH.gltf");
        return AppExit::error();
    };
    let mut app = App::new();
    app.add_plugin(DefaultPlugins::windowed(WindowPlugin {
        title: format!("gltf_viewer: {path}"),
        ..WindowPlugin::default()
    }))
    .add_plugin(OrbitCameraPlugin);
    let scene = match load_gltf(&mut app, &path) {
        Ok(scene) => scene,
        Err(error) => {
            eprintln!("error: {error}");
            return AppExit::error();
        }
    };
    for warning in &scene.warnings {
        eprintln!("warning: {warning}");
    }
    let (low, high) = scene
        .framing_bounds
        .unwrap_or((Vec3::splat(-0.5), Vec3::splat(0.5)));
    let centre = (low + high) * 0.5;
    let radius = ((high - low).length() * 0.5).max(0.1);
    // The file's first camera, orbiting the middle of what it frames; else a three-quarter view.
    let camera = scene.cameras.first().copied().unwrap_or_else(|| {
        let eye = centre + Vec3::new(1.0, 0.8, 1.4).normalize() * radius * 2.5;
        app.world.spawn((
            Camera::perspective(45.0),
            Transform::from_translation(eye).looking_at(centre, Vec3::Y),
        ))
    });
    scene.activate_camera(&mut app.world, (!scene.cameras.is_empty()).then_some(0));
    let start = app
        .world
        .get::<&Transform>(camera)
        .map(|t| *t)
        .unwrap_or_default();
    let focus = (centre - start.translation)
        .dot(start.rotation * Vec3::NEG_Z)
        .max(0.5);
    let _ = app
        .world
        .insert_one(camera, OrbitCamera::from_transform(&start, focus));
    if scene.lights.is_empty() {
        app.world.spawn((
            DirectionalLight::default(),
            Transform::IDENTITY.looking_at(Vec3::new(-0.5, -1.0, -0.4), Vec3::Y),
        ));
    }
    app.run()
}
