//! Many GPU apps one after another in one process (a test harness, a scene editor, a renderer
//! recreated after a lost device): each app takes its adapter, device and queue with it when
//! dropped, and the process does not grow with every app. With a `wgpu::Instance` per app the
//! Vulkan loader reloaded the driver with each one: lavapipe's resident memory grew by a fifth
//! over these 200 apps, and NVIDIA's driver stopped loading at the 30th ("cannot allocate memory
//! in static TLS block").
//!
//! The only test of this binary: wgpu's report counts what every app of the process holds on
//! the instance they share.

use std::time::Instant;

use pom::preview::{PreviewView, spawn_preview};
use pom::render::Renderer;
use pom::wgpu::wgc::global::GlobalReport;
use pom::{App, GpuContext, PomPlugin, RenderPath, RenderPlugin, patterns};
use pom_tests::pom_scene::HeightMaterial;
use pom_tests::{HarnessError, render_and_capture};

/// Apps made, rendered with and dropped on each path.
const APPS_PER_PATH: usize = 100;
/// Side of each app's target in pixels.
const SIZE: u32 = 32;
/// Most the resident memory may grow from after the first apps to after the last (a fraction).
const MOST_GROWTH: f64 = 0.10;

/// An app on `path` with one parallax plane, one frame rendered (inside error scopes); returns
/// the instance its GPU context came from once the app is dropped.
fn render_one_frame(
    path: RenderPath,
    textures: &HeightMaterial,
) -> Result<pom::wgpu::Instance, HarnessError> {
    let mut app = App::new();
    app.add_plugin(RenderPlugin::new(SIZE, SIZE).with_path(path))
        .add_plugin(PomPlugin);
    app.finish()?;
    let material = textures.material(&mut app);
    spawn_preview(&mut app, material, &PreviewView::default())?;
    render_and_capture(&mut app)?;
    let ran_deferred = app.resources.get::<Renderer>().unwrap().runs_deferred();
    assert_eq!(
        ran_deferred,
        path == RenderPath::Deferred,
        "{path}: the path that ran"
    );
    let instance = app.resources.get::<GpuContext>().unwrap().instance.clone();
    let live = live_gpu_objects(&instance);
    assert!(
        live.iter()
            .any(|(kind, count)| *kind == "devices" && *count > 0),
        "{path}: wgpu's report does not count the live app's device: {live:?}"
    );
    Ok(instance)
}

/// What wgpu's report of `instance` counts as still held by the user, by kind (kinds of which
/// none is held left out).
fn live_gpu_objects(instance: &pom::wgpu::Instance) -> Vec<(&'static str, usize)> {
    let GlobalReport { surfaces, hub } = instance
        .generate_report()
        .expect("a wgpu-core instance has a report");
    [
        ("surfaces", &surfaces),
        ("adapters", &hub.adapters),
        ("devices", &hub.devices),
        ("queues", &hub.queues),
        ("buffers", &hub.buffers),
        ("textures", &hub.textures),
        ("texture views", &hub.texture_views),
        ("samplers", &hub.samplers),
        ("bind groups", &hub.bind_groups),
        ("shader modules", &hub.shader_modules),
        ("render pipelines", &hub.render_pipelines),
        ("compute pipelines", &hub.compute_pipelines),
        ("query sets", &hub.query_sets),
    ]
    .into_iter()
    .map(|(kind, registry)| (kind, registry.num_kept_from_user))
    .filter(|(_, count)| *count > 0)
    .collect()
}

/// The process's resident memory in bytes (Linux: /proc/self/statm, in pages of 4 KiB).
fn resident_bytes() -> u64 {
    let statm = std::fs::read_to_string("/proc/self/statm").expect("Linux's /proc/self/statm");
    let pages: u64 = statm
        .split_whitespace()
        .nth(1)
        .and_then(|field| field.parse().ok())
        .expect("statm's second field counts resident pages");
    pages * 4096
}

#[test]
fn a_hundred_apps_per_path_leave_no_gpu_object_and_no_memory_behind() {
    let textures = HeightMaterial {
        field: patterns::cobblestones(SIZE, 2),
        height_scale: 0.05,
    };
    let started = Instant::now();
    let mut after_first = None;
    // The paths alternate, so the first round warms both up (pipelines, driver caches) before
    // the memory it is compared with is read.
    for round in 1..=APPS_PER_PATH {
        for path in [RenderPath::Forward, RenderPath::Deferred] {
            let instance = render_one_frame(path, &textures)
                .unwrap_or_else(|error| panic!("app {round} on {path}: {error}"));
            let live = live_gpu_objects(&instance);
            assert!(
                live.is_empty(),
                "app {round} on {path}: still held after it was dropped: {live:?}"
            );
        }
        after_first.get_or_insert_with(resident_bytes);
    }
    let (first, last) = (after_first.unwrap_or_default(), resident_bytes());
    let growth = last as f64 / first as f64 - 1.0;
    let mib = |bytes: u64| bytes as f64 / (1024.0 * 1024.0);
    eprintln!(
        "{APPS_PER_PATH} apps per path in {:.1} s; resident {:.1} MiB after the first round, \
         {:.1} MiB after the last ({:+.1} %)",
        started.elapsed().as_secs_f64(),
        mib(first),
        mib(last),
        growth * 100.0
    );
    assert!(
        growth <= MOST_GROWTH,
        "resident memory grew {:.1} % (from {:.1} to {:.1} MiB) over {APPS_PER_PATH} apps per \
         path; at most {:.0} % allowed",
        growth * 100.0,
        mib(first),
        mib(last),
        MOST_GROWTH * 100.0
    );
}
