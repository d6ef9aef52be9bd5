//! No window: renders one frame of a parallax plane to a PNG (the path given, else
//! `headless.png`). Builds and runs without the `window` feature.
//!
//! `cargo run --release -p parallax-occlusion --example headless -- bricks.png`

use pom::prelude::*;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let out = std::env::args()
        .nth(1)
        .unwrap_or_else(|| "headless.png".to_owned());
    let mut app = App::new();
    app.add_plugin(DefaultPlugins::headless(512, 512));
    let bricks = patterns::bricks(256, 4.0, 8.0);
    let images = app
        .resources
        .get_mut::<Assets<Image>>()
        .ok_or("no image store")?;
    let material = ParallaxOcclusionMaterial {
        normal_map: Some(images.add(bricks.normal_map(0.05))),
        height_map: Some(HeightSource::Texture(images.add(bricks.to_image()))),
        ..Default::default()
    };
    let plane = app
        .resources
        .get_mut::<Assets<Mesh>>()
        .ok_or("no mesh store")?
        .add(Mesh::plane(2.0));
    app.world.spawn((plane, material, Transform::IDENTITY));
    app.world.spawn((
        Camera::perspective(45.0),
        Transform::from_xyz(0.0, 1.5, 2.0).looking_at(Vec3::ZERO, Vec3::Y),
    ));
    app.world.spawn((
        DirectionalLight::default(),
        Transform::IDENTITY.looking_at(Vec3::new(1.0, -1.0, -1.0), Vec3::Y),
    ));
    app.update()?;
    capture(&app)?.save(&out)?;
    println!("wrote {out}");
    Ok(())
}
