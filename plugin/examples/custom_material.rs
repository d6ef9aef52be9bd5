//! `Matte`, the material of the README and of "Writing your own material"
//! (plugin/docs/custom-material.md), in a window: a spinning cube over a floor, both `Matte`,
//! the cube's shadow on the floor, with the orbit camera.
//!
//! `cargo run --release -p parallax-occlusion --example custom_material --features window`

// The document's code, kept identical to it by tests/tests/custom_material.rs.
#[rustfmt::skip]
#[path = "../../tests/tests/custom_material/matte.rs"]
mod matte;

use matte::Matte;
use pom::prelude::*;

/// Marks the cube that spins.
struct Spinning;

fn main() -> AppExit {
    let mut app = App::new();
    app.add_plugin(DefaultPlugins::windowed(WindowPlugin {
        title: "custom_material".to_owned(),
        ..WindowPlugin::default()
    }))
    .add_plugin(MaterialPlugin::<Matte>::default())
    .add_plugin(OrbitCameraPlugin)
    .add_system(Stage::Startup, setup)
    .add_system(Stage::Update, spin);
    app.run()
}

fn setup(world: &mut World, resources: &mut Resources) {
    let Some(meshes) = resources.get_mut::<Assets<Mesh>>() else {
        return;
    };
    let (cube, floor) = (meshes.add(Mesh::cube(0.8)), meshes.add(Mesh::plane(4.0)));
    world.spawn((
        cube,
        Matte {
            color: Color::linear_rgb(0.9, 0.35, 0.05),
        },
        Transform::from_xyz(0.0, 0.5, 0.0),
        Spinning,
    ));
    world.spawn((
        floor,
        Matte {
            color: Color::linear_rgb(0.5, 0.5, 0.5),
        },
        Transform::IDENTITY,
    ));
    let eye = Transform::from_xyz(1.6, 1.8, 2.4).looking_at(Vec3::new(0.0, 0.4, 0.0), Vec3::Y);
    world.spawn((
        Camera::perspective(45.0),
        eye,
        OrbitCamera::from_transform(&eye, 3.2),
    ));
    world.spawn((
        DirectionalLight::default(),
        LightShadows::default(),
        Transform::IDENTITY.looking_at(Vec3::new(-0.4, -1.0, -0.6), Vec3::Y),
    ));
}

fn spin(world: &mut World, resources: &mut Resources) {
    let angle = resources.get::<Time>().map_or(0.0, Time::delta_secs);
    for transform in world.query_mut::<&mut Transform>().with::<&Spinning>() {
        transform.rotation = Quat::from_rotation_y(angle) * transform.rotation;
    }
}
