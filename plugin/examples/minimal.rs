//! The README's game in a window: a parallax brick plane, lit, seen from above.
//! `cargo run --release -p parallax-occlusion --example minimal --features window`
use pom::prelude::*;

fn main() -> AppExit {
    let mut app = App::new();
    app.add_plugin(DefaultPlugins::windowed(WindowPlugin::default()));
    let bricks = patterns::bricks(256, 4.0, 8.0);
    let images = app.resources.get_or_default::<Assets<Image>>();
    let material = ParallaxOcclusionMaterial {
        normal_map: Some(images.add(bricks.normal_map(0.05))),
        height_map: Some(HeightSource::Texture(images.add(bricks.to_image()))),
        ..Default::default()
    };
    let meshes = app.resources.get_or_default::<Assets<Mesh>>();
    let plane = meshes.add(Mesh::plane(2.0));
    app.world.spawn((plane, material, Transform::IDENTITY));
    let eye = Transform::from_xyz(0.0, 1.5, 2.0).looking_at(Vec3::ZERO, Vec3::Y);
    app.world.spawn((Camera::perspective(45.0), eye));
    let sun = Transform::IDENTITY.looking_at(Vec3::new(1.0, -1.0, -1.0), Vec3::Y);
    app.world.spawn((DirectionalLight::default(), sun));
    app.run()
}
