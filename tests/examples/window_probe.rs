//! A windowed program for the window runner's tests (tests/tests/window_runner.rs): the
//! README's brick plane, still (nothing moves, so any two frames look the same), plus what a
//! test asks for on the command line. It reports on standard error, in lines starting `probe:`.
//!
//! - `--frames N`: exits with status 0 after N updates (default 30);
//! - `--lose-device-at N`: destroys the GPU device in update N, as a driver reset would;
//! - `--resizes N`: asks for a new window size (through the `WindowPlugin` resource) in each of
//!   N updates, then for the first size again, and reports the GPU's live objects before and
//!   after (wgpu's counters);
//! - `--hold-until FILE`: after the resizes, keeps running until FILE exists (a test minimises
//!   and restores the window meanwhile);
//! - `--panic-from N`: a system panics in every update from N on;
//! - `--exit-on-error`: sets `WindowPlugin::exit_on_error`;
//! - `--memory-at A,B`: reports the process's resident memory and the GPU's live objects after
//!   updates A and B (a test that a long run stays flat);
//! - `--size WxH`: the window's size (default 320x240);
//! - `--path forward|deferred`: the render path (default: the renderer's own choice);
//! - always: `Time`'s smallest and largest delta and whether its elapsed time grew every frame.

use std::path::PathBuf;
use std::time::Duration;

use pom::hecs::World;
use pom::render::Renderer;
use pom::window::{AppExit, WindowEvents, WindowPlugin};
use pom::{glam::Vec3, *};

/// The window's size before and after the resizes, unless `--size` says otherwise.
const FIRST_SIZE: (u32, u32) = (320, 240);
/// Updates drawn before the first count of live GPU objects (everything made and cached).
const WARM_UP: u64 = 5;
/// Updates at the first size again before the second count (the last resize has landed).
const SETTLE: u64 = 20;

/// What the command line asks for.
#[derive(Debug, Default)]
struct Plan {
    frames: u64,
    lose_device_at: Option<u64>,
    resizes: u64,
    hold_until: Option<PathBuf>,
    panic_from: Option<u64>,
    exit_on_error: bool,
    memory_at: Vec<u64>,
    path: Option<RenderPath>,
    size: (u32, u32),
}

/// What the probe saw, in updates.
#[derive(Debug, Default)]
struct Seen {
    updates: u64,
    /// `Time` at the previous update.
    last_elapsed: Option<Duration>,
    smallest_delta: Option<Duration>,
    largest_delta: Duration,
    elapsed_always_grew: bool,
    /// Live GPU objects after the warm-up.
    before_resizes: Option<String>,
    /// When the resizes and the hold ended.
    settle_from: Option<u64>,
    /// Updates that saw the window resized.
    resized_updates: u64,
}

/// Stands for the game's own state: it must survive a device loss unchanged.
struct GameState(u32);

fn parse(args: &[String]) -> Result<Plan, String> {
    let mut plan = Plan {
        frames: 30,
        size: FIRST_SIZE,
        ..Plan::default()
    };
    let mut args = args.iter();
    while let Some(flag) = args.next() {
        let mut value = || args.next().ok_or(format!("{flag} needs a value"));
        let number = |text: &String| {
            text.parse::<u64>()
                .map_err(|_| format!("{flag} {text}: not a whole number"))
        };
        match flag.as_str() {
            "--frames" => plan.frames = number(value()?)?,
            "--lose-device-at" => plan.lose_device_at = Some(number(value()?)?),
            "--resizes" => plan.resizes = number(value()?)?,
            "--hold-until" => plan.hold_until = Some(PathBuf::from(value()?)),
            "--panic-from" => plan.panic_from = Some(number(value()?)?),
            "--exit-on-error" => plan.exit_on_error = true,
            "--memory-at" => {
                plan.memory_at = value()?
                    .split(',')
                    .map(|update| number(&update.to_owned()))
                    .collect::<Result<_, _>>()?;
            }
            "--size" => {
                let text = value()?;
                let (width, height) = text.split_once('x').ok_or(format!("--size {text}: WxH"))?;
                plan.size = (
                    number(&width.to_owned())? as u32,
                    number(&height.to_owned())? as u32,
                );
            }
            "--path" => {
                plan.path = Some(match value()?.as_str() {
                    "forward" => RenderPath::Forward,
                    "deferred" => RenderPath::Deferred,
                    other => return Err(format!("--path {other}: forward or deferred")),
                });
            }
            other => return Err(format!("unknown argument {other}")),
        }
    }
    Ok(plan)
}

fn main() -> AppExit {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let plan = match parse(&args) {
        Ok(plan) => plan,
        Err(error) => {
            eprintln!("error: {error}");
            return AppExit::error();
        }
    };
    let mut app = App::new();
    app.add_plugin(DefaultPlugins::windowed(WindowPlugin {
        title: "window probe".to_owned(),
        width: plan.size.0,
        height: plan.size.1,
        exit_on_error: plan.exit_on_error,
        ..WindowPlugin::default()
    }));
    let bricks = patterns::bricks(128, 4.0, 8.0);
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
    app.insert_resource(GameState(42))
        .insert_resource(plan)
        .insert_resource(Seen {
            elapsed_always_grew: true,
            ..Seen::default()
        })
        .add_system(Stage::Update, probe);
    app.run()
}

/// The live GPU objects that could leak, as one line. The GPU is waited for first: objects
/// dropped while a submission still used them are freed only once it is done, so a count taken
/// with frames in flight (a loaded machine) would hold some of them.
fn live_objects(resources: &Resources, wait: bool) -> String {
    let Some(gpu) = resources.get::<GpuContext>() else {
        return "no GPU".to_owned();
    };
    if wait {
        let _ = gpu.device.poll(wgpu::PollType::wait_indefinitely());
    }
    let hal = gpu.device.get_internal_counters().hal;
    format!(
        "buffers={} texture_memory={} texture_views={} bind_groups={}",
        hal.buffers.read(),
        hal.texture_memory.read(),
        hal.texture_views.read(),
        hal.bind_groups.read()
    )
}

fn probe(world: &mut World, resources: &mut Resources) {
    let (Some(time), Some(plan)) = (resources.get::<Time>(), resources.get::<Plan>()) else {
        return;
    };
    let (delta, elapsed) = (time.delta(), time.elapsed());
    let (frames, lose_device_at, resizes) = (plan.frames, plan.lose_device_at, plan.resizes);
    let (memory_at, path, first_size) = (plan.memory_at.clone(), plan.path, plan.size);
    let panic_from = plan.panic_from;
    let held = plan.hold_until.as_ref().is_some_and(|file| !file.exists());
    if let (Some(path), Some(renderer)) = (path, resources.get_mut::<Renderer>()) {
        renderer.set_path(path);
    }
    // Only the updates whose counts are reported wait for the GPU (the others keep its pace).
    let counted = resizes > 0
        && resources
            .get::<Seen>()
            .is_some_and(|seen| seen.updates + 1 == WARM_UP || seen.settle_from.is_some());
    let live = live_objects(resources, counted);
    let resized = resources
        .get::<WindowEvents>()
        .is_some_and(|events| events.resized.is_some());
    let Some(seen) = resources.get_mut::<Seen>() else {
        return;
    };
    seen.updates += 1;
    seen.resized_updates += u64::from(resized);
    let update = seen.updates;
    if update > 1 {
        seen.smallest_delta = Some(seen.smallest_delta.map_or(delta, |d| d.min(delta)));
        seen.largest_delta = seen.largest_delta.max(delta);
    }
    if seen.last_elapsed.is_some_and(|last| elapsed <= last) {
        seen.elapsed_always_grew = false;
    }
    seen.last_elapsed = Some(elapsed);
    if memory_at.contains(&update) {
        let resident = pom_tests::memory::resident_kib().unwrap_or(0);
        let live = live_objects(resources, true);
        eprintln!("probe: memory at update {update}: resident_kib={resident} {live}");
    }
    let Some(seen) = resources.get_mut::<Seen>() else {
        return;
    };
    if update == WARM_UP && resizes > 0 {
        seen.before_resizes = Some(live.clone());
    }
    // The size asked for this update.
    let resizing = resizes > 0 && update > WARM_UP && update <= WARM_UP + resizes;
    let size = if resizing {
        let step = (update - WARM_UP) as u32;
        (200 + (step * 37) % 400, 150 + (step * 53) % 300)
    } else {
        first_size
    };
    if resizes > 0 && update > WARM_UP + resizes && !held && seen.settle_from.is_none() {
        seen.settle_from = Some(update);
    }
    let done = match (resizes, seen.settle_from) {
        (0, _) => update >= frames,
        (_, Some(from)) => update >= from + SETTLE,
        (_, None) => false,
    };
    if done {
        let smallest = seen.smallest_delta.unwrap_or_default();
        eprintln!(
            "probe: time smallest_delta_s={:.6} largest_delta_s={:.6} elapsed_s={:.6} elapsed_always_grew={} updates={update}",
            smallest.as_secs_f64(),
            seen.largest_delta.as_secs_f64(),
            elapsed.as_secs_f64(),
            seen.elapsed_always_grew
        );
        if let Some(before) = &seen.before_resizes {
            eprintln!("probe: live before {before}");
            eprintln!("probe: live after {live}");
            eprintln!("probe: resized updates={}", seen.resized_updates);
        }
        let state = resources.get::<GameState>().map_or(0, |state| state.0);
        eprintln!("probe: game state {state}, {} entities", world.len());
        resources.insert(AppExit::Success);
    }
    if let Some(window) = resources.get_mut::<WindowPlugin>() {
        (window.width, window.height) = size;
    }
    // The same message every time: the runner reports a repeated failure once.
    if let Some(from) = panic_from
        && update >= from
    {
        panic!("the probe panics from update {from} on");
    }
    if lose_device_at == Some(update)
        && let Some(gpu) = resources.get::<GpuContext>()
    {
        eprintln!("probe: destroying the device in update {update}");
        gpu.device.destroy();
        // The device-lost callback runs when the device is next polled.
        let _ = gpu.device.poll(wgpu::PollType::Poll);
    }
}
