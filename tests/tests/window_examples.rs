//! The library's examples run as a game would: the windowed ones under Xvfb on the software
//! driver (`POM_EXIT_AFTER_FRAMES` ends them with status 0 and `POM_SCREENSHOT` writes the last
//! presented frame, which shows a scene; bad automation variables are one-line errors), the
//! headless one writing its PNG.
//!
//! `cargo test` builds the examples (the `window` feature is on in this workspace) into
//! target/<profile>/examples/, beside the test binaries' deps/ folder.

use std::path::{Path, PathBuf};
use std::process::{Child, Command};
use std::time::{Duration, Instant};

use pom_tests::xvfb::{Xvfb, distinct_colours};

#[path = "support/close_request.rs"]
mod close_request;

/// How long an example may take to draw its frames (a debug build on a software GPU).
const EXAMPLE_TIMEOUT: Duration = Duration::from_secs(300);

fn example(name: &str) -> PathBuf {
    let deps = std::env::current_exe().expect("the test binary's path");
    let profile = deps
        .parent()
        .and_then(Path::parent)
        .expect("test binaries live in target/<profile>/deps");
    let path = profile.join("examples").join(name);
    assert!(
        path.is_file(),
        "{} is missing: `cargo test --workspace` builds the examples (a filtered run builds none: `cargo build -p parallax-occlusion --examples --features window`)",
        path.display()
    );
    path
}

/// Runs example `name` for `frames` frames on a fresh Xvfb and returns its screenshot.
fn screenshot_of(name: &str, frames: u32) -> image::RgbaImage {
    screenshot_of_with(name, &[], frames)
}

/// [`screenshot_of`] with arguments.
fn screenshot_of_with(name: &str, args: &[&std::ffi::OsStr], frames: u32) -> image::RgbaImage {
    let xvfb = Xvfb::start();
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("window_examples");
    std::fs::create_dir_all(&dir).unwrap();
    let screenshot = dir.join(format!("{name}.png"));
    let _ = std::fs::remove_file(&screenshot);
    let output = xvfb.run(
        Command::new(example(name))
            .args(args)
            .env("POM_EXIT_AFTER_FRAMES", frames.to_string())
            .env("POM_SCREENSHOT", &screenshot),
        EXAMPLE_TIMEOUT,
    );
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(
        output.status.success(),
        "{name} failed ({}):\n{stderr}",
        output.status
    );
    image::open(&screenshot)
        .unwrap_or_else(|error| panic!("{name} wrote no screenshot ({error}):\n{stderr}"))
        .to_rgba8()
}

#[test]
fn the_parallax_example_runs_thirty_frames_and_shows_its_scene() {
    let image = screenshot_of("parallax", 30);
    // WindowPlugin's default size; Xvfb's scale is 1.
    assert_eq!(image.dimensions(), (1280, 720));
    // The bricks are grey, lit and shadowed in many shades; the background is one colour.
    let colours = distinct_colours(&image, 0..1280, 0..720);
    assert!(colours > 100, "only {colours} distinct colours: no scene");
    let (sky, floor) = (image.get_pixel(10, 10).0, image.get_pixel(640, 700).0);
    assert_ne!(
        sky, floor,
        "the floor at the bottom looks like the background"
    );
}

#[test]
fn a_bad_automation_variable_is_a_one_line_error_and_a_failing_status() {
    let xvfb = Xvfb::start();
    for (variable, value, says) in [
        (
            "POM_EXIT_AFTER_FRAMES",
            "abc",
            "POM_EXIT_AFTER_FRAMES=\"abc\" is not a frame count",
        ),
        (
            "POM_EXIT_AFTER_FRAMES",
            "-1",
            "POM_EXIT_AFTER_FRAMES=\"-1\" is not a frame count",
        ),
        (
            "POM_SCREENSHOT",
            "/no/such/folder/shot.png",
            "the folder \"/no/such/folder\" does not exist",
        ),
        (
            "POM_FRAME_TIMES",
            "/no/such/folder/times.csv",
            "POM_FRAME_TIMES=\"/no/such/folder/times.csv\": the folder",
        ),
    ] {
        let output = xvfb.run(
            Command::new(example("parallax"))
                .env("POM_EXIT_AFTER_FRAMES", "1")
                .env(variable, value),
            EXAMPLE_TIMEOUT,
        );
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert!(!output.status.success(), "{variable}={value}: exited 0");
        assert_eq!(stderr.lines().count(), 1, "{variable}={value}: {stderr}");
        assert!(
            stderr.contains(says) && !stderr.contains("panicked"),
            "{stderr}"
        );
    }
}

/// Runs the headless example `name` with no display and returns the PNG it wrote.
fn headless_output(name: &str) -> image::RgbaImage {
    let out = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("{name}-example.png"));
    let _ = std::fs::remove_file(&out);
    let output = Command::new(example(name))
        .arg(&out)
        .env_remove("DISPLAY")
        .env_remove("WAYLAND_DISPLAY")
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(output.status.success(), "{name}: {stderr}");
    image::open(&out).unwrap().to_rgba8()
}

#[test]
fn the_headless_example_writes_its_frame_without_a_display() {
    let image = headless_output("headless");
    assert_eq!(image.dimensions(), (512, 512));
    let colours = distinct_colours(&image, 0..512, 0..512);
    assert!(colours > 100, "only {colours} distinct colours: no bricks");
}

/// The depth the parallax example's title shows.
fn title_depth(title: &str) -> f32 {
    title
        .split("depth ")
        .nth(1)
        .and_then(|rest| rest.split(' ').next())
        .and_then(|depth| depth.parse().ok())
        .unwrap_or_else(|| panic!("no depth in the title {title:?}"))
}

/// Starts the parallax example on `xvfb`, writing its last frame to `screenshot`, and presses
/// 2 in its window until the title's depth has risen by `rise`; returns the process, the
/// window's id and the depth before.
fn deepen_parallax(xvfb: &Xvfb, screenshot: &Path, rise: f32) -> (Child, String, f32) {
    let child = xvfb.spawn(Command::new(example("parallax")).env("POM_SCREENSHOT", screenshot));
    // Its first frame titles it with the values.
    let found = xvfb.xdotool(&["search", "--sync", "--name", "^parallax: depth"]);
    let window = found.lines().next().unwrap_or_default().to_owned();
    let title = || xvfb.xdotool(&["getwindowname", &window]);
    let before = title_depth(&title());
    // Keys go to the focused window (xdotool's synthetic events to a window are ignored).
    xvfb.xdotool(&["windowfocus", "--sync", &window]);
    let deadline = Instant::now() + Duration::from_secs(120);
    while title_depth(&title()) < before + rise {
        assert!(
            Instant::now() < deadline,
            "the key 2 raised the depth from {before} only to: {}",
            title()
        );
        xvfb.xdotool(&["key", "2"]);
        std::thread::sleep(Duration::from_millis(500));
    }
    (child, window, before)
}

#[test]
fn the_parallax_window_takes_keys_follows_resizes_and_exits_0_when_closed() {
    let xvfb = Xvfb::start();
    let screenshot = Path::new(env!("CARGO_TARGET_TMPDIR")).join("parallax-resized.png");
    let _ = std::fs::remove_file(&screenshot);
    // One step of 0.01 up.
    let (mut child, window, _) = deepen_parallax(&xvfb, &screenshot, 0.005);
    for (width, height) in [(900, 500), (640, 480), (1000, 700), (500, 500), (800, 450)] {
        xvfb.xdotool(&[
            "windowsize",
            "--sync",
            &window,
            &width.to_string(),
            &height.to_string(),
        ]);
        std::thread::sleep(Duration::from_millis(800));
    }
    // A frame or more at the last size, then the window goes away.
    std::thread::sleep(Duration::from_secs(2));
    xvfb.xdotool(&["windowclose", &window]);
    let deadline = Instant::now() + EXAMPLE_TIMEOUT;
    let status = loop {
        if let Some(status) = child.try_wait().unwrap() {
            break status;
        }
        assert!(
            Instant::now() < deadline,
            "the example did not exit after its window closed"
        );
        std::thread::sleep(Duration::from_millis(50));
    };
    let stderr = child
        .wait_with_output()
        .map(|o| String::from_utf8_lossy(&o.stderr).into_owned());
    assert!(
        status.success(),
        "closing the window exited {status}: {stderr:?}"
    );
    let image = image::open(&screenshot).unwrap().to_rgba8();
    assert_eq!(
        image.dimensions(),
        (800, 450),
        "the last frame is the window's last size"
    );
    let colours = distinct_colours(&image, 0..800, 0..450);
    assert!(
        colours > 100,
        "only {colours} distinct colours after the resizes"
    );
}

/// Mean absolute difference of the colour channels of `a` and `b` in the floor's front-left
/// corner, clear of the spinning cube and its shadow.
fn floor_difference(a: &image::RgbaImage, b: &image::RgbaImage) -> f64 {
    let (mut sum, mut count) = (0_u64, 0_u64);
    for y in 560..720 {
        for x in 0..320 {
            let (p, q) = (a.get_pixel(x, y).0, b.get_pixel(x, y).0);
            for c in 0..3 {
                sum += u64::from(p[c].abs_diff(q[c]));
                count += 1;
            }
        }
    }
    sum as f64 / count as f64
}

#[test]
fn a_key_press_changes_the_parallax_depth_on_screen_and_a_close_request_exits_0() {
    let untouched = screenshot_of("parallax", 30);
    let xvfb = Xvfb::start();
    let screenshot = Path::new(env!("CARGO_TARGET_TMPDIR")).join("parallax-deeper.png");
    let _ = std::fs::remove_file(&screenshot);
    // Three steps of 0.01 deeper: the bricks' relief grows visibly.
    let (child, window, before) = deepen_parallax(&xvfb, &screenshot, 0.025);
    close_request::request_close(&xvfb, window.parse().expect("a window id"));
    let output = pom_tests::xvfb::wait_for(child, EXAMPLE_TIMEOUT);
    assert!(
        output.status.success(),
        "the close request exited {}: {}",
        output.status,
        String::from_utf8_lossy(&output.stderr)
    );
    let deeper = image::open(&screenshot).unwrap().to_rgba8();
    let difference = floor_difference(&untouched, &deeper);
    // Under the window's default sky the bricks are lit from all around besides the sun, so
    // the deeper relief changes the floor by about 1.7 levels a channel (it was over 2 under
    // the flat ambient light).
    assert!(
        difference > 1.0,
        "the floor looks the same after the depth rose from {before}: mean difference {difference}"
    );
}

#[test]
fn the_gltf_viewer_shows_the_street_corner_and_names_a_bad_file() {
    let street_corner = Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets/street_corner.glb");
    let image = screenshot_of_with("gltf_viewer", &[street_corner.as_os_str()], 30);
    let colours = distinct_colours(&image, 0..1280, 0..720);
    assert!(
        colours > 1000,
        "only {colours} distinct colours: no street corner"
    );
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("window_examples");
    std::fs::create_dir_all(&dir).unwrap();
    let broken = dir.join("broken.glb");
    std::fs::write(&broken, "not a glTF file").unwrap();
    let missing = dir.join("missing.glb");
    for file in [&missing, &broken] {
        let output = Command::new(example("gltf_viewer"))
            .arg(file)
            .env_remove("DISPLAY")
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert!(!output.status.success(), "{}: exited 0", file.display());
        assert!(
            stderr.contains(&*file.to_string_lossy()) && !stderr.contains("panicked"),
            "{stderr}"
        );
    }
}

#[test]
fn the_custom_material_example_shows_the_documented_material() {
    let image = screenshot_of("custom_material", 30);
    // The cube is unlit orange (linear 0.9, 0.35, 0.05, tonemapped): red over green over blue,
    // where the lit floor is grey and the background a dark blue-grey.
    let cube_pixels = image
        .pixels()
        .filter(|pixel| {
            let [r, g, b, _] = pixel.0;
            r > 200 && (100..200).contains(&g) && b < 80
        })
        .count();
    assert!(
        cube_pixels > 2000,
        "only {cube_pixels} pixels of the cube's colour"
    );
}

#[test]
fn the_readmes_window_game_is_the_minimal_example_and_runs() {
    let readme = include_str!("../../README.md");
    let example = include_str!("../../plugin/examples/minimal.rs");
    let code = &example[example
        .find("use pom::prelude")
        .expect("the example's code")..];
    let section = &readme[readme
        .find("## A game in a window")
        .expect("the README's section")..];
    assert!(
        section.contains(code),
        "the README's window game and plugin/examples/minimal.rs differ"
    );
    let image = screenshot_of("minimal", 30);
    let colours = distinct_colours(&image, 0..1280, 0..720);
    assert!(colours > 100, "only {colours} distinct colours: no bricks");
}

/// The luminance of an sRGB-encoded pixel, encoded: what the post-effect example writes.
fn encoded_luminance([r, g, b, _]: [u8; 4]) -> f32 {
    let linear = |value: u8| pom::srgb_to_linear(f32::from(value) / 255.0);
    let luminance = 0.2126 * linear(r) + 0.7152 * linear(g) + 0.0722 * linear(b);
    pom::linear_to_srgb(luminance.clamp(0.0, 1.0)) * 255.0
}

#[test]
fn the_post_effect_example_turns_the_street_corner_grey() {
    let grey = headless_output("post_effect");
    // The same frame without the effect.
    let scene = Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets/street_corner.glb");
    let mut app = pom::App::new();
    app.add_plugin(pom::DefaultPlugins::headless(384, 216));
    pom::load_gltf(&mut app, &scene).unwrap();
    let colour = pom_tests::render_and_capture(&mut app).unwrap();
    assert_eq!(grey.dimensions(), colour.dimensions());
    for (x, y, pixel) in grey.enumerate_pixels() {
        let [r, g, b, a] = pixel.0;
        assert!(
            r == g && g == b,
            "pixel ({x}, {y}) is not grey: {:?}",
            pixel.0
        );
        let before = colour.get_pixel(x, y).0;
        let expected = encoded_luminance(before);
        assert!(
            (f32::from(r) - expected).abs() <= 1.0 && a == before[3],
            "pixel ({x}, {y}) is {r}, the luminance of {before:?} is {expected}"
        );
    }
    assert!(distinct_colours(&grey, 0..384, 0..216) > 50, "no scene");
}

#[test]
fn the_renderer_guide_shows_the_post_effect_example() {
    let guide = include_str!("../../plugin/docs/renderer.md");
    let example = include_str!("../../plugin/examples/post_effect.rs");
    let code = &example[example
        .find("use pom::prelude")
        .expect("the example's code")..];
    let section = &guide[guide
        .find("## A post effect of your own")
        .expect("the guide's section")..];
    assert!(
        section.contains(code),
        "the renderer guide's post effect and plugin/examples/post_effect.rs differ"
    );
}

#[test]
fn the_night_street_example_shows_the_street_lit_by_its_lamps_and_lanterns() {
    let image = screenshot_of("night_street", 20);
    assert_eq!(image.dimensions(), (1280, 720));
    // A night: most of the frame is dark, and the lamps light the stones and bricks in many
    // warm shades (red over blue where they shine).
    let colours = distinct_colours(&image, 0..1280, 0..720);
    assert!(colours > 100, "only {colours} distinct colours: no scene");
    let (lit, warm) = image.pixels().fold((0, 0), |(lit, warm), pixel| {
        let [r, _, b, _] = pixel.0;
        (
            lit + usize::from(r > 40),
            warm + usize::from(r > 40 && r > b + 20),
        )
    });
    assert!(lit > 20_000, "only {lit} lit pixels");
    assert!(warm * 10 > lit * 8, "{warm} of {lit} lit pixels are warm");
}

#[test]
fn the_terrain_example_shows_its_layers_under_the_sky() {
    let image = screenshot_of("terrain", 10);
    assert_eq!(image.dimensions(), (1280, 720));
    let colours = distinct_colours(&image, 0..1280, 0..720);
    assert!(colours > 100, "only {colours} distinct colours: no scene");
    // Grass (green over red and blue), rock and cobbles (grey), earth (red over blue), sky.
    let share = |test: &dyn Fn([u8; 4]) -> bool| {
        image.pixels().filter(|pixel| test(pixel.0)).count() as f32 / (1280.0 * 720.0)
    };
    let grass = share(&|[r, g, b, _]| g > r + 30 && g > b + 30);
    let grey = share(&|[r, g, b, _]| r > 120 && r.abs_diff(g) < 20 && r.abs_diff(b) < 30);
    let earth = share(&|[r, g, b, _]| r > g + 15 && g > b + 10 && r > 60);
    eprintln!("grass {grass:.3}, grey {grey:.3}, earth {earth:.3}");
    assert!(grass > 0.2, "grass covers {grass}");
    assert!(grey > 0.03, "rock and cobbles cover {grey}");
    assert!(earth > 0.005, "earth covers {earth}");
}

#[test]
fn the_rocks_example_shows_boulders_with_relief_on_the_cobbles() {
    let image = screenshot_of("rocks", 10);
    assert_eq!(image.dimensions(), (1280, 720));
    // The boulders stand in the middle of the frame: grey rock there (not the brown cobbles or
    // the blue sky), lit unevenly by its relief.
    let rock: Vec<f32> = image
        .enumerate_pixels()
        .filter(|(x, y, _)| (300..800).contains(x) && (150..500).contains(y))
        .map(|(_, _, pixel)| pixel.0)
        .filter(|[r, g, b, _]| r.abs_diff(*g) < 12 && r.abs_diff(*b) < 20 && *r > 40)
        .map(encoded_luminance)
        .collect();
    let share = rock.len() as f32 / (500.0 * 350.0);
    let mean = rock.iter().sum::<f32>() / rock.len().max(1) as f32;
    let spread =
        (rock.iter().map(|l| (l - mean).powi(2)).sum::<f32>() / rock.len().max(1) as f32).sqrt();
    eprintln!("rock covers {share:.3} of the middle, luminance {mean:.1} ± {spread:.1} of 255");
    assert!(share > 0.3, "rock covers {share} of the middle");
    assert!(
        spread > 10.0,
        "the rock is flat: luminance spread {spread} of 255"
    );
}

/// A windowed example built without the `window` feature fails to compile, so each declares
/// the feature it needs: `cargo build --examples` then skips it instead of failing.
#[test]
fn every_windowed_example_requires_the_window_feature() {
    let plugin = Path::new(env!("CARGO_MANIFEST_DIR")).join("../plugin");
    let manifest = std::fs::read_to_string(plugin.join("Cargo.toml")).unwrap();
    let declared: Vec<&str> = manifest
        .split("[[example]]")
        .skip(1)
        .filter(|entry| entry.contains("required-features = [\"window\"]"))
        .filter_map(|entry| entry.split('"').nth(1))
        .collect();
    let mut windowed = Vec::new();
    for file in std::fs::read_dir(plugin.join("examples")).unwrap() {
        let path = file.unwrap().path();
        let text = std::fs::read_to_string(&path).unwrap();
        if text.contains("windowed(") || text.contains("WindowPlugin") {
            windowed.push(path.file_stem().unwrap().to_string_lossy().into_owned());
        }
    }
    windowed.sort();
    assert!(windowed.len() >= 5, "{windowed:?}");
    for name in &windowed {
        assert!(
            declared.contains(&name.as_str()),
            "plugin/Cargo.toml has no [[example]] {name} with required-features = [\"window\"]"
        );
    }
}
