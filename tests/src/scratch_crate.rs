//! Crates outside the workspace, as a user makes them: a manifest of their own (no workspace
//! setting, dev-dependency or unified feature helps them), built offline against the
//! workspace's lock file so they get the versions the workspace tested.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// The folder of the plugin crate, absolute, for a manifest's `path =`.
pub fn plugin_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../plugin")
        .canonicalize()
        .expect("the plugin folder exists")
}

/// Writes a binary crate named `name` under `dir`: its manifest (`sections`: dependencies,
/// patches), the workspace's lock file and `main` as `src/main.rs`.
pub fn write(dir: &Path, name: &str, sections: &str, main: &str) {
    let lock = Path::new(env!("CARGO_MANIFEST_DIR")).join("../Cargo.lock");
    std::fs::create_dir_all(dir.join("src")).unwrap();
    std::fs::write(
        dir.join("Cargo.toml"),
        format!(
            "[package]\nname = \"{name}\"\nversion = \"0.1.0\"\nedition = \"2024\"\n\n\
             {sections}\n\
             # A workspace of its own: nothing of ours is inherited.\n[workspace]\n\n\
             # Debug info is what a 2-core build spends most on; these tests do not need it.\n\
             [profile.dev]\ndebug = false\n"
        ),
    )
    .unwrap();
    std::fs::copy(lock, dir.join("Cargo.lock")).unwrap();
    std::fs::write(dir.join("src/main.rs"), main).unwrap();
}

/// `cargo build --offline` of the crate in `dir` into `target_dir` (not the workspace's:
/// the lock on it is held by the test run).
pub fn build(dir: &Path, target_dir: &Path) -> Output {
    let cargo = std::env::var_os("CARGO").unwrap_or_else(|| "cargo".into());
    Command::new(cargo)
        .args(["build", "--offline", "--quiet"])
        .current_dir(dir)
        .env("CARGO_TARGET_DIR", target_dir)
        .env_remove("RUSTFLAGS")
        .output()
        .expect("running cargo")
}
