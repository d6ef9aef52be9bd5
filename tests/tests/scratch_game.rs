//! A game outside this workspace, as a new user makes one: a scratch crate with the README's
//! dependency line (the registry's crate patched to this checkout) and the README's window game
//! copied verbatim as its `main.rs`.
//! It must build on its own (no workspace setting, dev-dependency or unified feature helps
//! it), open its window under Xvfb on the software driver, draw 60 frames and exit 0 with a
//! screenshot of the scene.

use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Duration;

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
/// registry's crate patched to this checkout), the workspace's lock file (so it builds the
/// versions the workspace tested, offline) and the README's game as `src/main.rs`.
fn write_scratch_crate(dir: &Path) {
    let repository = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let plugin = repository.join("plugin").canonicalize().unwrap();
    std::fs::create_dir_all(dir.join("src")).unwrap();
    std::fs::write(
        dir.join("Cargo.toml"),
        format!(
            "[package]\nname = \"scratch-game\"\nversion = \"0.1.0\"\nedition = \"2024\"\n\n\
             {dependencies}\n\
             [patch.crates-io]\nparallax-occlusion = {{ path = {plugin:?} }}\n\n\
             # A workspace of its own: nothing of ours is inherited.\n[workspace]\n\n\
             # Debug info is what a 2-core build spends most on; this test does not need it.\n\
             [profile.dev]\ndebug = false\n",
            dependencies = readme_dependencies(),
        ),
    )
    .unwrap();
    std::fs::copy(repository.join("Cargo.lock"), dir.join("Cargo.lock")).unwrap();
    std::fs::write(dir.join("src/main.rs"), readme_game()).unwrap();
}

#[test]
fn the_readmes_window_game_builds_outside_the_workspace_and_runs_sixty_frames() {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("scratch-game");
    write_scratch_crate(&dir);
    let cargo = std::env::var_os("CARGO").unwrap_or_else(|| "cargo".into());
    let built = Command::new(cargo)
        .args(["build", "--offline", "--quiet"])
        .current_dir(&dir)
        // Its own target folder, under ours: the lock on ours is held by this test run.
        .env("CARGO_TARGET_DIR", dir.join("target"))
        .env_remove("RUSTFLAGS")
        .output()
        .expect("running cargo");
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
