//! A game survives its scene shadows: a parallax plane under a directional light casting
//! shadows with the default settings (three cascades, each its own slot of the frame uniform)
//! keeps the process's resident memory flat, frame after frame, on both paths.
//!
//! A shader that branches on a frame value differing between those slots was compiled again at
//! every bind by Mesa 22's lavapipe, which kept every copy (2.9 MB a frame here).

use pom::glam::Vec3;
use pom::{
    App, Assets, Camera, DirectionalLight, HeightSource, Image, LightShadows, Mesh,
    ParallaxOcclusionMaterial, PomPlugin, RenderPath, RenderPlugin, Transform, patterns,
};
use pom_tests::memory::{ResidentGrowth, live_objects, resident_kib};
use pom_tests::{run_frames, set_path};

/// Frames before the first reading: pipelines compiled, shadow maps made.
const WARM_UP: usize = 100;
/// Frames between the two readings.
const MEASURED: usize = 300;
/// How much resident memory may grow between the readings (allocator noise).
const TOLERANCE: f64 = 0.05;

/// A small parallax plane seen from above, lit by a sun with default scene shadows.
fn shadowed_parallax_plane(path: RenderPath) -> App {
    let mut app = App::new();
    app.add_plugin(RenderPlugin::new(64, 40))
        .add_plugin(PomPlugin);
    let plane = app
        .resources
        .get_or_default::<Assets<Mesh>>()
        .add(Mesh::plane(2.0));
    let bricks = patterns::bricks(64, 4.0, 8.0);
    let images = app.resources.get_or_default::<Assets<Image>>();
    let material = ParallaxOcclusionMaterial {
        normal_map: Some(images.add(bricks.normal_map(0.05))),
        height_map: Some(HeightSource::Texture(images.add(bricks.to_image()))),
        ..Default::default()
    };
    app.world.spawn((plane, material, Transform::IDENTITY));
    let sun = Transform::IDENTITY.looking_at(Vec3::new(-0.6, -1.0, -0.4), Vec3::Y);
    app.world
        .spawn((DirectionalLight::default(), sun, LightShadows::default()));
    let eye = Transform::from_xyz(0.0, 1.2, 1.6).looking_at(Vec3::ZERO, Vec3::Y);
    app.world.spawn((Camera::perspective(45.0), eye));
    app.finish().unwrap();
    set_path(&mut app, path);
    app
}

#[test]
fn scene_shadow_maps_keep_memory_flat_on_both_paths() {
    for path in [RenderPath::Forward, RenderPath::Deferred] {
        let mut app = shadowed_parallax_plane(path);
        run_frames(&mut app, WARM_UP).unwrap();
        let live_early = live_objects(&app);
        let early_kib = resident_kib().expect("/proc/self/status has VmRSS");
        run_frames(&mut app, MEASURED).unwrap();
        let growth = ResidentGrowth {
            early_kib,
            late_kib: resident_kib().unwrap(),
        };
        eprintln!(
            "{path:?}: resident {} KiB after frame {WARM_UP}, {} KiB after frame {}: {:.0} bytes a frame",
            growth.early_kib,
            growth.late_kib,
            WARM_UP + MEASURED,
            growth.bytes_per_frame(MEASURED as u64)
        );
        assert_eq!(
            live_objects(&app),
            live_early,
            "{path:?}: wgpu's live objects changed"
        );
        assert!(
            growth.within(TOLERANCE),
            "{path:?}: resident memory grew from {} to {} KiB over {MEASURED} frames",
            growth.early_kib,
            growth.late_kib
        );
    }
}
