//! GPU pass timing on the software driver: figures appear, are positive and finite, and the
//! timestamp work raises no validation error. (lavapipe exposes timestamps; its figures say
//! nothing about speed.)

use pom::gpu::{GpuTimer, set_gpu_timing};
use pom::preview::{PreviewView, spawn_preview};
use pom::{
    App, Assets, DynamicHeightField, GpuTimings, HeightField, HeightSource, Image,
    ParallaxOcclusionMaterial, PomPlugin, RenderPlugin, TimingMode,
};
use pom_tests::pom_scene::HeightMaterial;
use pom_tests::run_frames;

const HEIGHT_SCALE: f32 = 0.04;

fn timed_app(mode: TimingMode) -> App {
    let mut app = App::new();
    app.add_plugin(RenderPlugin::new(48, 48).with_gpu_timing(Some(mode)));
    app.add_plugin(PomPlugin);
    app.finish().unwrap();
    let field = HeightField::from_fn(32, 32, |u, v| {
        0.5 + 0.4 * (u * 12.0).sin() * (v * 9.0).cos()
    });
    let images = app.resources.get_mut::<Assets<Image>>().unwrap();
    let dynamic = DynamicHeightField::new(images, &field, HEIGHT_SCALE).unwrap();
    let material = ParallaxOcclusionMaterial {
        normal_map: Some(dynamic.normal.clone()),
        height_map: Some(HeightSource::Texture(dynamic.height.clone())),
        height_scale: HEIGHT_SCALE,
        ..ParallaxOcclusionMaterial::default()
    };
    spawn_preview(&mut app, material, &PreviewView::default()).unwrap();
    let plane = app
        .world
        .query::<(pom::hecs::Entity, &ParallaxOcclusionMaterial)>()
        .iter()
        .map(|(entity, _)| entity)
        .next()
        .unwrap();
    app.world.insert_one(plane, dynamic).unwrap();
    app
}

fn supported(app: &App) -> bool {
    let gpu = app.resources.get::<pom::GpuContext>().unwrap();
    gpu.device
        .features()
        .contains(pom::wgpu::Features::TIMESTAMP_QUERY)
}

fn assert_plausible(timings: &GpuTimings, pass: &str) {
    let ms = timings
        .pass_ms(pass)
        .unwrap_or_else(|| panic!("no reading for {pass}: {timings:?}"));
    assert!(ms.is_finite() && ms > 0.0, "{pass}: {ms} ms");
}

#[test]
fn blocking_timings_cover_the_phases_and_the_sobel_pass_from_the_first_frame() {
    let mut app = timed_app(TimingMode::Blocking);
    assert!(supported(&app), "lavapipe exposes TIMESTAMP_QUERY");
    run_frames(&mut app, 1).unwrap();
    let timings = app.resources.get::<GpuTimings>().unwrap().clone();
    for phase in ["prepass", "opaque", "post", "sobel pass"] {
        assert_plausible(&timings, phase);
    }
    let GpuTimings::Supported { frame, .. } = timings else {
        panic!("timing is on")
    };
    assert_eq!(frame, 1, "blocking mode reads the frame it just rendered");
}

#[test]
fn frames_that_build_a_max_pyramid_time_the_build_and_only_those() {
    use pom::gpu::DERIVED_TEXTURES_PASS;
    let mut app = timed_app(TimingMode::Blocking);
    pom_tests::pom_scene::set_material(&mut app, |material| {
        material.method = pom::ParallaxMethod::MaxMip;
    });
    run_frames(&mut app, 1).unwrap();
    assert_plausible(
        app.resources.get::<GpuTimings>().unwrap(),
        DERIVED_TEXTURES_PASS,
    );
    run_frames(&mut app, 1).unwrap();
    let unchanged = app.resources.get::<GpuTimings>().unwrap();
    assert_eq!(
        unchanged.pass_ms(DERIVED_TEXTURES_PASS),
        None,
        "nothing to build while the heights stay: {unchanged:?}"
    );
    let height = app
        .world
        .query::<&DynamicHeightField>()
        .iter()
        .map(|field| field.height.clone())
        .next()
        .unwrap();
    let rewritten = HeightField::from_fn(32, 32, |u, v| u * v).to_image_16();
    *app.resources
        .get_mut::<Assets<Image>>()
        .unwrap()
        .get_mut(&height)
        .unwrap() = rewritten;
    run_frames(&mut app, 1).unwrap();
    assert_plausible(
        app.resources.get::<GpuTimings>().unwrap(),
        DERIVED_TEXTURES_PASS,
    );
}

#[test]
fn non_blocking_timings_appear_after_a_few_frames_and_keep_coming() {
    let mut app = timed_app(TimingMode::NonBlocking);
    run_frames(&mut app, 8).unwrap();
    let first = app.resources.get::<GpuTimings>().unwrap().clone();
    assert_plausible(&first, "opaque");
    assert_plausible(&first, "sobel pass");
    run_frames(&mut app, 8).unwrap();
    let (
        GpuTimings::Supported { frame: before, .. },
        GpuTimings::Supported {
            frame: after,
            rejected,
            ..
        },
    ) = (first, app.resources.get::<GpuTimings>().unwrap().clone())
    else {
        panic!("timing is on")
    };
    assert!(
        after > before,
        "newer frames are read: {before} then {after}"
    );
    assert!(after <= 16, "no reading from the future: frame {after}");
    assert_eq!(rejected, 0, "every pass wrote both timestamps");
}

#[test]
fn timing_can_be_turned_off_and_says_so() {
    let mut app = App::new();
    app.add_plugin(RenderPlugin::new(32, 32).with_gpu_timing(None));
    let textures = HeightMaterial {
        field: HeightField::from_fn(16, 16, |u, _| u),
        height_scale: HEIGHT_SCALE,
    };
    app.add_plugin(PomPlugin);
    app.finish().unwrap();
    let material = textures.material(&mut app);
    spawn_preview(&mut app, material, &PreviewView::default()).unwrap();
    run_frames(&mut app, 2).unwrap();
    assert_eq!(
        app.resources.get::<GpuTimings>(),
        Some(&GpuTimings::Unsupported)
    );
    assert!(app.resources.get::<GpuTimer>().is_none());
    // And back on at run time.
    assert!(set_gpu_timing(
        &mut app.resources,
        Some(TimingMode::Blocking)
    ));
    run_frames(&mut app, 1).unwrap();
    assert_plausible(app.resources.get::<GpuTimings>().unwrap(), "opaque");
}

#[test]
fn the_texel_rate_probe_samples_its_texture_and_is_timed() {
    use pom::gpu::resolve_gpu_timings;
    use pom::texel_rate_probe::{PROBE_PASS, TexelRateProbe};
    let mut app = App::new();
    app.add_plugin(RenderPlugin::new(32, 16).with_gpu_timing(Some(TimingMode::Blocking)));
    app.finish().unwrap();
    let gpu = app.resources.get::<pom::GpuContext>().unwrap();
    let format = app
        .resources
        .get::<pom::render::RenderTarget>()
        .unwrap()
        .color
        .format();
    let probe = TexelRateProbe::new(gpu, format, 0);
    assert_eq!(probe.taps(), 1, "taps are at least one");
    let probe = TexelRateProbe::new(gpu, format, 16);
    probe.render(&mut app.resources).unwrap();
    resolve_gpu_timings(&mut app.world, &mut app.resources).unwrap();
    let gpu = app.resources.get::<pom::GpuContext>().unwrap();
    assert!(gpu.take_uncaptured_errors().is_empty());
    if supported(&app) {
        assert_plausible(app.resources.get::<GpuTimings>().unwrap(), PROBE_PASS);
    }
    // The mean of 16 samples of hashed texels: about 0.5 (188 once sRGB-encoded), not black.
    let image = pom::capture(&app).unwrap();
    let mean = image.pixels().map(|p| f64::from(p.0[0])).sum::<f64>() / (32.0 * 16.0);
    assert!((60.0..230.0).contains(&mean), "mean red {mean}");
}
