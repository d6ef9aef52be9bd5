//! A game survives: thousands of headless frames of the street corner under TAA, with its sun's
//! scene shadows, a spinning parallax cube (object motion) and both render paths, leave the
//! process's resident memory and wgpu's live objects where they were after the warm-up.
//!
//! Resident memory is what the operating system sees: a driver that compiles or keeps something
//! each frame grows it while wgpu's counters stay flat. The two paths run one after the other
//! in one test, so neither's figures carry the other's allocations.

use std::path::Path;

use pom::glam::{Quat, Vec3};
use pom::hecs::World;
use pom::{
    AntiAliasing, App, AppError, Assets, Camera, HeightSource, Image, Mesh,
    ParallaxOcclusionMaterial, PomPlugin, RenderPath, RenderPlugin, Resources, Stage, Transform,
    load_gltf, patterns,
};
use pom_tests::memory::{ResidentGrowth, live_objects, resident_kib};
use pom_tests::{run_frames, set_path};

/// Frames before the first reading: pipelines compiled, histories and shadow maps made, the
/// allocator's pools at their working size.
const WARM_UP: usize = 500;
/// Frames between the two readings.
const MEASURED: usize = 3_500;
/// Frames after the second reading (the run is 5,000 frames long).
const TAIL: usize = 1_000;
/// How much resident memory may grow between the readings (allocator noise).
const TOLERANCE: f64 = 0.05;

/// Marks the cube the spin system turns.
struct Spinning;

fn spin(world: &mut World, _: &mut Resources) -> Result<(), AppError> {
    for transform in world.query_mut::<&mut Transform>().with::<&Spinning>() {
        transform.rotation *= Quat::from_rotation_y(0.02);
    }
    Ok(())
}

/// The street corner from its own camera under TAA, its sun casting scene shadows, and a
/// parallax cube turning in front of it.
fn street_corner_under_taa(path: RenderPath) -> App {
    let scene_file = Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets/street_corner.glb");
    let mut app = App::new();
    app.add_plugin(RenderPlugin::new(64, 40))
        .add_plugin(PomPlugin);
    app.add_system(Stage::Update, spin);
    let scene = load_gltf(&mut app, &scene_file).unwrap();
    for &light in &scene.lights {
        let shadows = pom::LightShadows {
            map_size: 128,
            ..pom::LightShadows::default()
        };
        app.world.insert_one(light, shadows).unwrap();
    }
    for &camera in &scene.cameras {
        app.world.insert_one(camera, AntiAliasing::Taa).unwrap();
    }
    let cube = app
        .resources
        .get_mut::<Assets<Mesh>>()
        .unwrap()
        .add(Mesh::cube(0.5));
    let bricks = patterns::bricks(64, 4.0, 8.0);
    let images = app.resources.get_or_default::<Assets<Image>>();
    let material = ParallaxOcclusionMaterial {
        normal_map: Some(images.add(bricks.normal_map(0.05))),
        height_map: Some(HeightSource::Texture(images.add(bricks.to_image()))),
        ..Default::default()
    };
    app.world.spawn((
        cube,
        material,
        Transform::from_translation(Vec3::new(0.0, 0.5, 0.0)),
        Spinning,
    ));
    app.finish().unwrap();
    set_path(&mut app, path);
    app
}

fn resident_growth(path: RenderPath) -> ResidentGrowth {
    let mut app = street_corner_under_taa(path);
    assert_eq!(app.world.query::<&Camera>().iter().count(), 1);
    run_frames(&mut app, WARM_UP).unwrap();
    let live_early = live_objects(&app);
    let early_kib = resident_kib().expect("/proc/self/status has VmRSS");
    run_frames(&mut app, MEASURED).unwrap();
    let late_kib = resident_kib().unwrap();
    let live_late = live_objects(&app);
    run_frames(&mut app, TAIL).unwrap();
    assert_eq!(
        live_late, live_early,
        "{path:?}: wgpu's live objects changed"
    );
    ResidentGrowth {
        early_kib,
        late_kib,
    }
}

#[test]
fn five_thousand_headless_frames_under_taa_keep_memory_flat_on_both_paths() {
    let mut report = Vec::new();
    for path in [RenderPath::Forward, RenderPath::Deferred] {
        let growth = resident_growth(path);
        eprintln!(
            "{path:?}: resident {} KiB after frame {WARM_UP}, {} KiB after frame {}: {:.0} bytes a frame",
            growth.early_kib,
            growth.late_kib,
            WARM_UP + MEASURED,
            growth.bytes_per_frame(MEASURED as u64)
        );
        report.push((path, growth));
    }
    for (path, growth) in report {
        assert!(
            growth.within(TOLERANCE),
            "{path:?}: resident memory grew from {} to {} KiB over {MEASURED} frames",
            growth.early_kib,
            growth.late_kib
        );
    }
}
