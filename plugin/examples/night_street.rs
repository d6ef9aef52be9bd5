//! The street corner at night: the shipped night scene (street lamps, a lamp post, the sign's
//! lamp and a string of bulbs) with 256 lanterns drifting over the cobblestones, each a point
//! light of its own, under the night sky; an orbit camera (left drag orbits, right drag pans,
//! the wheel zooms). Every lantern lights the relief it floats over; the brightest four at
//! each pixel also cast the relief's own soft shadows.
//!
//! `cargo run --release -p parallax-occlusion --example night_street --features window`

use pom::prelude::*;

/// Lanterns over the street.
const LANTERNS: usize = 256;

/// A lantern circling the point it was put over, `radius` metres out, at its own pace.
struct Lantern {
    centre: Vec3,
    radius: f32,
    speed: f32,
    phase: f32,
}

fn main() -> AppExit {
    let mut app = App::new();
    app.add_plugin(DefaultPlugins::windowed(WindowPlugin {
        title: format!("night_street: {LANTERNS} lanterns and the street's own lamps"),
        ..WindowPlugin::default()
    }))
    .add_plugin(OrbitCameraPlugin)
    .add_system(Stage::Update, drift);
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../assets/street_corner_night.glb"
    );
    let scene = match load_gltf(&mut app, path) {
        Ok(scene) => scene,
        Err(error) => {
            eprintln!("error: {error}");
            return AppExit::error();
        }
    };
    if let Some(&camera) = scene.cameras.first() {
        let start = app
            .world
            .get::<&Transform>(camera)
            .map(|t| *t)
            .unwrap_or_default();
        let _ = app
            .world
            .insert_one(camera, OrbitCamera::from_transform(&start, 5.0));
    }
    spawn_lanterns(&mut app.world);
    app.run()
}

/// The lanterns: a 16 × 16 grid over the 6 m floor, shuffled a little, in warm colours.
fn spawn_lanterns(world: &mut World) {
    let side = (LANTERNS as f32).sqrt() as usize;
    for index in 0..LANTERNS {
        // A cheap hash for each lantern's own colour, pace and height.
        let hash = |salt: u32| {
            let mut x = (index as u32).wrapping_mul(0x9E37_79B9) ^ salt.wrapping_mul(0x85EB_CA6B);
            x ^= x >> 15;
            x = x.wrapping_mul(0x2C1B_3C6D);
            (x >> 8) as f32 / (1 << 24) as f32
        };
        let (i, j) = ((index % side) as f32, (index / side) as f32);
        let spacing = 5.6 / side as f32;
        let centre = Vec3::new(
            -2.8 + spacing * (i + 0.5),
            0.25 + 0.5 * hash(1),
            -2.8 + spacing * (j + 0.5),
        );
        let light = PointLight {
            color: Color::linear_rgb(1.0, 0.35 + 0.4 * hash(2), 0.1 + 0.2 * hash(3)),
            intensity: 6.0,
            range: 1.0,
        };
        let lantern = Lantern {
            centre,
            radius: 0.1 + 0.15 * hash(4),
            speed: 0.3 + 0.7 * hash(5),
            phase: std::f32::consts::TAU * hash(6),
        };
        world.spawn((light, Transform::from_translation(centre), lantern));
    }
}

/// Moves each lantern along its circle.
fn drift(world: &mut World, resources: &mut Resources) {
    let seconds = resources.get::<Time>().map_or(0.0, Time::elapsed_secs) as f32;
    for (transform, lantern) in world.query_mut::<(&mut Transform, &Lantern)>() {
        let angle = lantern.phase + seconds * lantern.speed;
        transform.translation =
            lantern.centre + Vec3::new(angle.cos(), 0.0, angle.sin()) * lantern.radius;
    }
}
