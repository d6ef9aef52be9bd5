//! A game outside this workspace, as a new user makes one: a scratch crate with the README's
//! dependency line (the registry's crate patched to this checkout) and the README's window game
//! copied verbatim as its `main.rs`.
//! It must build on its own (no workspace setting, dev-dependency or unified feature helps
//! it), open its window under Xvfb on the software driver, draw 60 frames and exit 0 with a
//! screenshot of the scene.

use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Duration;

use pom_tests::scratch_crate;
use pom_tests::sources::fenced_block;
use pom_tests::xvfb::{Xvfb, distinct_colours};

/// The README's window game: the Rust block of its "A game in a window" section.
fn readme_game() -> &'static str {
    fenced_block(
        include_str!("../../README.md"),
        "## A game in a window",
        "rust",
    )
}

/// The README's dependency section for that game.
fn readme_dependencies() -> &'static str {
    fenced_block(
        include_str!("../../README.md"),
        "## A game in a window",
        "toml",
    )
}

/// Writes the scratch crate under `dir`: its manifest (the README's dependency line, the
/// registry's crate patched to this checkout) and the README's game as `src/main.rs`.
fn write_scratch_crate(dir: &Path) {
    let sections = format!(
        "{dependencies}\n[patch.crates-io]\nparallax-occlusion = {{ path = {plugin:?} }}\n",
        dependencies = readme_dependencies(),
        plugin = scratch_crate::plugin_dir(),
    );
    scratch_crate::write(dir, "scratch-game", &sections, readme_game());
}

#[test]
fn the_readmes_window_game_builds_outside_the_workspace_and_runs_sixty_frames() {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("scratch-game");
    write_scratch_crate(&dir);
    let built = scratch_crate::build(&dir, &dir.join("target"));
    assert!(
        built.status.success(),
        "the scratch game does not build:\n{}",
        String::from_utf8_lossy(&built.stderr)
    );
    let xvfb = Xvfb::start();
    let screenshot = dir.join("screenshot.png");
    let _ = std::fs::remove_file(&screenshot);
    let output = xvfb.run(
        Command::new(dir.join("target/debug/scratch-game"))
            .env("POM_EXIT_AFTER_FRAMES", "60")
            .env("POM_SCREENSHOT", &screenshot),
        Duration::from_secs(300),
    );
    assert!(
        output.status.success(),
        "the scratch game exited {}:\n{}",
        output.status,
        String::from_utf8_lossy(&output.stderr)
    );
    let image = image::open(&screenshot).unwrap().to_rgba8();
    assert_eq!(image.dimensions(), (1280, 720));
    let colours = distinct_colours(&image, 0..1280, 0..720);
    assert!(colours > 100, "only {colours} distinct colours: no bricks");
}
