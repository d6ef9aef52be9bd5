//! A spinning parallax cube on a parallax floor, in a window (the shape of Bevy's
//! `parallax_mapping` example). Keys: 1 / 2 depth down / up, 3 / 4 max samples down / up,
//! Space the next method, arrows move the light; the values are in the window's title. The
//! camera flies (`FlyCameraPlugin`): W/A/S/D and Q/E, drag with a mouse button held to look.
//!
//! `cargo run --release -p parallax-occlusion --example parallax --features window`

use pom::prelude::*;

/// Marks the cube that spins.
struct Spinning;

fn main() -> AppExit {
    let mut app = App::new();
    app.add_plugin(DefaultPlugins::windowed(WindowPlugin {
        title: "parallax".to_owned(),
        ..WindowPlugin::default()
    }))
    .add_plugin(FlyCameraPlugin)
    .add_system(Stage::Startup, setup)
    .add_system(Stage::Update, controls)
    .add_system(Stage::Update, spin);
    app.run()
}

/// The bricks as a parallax material: normals from the same heights, at the same depth.
fn bricks(resources: &mut Resources) -> ParallaxOcclusionMaterial {
    let height = patterns::bricks(256, 4.0, 8.0);
    let Some(images) = resources.get_mut::<Assets<Image>>() else {
        return ParallaxOcclusionMaterial::default();
    };
    ParallaxOcclusionMaterial {
        normal_map: Some(images.add(height.normal_map(0.05))),
        height_map: Some(HeightSource::Texture(images.add(height.to_image()))),
        height_scale: 0.05,
        ..ParallaxOcclusionMaterial::default()
    }
}

fn setup(world: &mut World, resources: &mut Resources) {
    let material = bricks(resources);
    let Some(meshes) = resources.get_mut::<Assets<Mesh>>() else {
        return;
    };
    let floor = meshes.add(Mesh::plane_tiled(6.0, 3.0));
    let cube = meshes.add(Mesh::cube(1.0));
    world.spawn((floor, material.clone(), Transform::IDENTITY));
    world.spawn((
        cube,
        material,
        Transform::from_xyz(0.0, 0.75, 0.0),
        Spinning,
    ));
    let eye = Transform::from_xyz(1.8, 2.2, 3.2).looking_at(Vec3::new(0.0, 0.4, 0.0), Vec3::Y);
    world.spawn((
        Camera::perspective(45.0),
        FlyCamera::from_transform(&eye),
        eye,
    ));
    world.spawn((
        DirectionalLight::default(),
        Transform::IDENTITY.looking_at(Vec3::new(-1.0, -1.0, -0.6), Vec3::Y),
    ));
}

/// Keys change every parallax material; the window's title says the values.
fn controls(world: &mut World, resources: &mut Resources) {
    let Some(keys) = resources.get::<ButtonInput<KeyCode>>() else {
        return;
    };
    let step = |down: KeyCode, up: KeyCode| {
        f32::from(u8::from(keys.just_pressed(up))) - f32::from(u8::from(keys.just_pressed(down)))
    };
    let (depth, samples) = (
        step(KeyCode::Digit1, KeyCode::Digit2),
        step(KeyCode::Digit3, KeyCode::Digit4),
    );
    let next_method = keys.just_pressed(KeyCode::Space);
    let light_turn = step(KeyCode::ArrowLeft, KeyCode::ArrowRight) * 0.2;
    let light_tilt = step(KeyCode::ArrowDown, KeyCode::ArrowUp) * 0.1;
    let mut title = None;
    for material in world.query_mut::<&mut ParallaxOcclusionMaterial>() {
        material.height_scale = (material.height_scale + depth * 0.01).clamp(0.0, 0.2);
        material.max_samples =
            (material.max_samples as f32 + samples * 8.0).clamp(8.0, 128.0) as u32;
        if next_method {
            let methods = ParallaxMethod::VALUES;
            let index = methods
                .iter()
                .position(|m| *m == material.method)
                .unwrap_or(0);
            material.method = methods[(index + 1) % methods.len()];
        }
        title = Some(format!(
            "parallax: depth {:.2} (1/2), max samples {} (3/4), method {} (space), light (arrows)",
            material.height_scale,
            material.max_samples,
            material.method.name()
        ));
    }
    for transform in world
        .query_mut::<&mut Transform>()
        .with::<&DirectionalLight>()
    {
        transform.rotation = Quat::from_rotation_y(light_turn)
            * transform.rotation
            * Quat::from_rotation_x(light_tilt);
    }
    if let (Some(title), Some(window)) = (title, resources.get_mut::<WindowPlugin>()) {
        window.title = title;
    }
}

/// Turns the cube by a quarter turn a second, whatever the frame rate.
fn spin(world: &mut World, resources: &mut Resources) {
    let angle = resources.get::<Time>().map_or(0.0, Time::delta_secs) * std::f32::consts::FRAC_PI_2;
    for transform in world.query_mut::<&mut Transform>().with::<&Spinning>() {
        transform.rotation = Quat::from_rotation_y(angle) * transform.rotation;
    }
}
