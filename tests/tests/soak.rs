//! Soak: loading and dropping a glTF scene with parallax materials 100 times, and editing
//! every parameter 1,000 times, leaves the GPU's live buffers, texture memory, texture views and
//! bind groups where they started (wgpu's internal counters, `counters` feature).

use std::path::Path;

use pom::glam::Vec3;
use pom::material::{ParamKind, ParamValue};
use pom::{App, Camera, GpuContext, ParallaxOcclusionMaterial, Transform, load_gltf};
use pom_tests::headless_app;
use pom_tests::parameters::every_parameter_changed;

/// The live GPU objects the app could leak. Textures are counted by their memory: wgpu-hal 30's
/// texture count is not raised on Vulkan when a texture is made (it reads 0 with textures alive
/// and goes negative as they are dropped), its texture memory is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct LiveObjects {
    buffers: isize,
    texture_memory: isize,
    texture_views: isize,
    bind_groups: isize,
}

fn live_objects(app: &App) -> LiveObjects {
    let gpu = app.resources.get::<GpuContext>().unwrap();
    // Destruction of dropped objects completes on the next poll.
    gpu.device
        .poll(pom::wgpu::PollType::wait_indefinitely())
        .unwrap();
    let counters = gpu.device.get_internal_counters().hal;
    LiveObjects {
        buffers: counters.buffers.read(),
        texture_memory: counters.texture_memory.read(),
        texture_views: counters.texture_views.read(),
        bind_groups: counters.bind_groups.read(),
    }
}

fn frame(app: &mut App) {
    app.update().unwrap();
}

fn app_with_camera() -> App {
    let mut app = headless_app(32, 32).unwrap();
    app.add_plugin(pom::PomPlugin);
    app.world.spawn((
        Camera::perspective(50.0),
        Transform::from_xyz(4.0, 5.0, 7.0).looking_at(Vec3::ZERO, Vec3::Y),
    ));
    app
}

fn load_and_drop(app: &mut App, path: &Path) {
    let scene = load_gltf(app, path).unwrap();
    frame(app);
    for entity in scene.entities {
        if app.world.contains(entity) {
            pom::despawn_recursive(&mut app.world, entity);
        }
    }
    // The frame that frees the dropped assets, on the CPU and then on the GPU.
    frame(app);
}

#[test]
fn loading_and_dropping_a_scene_leaks_no_gpu_objects() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets/street_corner.glb");
    let mut app = app_with_camera();
    // The first load compiles pipelines and sizes the per-draw buffers: what stays is not a leak.
    load_and_drop(&mut app, &path);
    let before = live_objects(&app);
    assert!(
        before.buffers > 0 && before.texture_memory > 0,
        "wgpu's counters are on: {before:?}"
    );
    for _ in 0..100 {
        load_and_drop(&mut app, &path);
    }
    assert_eq!(live_objects(&app), before);
}

/// The `step`th value to set `param` to: the changed value and the default by turns, and the
/// next choice for choices, so every value of every parameter is visited.
fn value_at(step: usize, changed: ParamValue, default: ParamValue, kind: &ParamKind) -> ParamValue {
    match (kind, default) {
        (ParamKind::Choice(choices), ParamValue::Choice(name)) => {
            let start = choices.iter().position(|c| c.name == name).unwrap_or(0);
            ParamValue::Choice(choices[(start + step) % choices.len()].name)
        }
        _ if step % 2 == 1 => changed,
        _ => default,
    }
}

#[test]
fn editing_every_parameter_a_thousand_times_leaks_no_gpu_objects() {
    let mut app = app_with_camera();
    let field = pom::patterns::bricks(32, 4.0, 8.0);
    let images = app.resources.get_mut::<pom::Assets<pom::Image>>().unwrap();
    let material = ParallaxOcclusionMaterial {
        normal_map: Some(images.add(field.normal_map(0.05))),
        height_map: Some(pom::HeightSource::Texture(images.add(field.to_image()))),
        ..ParallaxOcclusionMaterial::default()
    };
    let plane = app
        .resources
        .get_mut::<pom::Assets<pom::Mesh>>()
        .unwrap()
        .add(pom::Mesh::plane(4.0));
    let entity = app.world.spawn((plane, material, Transform::IDENTITY));
    let changed = every_parameter_changed();
    let default = ParallaxOcclusionMaterial::default();
    let parameters = ParallaxOcclusionMaterial::PARAMETERS;
    // One pass over every value first: pipelines of new variants are compiled once and kept.
    let edit = |app: &mut App, step: usize| {
        let param = &parameters[step % parameters.len()];
        let round = step / parameters.len();
        let value = value_at(
            round,
            (param.get)(&changed),
            (param.get)(&default),
            &param.spec.kind,
        );
        let mut material = app
            .world
            .get::<&mut ParallaxOcclusionMaterial>(entity)
            .unwrap();
        (param.set)(&mut material, value).unwrap();
        drop(material);
        frame(app);
    };
    for step in 0..parameters.len() * 8 {
        edit(&mut app, step);
    }
    let before = live_objects(&app);
    // At least a thousand edits, ending where the measured ones began (every parameter back at
    // the value it had then), whatever the count of parameters.
    for step in 0..1000_usize.next_multiple_of(2 * parameters.len()) {
        edit(&mut app, step);
    }
    assert_eq!(live_objects(&app), before);
}
