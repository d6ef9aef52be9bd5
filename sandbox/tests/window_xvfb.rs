//! Starts the real sandbox window under Xvfb (on whatever Vulkan driver the environment pins:
//! tests/run pins Mesa's software driver), lets it draw five frames, and checks the screenshot
//! it writes: the window's size, a 3D scene in the viewport, and the side panel beside it
//! (compared with its reference image).

use std::path::Path;
use std::process::Command;
use std::time::Duration;

use pom_tests::xvfb::{Xvfb, distinct_colours};
use pom_tests::{FlipTolerance, check_golden};

/// The window's size in pixels (the sandbox opens at 1280×720 logical pixels; Xvfb's scale is 1).
const WINDOW_SIZE: (u32, u32) = (1280, 720);
/// Width of the side panel when the window opens, in pixels: the part compared with a reference.
const PANEL_WIDTH: u32 = 380;
/// How long the sandbox may take (a debug build drawing on a software GPU).
const SANDBOX_TIMEOUT: Duration = Duration::from_secs(300);

/// Runs the sandbox on `xvfb`, killing it if it overruns; returns its stderr.
fn run_sandbox(xvfb: &Xvfb, args: &[&std::ffi::OsStr]) -> String {
    let output = xvfb.run(
        Command::new(env!("CARGO_BIN_EXE_sandbox")).args(args),
        SANDBOX_TIMEOUT,
    );
    let stderr = String::from_utf8_lossy(&output.stderr).into_owned();
    assert!(
        output.status.success(),
        "the sandbox failed ({}):\n{stderr}",
        output.status
    );
    stderr
}

fn mean_colour(
    image: &image::RgbaImage,
    x: std::ops::Range<u32>,
    y: std::ops::Range<u32>,
) -> [f64; 3] {
    let mut sum = [0.0; 3];
    let mut count = 0.0;
    for y in y {
        for x in x.clone() {
            let pixel = image.get_pixel(x, y).0;
            for channel in 0..3 {
                sum[channel] += f64::from(pixel[channel]);
            }
            count += 1.0;
        }
    }
    sum.map(|s| s / count)
}

/// Runs the sandbox for 5 frames under a fresh Xvfb with `extra` flags and returns its
/// screenshot, kept under target/`folder`/ (overwritten by each run, so the last one is there
/// to look at).
fn window_screenshot(folder: &str, extra: &[&str]) -> image::RgbaImage {
    let xvfb = Xvfb::start();
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(folder);
    std::fs::create_dir_all(&dir).unwrap();
    let screenshot = dir.join("window.png");
    let state = dir.join("state.ron");
    // A stale screenshot or state from an earlier run must not count.
    let _ = std::fs::remove_file(&screenshot);
    let _ = std::fs::remove_file(&state);
    let mut args: Vec<&std::ffi::OsStr> = vec![
        "--exit-after-frames".as_ref(),
        "5".as_ref(),
        "--screenshot".as_ref(),
        screenshot.as_os_str(),
        "--state".as_ref(),
        state.as_os_str(),
    ];
    args.extend(extra.iter().map(std::ffi::OsStr::new));
    let stderr = run_sandbox(&xvfb, &args);
    let image = image::open(&screenshot)
        .unwrap_or_else(|error| {
            panic!(
                "no screenshot at {} ({error}); stderr:\n{stderr}",
                screenshot.display()
            )
        })
        .to_rgba8();
    let _ = std::fs::remove_file(&state);
    image
}

#[test]
fn the_window_shows_the_scene_and_the_panel_in_its_screenshot() {
    let image = window_screenshot("window_xvfb", &[]);
    assert_eq!(
        image.dimensions(),
        WINDOW_SIZE,
        "the screenshot is the window's size"
    );
    let (width, height) = WINDOW_SIZE;
    // The side panel is on the left (380 points wide); the 3D view fills the rest.
    let viewport = (500..width - 10, 10..height - 10);
    let panel = (10..300, 40..height - 40);
    let scene_colours = distinct_colours(&image, viewport.0.clone(), viewport.1.clone());
    assert!(
        scene_colours > 1000,
        "the viewport has only {scene_colours} distinct colours: no 3D scene"
    );
    let panel_colours = distinct_colours(&image, panel.0.clone(), panel.1.clone());
    assert!(
        panel_colours > 20,
        "the panel region has only {panel_colours} distinct colours: no text or widgets"
    );
    let scene_mean = mean_colour(&image, viewport.0, viewport.1);
    let panel_mean = mean_colour(&image, panel.0, panel.1);
    let difference: f64 = scene_mean
        .iter()
        .zip(panel_mean)
        .map(|(a, b)| (a - b).abs())
        .sum();
    assert!(
        difference > 15.0,
        "the panel region ({panel_mean:?}) looks like the viewport ({scene_mean:?})"
    );
}

/// The panel's pixels do not depend on the 3D scene: its text and widgets are drawn by egui
/// the same way on any driver, so a change of layout shows as a large difference.
#[test]
fn the_panel_at_1280_by_720_matches_its_reference() {
    let image = window_screenshot("window_xvfb_panel", &[]);
    let panel = image::imageops::crop_imm(&image, 0, 0, PANEL_WIDTH, WINDOW_SIZE.1).to_image();
    if let Err(error) = check_golden("sandbox_panel_1280x720", &panel, FlipTolerance::default()) {
        panic!("{error}");
    }
}

#[test]
fn the_split_view_shows_a_wipe_between_two_images() {
    let image = window_screenshot("window_xvfb_split", &["--split-method", "normal"]);
    let (width, height) = image.dimensions();
    // The wipe is a bright vertical line through the viewport's middle (the panel is on the
    // left, so the middle of the viewport is right of the window's middle).
    let rows = 20..height - 20;
    let bright_rows = |x: u32| {
        rows.clone()
            .filter(|y| image.get_pixel(x, *y).0[..3].iter().all(|c| *c > 230))
            .count()
    };
    let wipe_columns: Vec<u32> = (width / 2..width - 100)
        .filter(|x| bright_rows(*x) * 10 > rows.len() * 9)
        .collect();
    assert!(
        !wipe_columns.is_empty() && wipe_columns.len() <= 4,
        "expected one wipe line, found bright columns {wipe_columns:?}"
    );
}

#[test]
fn without_a_display_it_says_so_once_and_points_at_headless_rendering() {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("window_no_display");
    std::fs::create_dir_all(&dir).unwrap();
    let output = Command::new(env!("CARGO_BIN_EXE_sandbox"))
        .args(["--exit-after-frames", "1", "--state"])
        .arg(dir.join("state.ron"))
        .env_remove("DISPLAY")
        .env_remove("WAYLAND_DISPLAY")
        .env_remove("WAYLAND_SOCKET")
        .output()
        .unwrap();
    assert!(!output.status.success());
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(
        stderr.matches("cannot open a window").count(),
        1,
        "{stderr}"
    );
    assert!(stderr.contains("sandbox render"), "{stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
}
