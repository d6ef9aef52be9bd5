//! The window runner under Xvfb on the software driver, driven by the `window_probe` example of
//! this crate: a lost GPU device is replaced and the next frame looks as before, `Time` runs
//! in real time, a thousand resizes and a hundred unmap/map cycles leak no GPU memory, and a
//! close request (what a window manager's close button sends) ends the app with status 0.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::time::Duration;

use pom_tests::xvfb::Xvfb;

#[path = "support/close_request.rs"]
mod close_request;
use close_request::request_close;

/// How long the probe may take (a debug build on a software GPU; the soak draws 1,000 frames).
const PROBE_TIMEOUT: Duration = Duration::from_secs(600);

fn probe() -> PathBuf {
    let deps = std::env::current_exe().expect("the test binary's path");
    let profile = deps
        .parent()
        .and_then(Path::parent)
        .expect("test binaries live in target/<profile>/deps");
    let path = profile.join("examples").join("window_probe");
    assert!(
        path.is_file(),
        "{} is missing: `cargo test --workspace` builds it (a filtered run: `cargo build -p pom-tests --examples`)",
        path.display()
    );
    path
}

fn scratch(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("window_runner");
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join(name);
    let _ = std::fs::remove_file(&path);
    path
}

/// Runs the probe with `args` on a fresh Xvfb, asserting status 0; returns its report lines.
fn run_probe(args: &[&str], screenshot: Option<&Path>) -> String {
    let xvfb = Xvfb::start();
    let mut command = Command::new(probe());
    command.args(args);
    if let Some(path) = screenshot {
        command.env("POM_SCREENSHOT", path);
    }
    let output = xvfb.run(&mut command, PROBE_TIMEOUT);
    report(&output)
}

fn report(output: &Output) -> String {
    let stderr = String::from_utf8_lossy(&output.stderr).into_owned();
    assert!(
        output.status.success(),
        "the probe failed ({}):\n{stderr}",
        output.status
    );
    stderr
}

/// The value of `key=` in the report's line starting `probe: {line}`.
fn value<'a>(report: &'a str, line: &str, key: &str) -> &'a str {
    let found = report
        .lines()
        .find_map(|text| text.strip_prefix(&format!("probe: {line}")))
        .unwrap_or_else(|| panic!("no `probe: {line}` line in:\n{report}"));
    found
        .split_whitespace()
        .find_map(|pair| pair.strip_prefix(&format!("{key}=")))
        .unwrap_or_else(|| panic!("no {key}= in `{found}`"))
}

#[test]
fn a_lost_device_is_replaced_and_the_next_frame_looks_as_before() {
    let before = scratch("before_loss.png");
    // The window runs TAA: 16 frames are one whole cycle of its jitter, a settled history.
    run_probe(&["--frames", "16"], Some(&before));
    let after = scratch("after_loss.png");
    // Update 6 loses the device; update 7 is the first frame on the new one (a new target, so
    // a new history), update 22 the last: 16 frames again.
    let report = run_probe(&["--frames", "22", "--lose-device-at", "6"], Some(&after));
    assert!(
        report.contains("the GPU device was lost") && report.contains("goes on on a new GPU"),
        "the runner said nothing of the loss:\n{report}"
    );
    assert!(
        report.contains("probe: game state 42, 3 entities"),
        "the game's world or resources changed:\n{report}"
    );
    assert!(
        !report.contains("error:"),
        "the run reported errors:\n{report}"
    );
    let (before, after) = (
        image::open(&before).unwrap().to_rgba8(),
        image::open(&after).unwrap().to_rgba8(),
    );
    let colours = pom_tests::xvfb::distinct_colours(&before, 0..320, 0..240);
    assert!(
        colours > 50,
        "only {colours} colours before the loss: no scene"
    );
    let flip = pom::flip_compare(&before, &after, 0.99).expect("both frames are 320x240");
    assert!(
        flip.mean <= 0.01,
        "the frame after the loss differs: FLIP mean {}",
        flip.mean
    );
}

#[test]
fn time_runs_in_real_time_in_a_window() {
    let report = run_probe(&["--frames", "30"], None);
    let smallest: f64 = value(&report, "time", "smallest_delta_s").parse().unwrap();
    let elapsed: f64 = value(&report, "time", "elapsed_s").parse().unwrap();
    assert!(smallest > 0.0, "a frame had no delta:\n{report}");
    assert!(
        elapsed > smallest * 28.0,
        "elapsed did not add up:\n{report}"
    );
    assert_eq!(value(&report, "time", "elapsed_always_grew"), "true");
}

#[test]
fn a_thousand_resizes_and_a_hundred_unmaps_leak_no_gpu_memory() {
    let xvfb = Xvfb::start();
    let hold = scratch("resizes_done");
    let hold_arg = hold.to_str().unwrap().to_owned();
    let child =
        xvfb.spawn(Command::new(probe()).args(["--resizes", "1000", "--hold-until", &hold_arg]));
    let window = xvfb.xdotool(&["search", "--sync", "--name", "window probe"]);
    // Without a window manager, minimising is unmapping: the window has no place on screen.
    for _ in 0..100 {
        xvfb.xdotool(&["windowunmap", "--sync", &window]);
        xvfb.xdotool(&["windowmap", "--sync", &window]);
    }
    std::fs::write(&hold, b"").unwrap();
    let output = pom_tests::xvfb::wait_for(child, PROBE_TIMEOUT);
    let report = report(&output);
    let counts = |line: &str| -> Vec<(String, u64)> {
        let found = report
            .lines()
            .find_map(|text| text.strip_prefix(&format!("probe: live {line} ")))
            .unwrap_or_else(|| panic!("no count {line}:\n{report}"));
        found
            .split_whitespace()
            .map(|pair| {
                let (name, count) = pair.split_once('=').expect("name=count");
                (name.to_owned(), count.parse().expect("a count"))
            })
            .collect()
    };
    let (before, after) = (counts("before"), counts("after"));
    for ((name, before), (_, after)) in before.iter().zip(&after) {
        // Texture memory is the same (the targets are at the first size again); a count may
        // fall (a view cached at the start let go) but never grow.
        if name == "texture_memory" {
            assert_eq!(before, after, "{name} changed:\n{report}");
        } else {
            assert!(
                after <= before,
                "{name} grew from {before} to {after}:\n{report}"
            );
        }
    }
    let resized: u64 = value(&report, "resized", "updates").parse().unwrap();
    // Resizes that land in one update count once.
    assert!(
        resized >= 500,
        "only {resized} updates saw a resize:\n{report}"
    );
    assert!(!report.contains("error:"), "{report}");
}

#[test]
fn a_panicking_system_is_reported_once_and_the_window_stays_unless_asked_to_exit() {
    let report = run_probe(&["--frames", "12", "--panic-from", "3"], None);
    assert_eq!(
        report.matches("a system panicked").count(),
        1,
        "the runner's report:\n{report}"
    );
    assert_eq!(
        report.matches("panicked at").count(),
        1,
        "the panic hook's report:\n{report}"
    );
    assert!(
        report.contains("updates=12"),
        "the window did not stay:\n{report}"
    );

    let xvfb = Xvfb::start();
    let output = xvfb.run(
        Command::new(probe()).args(["--frames", "12", "--panic-from", "3", "--exit-on-error"]),
        PROBE_TIMEOUT,
    );
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(
        !output.status.success(),
        "exit_on_error exited 0:\n{stderr}"
    );
    assert!(
        stderr.contains("a system panicked") && !stderr.contains("updates=12"),
        "{stderr}"
    );
}

#[test]
fn a_close_request_ends_the_app_with_status_zero() {
    let xvfb = Xvfb::start();
    let child = xvfb.spawn(Command::new(probe()).args(["--frames", "100000"]));
    let window = xvfb.xdotool(&["search", "--sync", "--name", "window probe"]);
    // A few frames first, so the close comes to a running app.
    std::thread::sleep(Duration::from_secs(2));
    request_close(
        &xvfb,
        window.parse().expect("xdotool prints the window's id"),
    );
    let output = pom_tests::xvfb::wait_for(child, Duration::from_secs(60));
    report(&output);
}

/// The README's brick plane in a window under the window's default TAA, 2,000 frames on each
/// path: resident memory after update 1,500 is within 5 % of after update 500, and wgpu's live
/// objects are the same (the process as the operating system sees it, not only wgpu's counts).
#[test]
fn two_thousand_windowed_frames_keep_memory_flat_on_both_paths() {
    // The resident KiB and the rest of the line (the live objects) after `update`.
    let reading = |report: &str, update: u64| -> (u64, String) {
        let resident = value(
            report,
            &format!("memory at update {update}:"),
            "resident_kib",
        );
        let line = report
            .lines()
            .find(|text| text.starts_with(&format!("probe: memory at update {update}:")))
            .unwrap_or_default();
        let live = line.split_once(" buffers=").map_or("", |(_, live)| live);
        (resident.parse().expect("KiB"), live.to_owned())
    };
    for path in ["forward", "deferred"] {
        let report = run_probe(
            &[
                "--frames",
                "2000",
                "--memory-at",
                "500,1500",
                "--path",
                path,
                "--size",
                "96x64",
            ],
            None,
        );
        let (early, early_live) = reading(&report, 500);
        let (late, late_live) = reading(&report, 1500);
        eprintln!("{path}: resident {early} KiB after update 500, {late} KiB after 1500");
        assert_eq!(
            early_live, late_live,
            "{path}: live objects changed:\n{report}"
        );
        assert!(
            late as f64 <= early as f64 * 1.05,
            "{path}: resident memory grew from {early} to {late} KiB:\n{report}"
        );
    }
}
