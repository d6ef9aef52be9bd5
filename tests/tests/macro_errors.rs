//! What a game's programmer reads when a `material_parameters!` declaration is malformed: a
//! scratch crate outside the workspace declares a material whose second parameter has no doc
//! line, and its build must fail with one error naming that parameter and the fix.

use std::path::{Path, PathBuf};
use std::process::Command;

/// A material declaration whose `roughness` parameter lacks its doc line.
const UNDOCUMENTED_PARAMETER: &str = r#"use pom::prelude::*;

pom::material_parameters! {
    /// A matte surface.
    #[derive(Clone, Debug, PartialEq)]
    pub struct Matte {
        parameters {
            /// The surface's colour, linear.
            color: Color = Color::WHITE, ParamSpec::color();
            roughness: f32 = 0.5, ParamSpec::unit();
        }
    }
}

fn main() {
    let _ = Matte::default();
}
"#;

/// Writes the scratch crate under `dir`: a manifest depending on this checkout's plugin, the
/// workspace's lock file (offline, the tested versions) and `main`.
fn write_scratch_crate(dir: &Path, main: &str) {
    let repository = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let plugin = repository.join("plugin").canonicalize().unwrap();
    std::fs::create_dir_all(dir.join("src")).unwrap();
    std::fs::write(
        dir.join("Cargo.toml"),
        format!(
            "[package]\nname = \"macro-errors\"\nversion = \"0.1.0\"\nedition = \"2024\"\n\n\
             [dependencies]\npom = {{ package = \"parallax-occlusion\", path = {plugin:?} }}\n\n\
             [workspace]\n\n[profile.dev]\ndebug = false\n"
        ),
    )
    .unwrap();
    std::fs::copy(repository.join("Cargo.lock"), dir.join("Cargo.lock")).unwrap();
    std::fs::write(dir.join("src/main.rs"), main).unwrap();
}

#[test]
fn a_parameter_without_a_doc_line_is_named_in_one_readable_error() {
    let scratch = PathBuf::from(env!("CARGO_TARGET_TMPDIR"));
    let dir = scratch.join("macro-errors");
    write_scratch_crate(&dir, UNDOCUMENTED_PARAMETER);
    let cargo = std::env::var_os("CARGO").unwrap_or_else(|| "cargo".into());
    let built = Command::new(cargo)
        .args(["build", "--offline", "--quiet"])
        .current_dir(&dir)
        // The scratch game's target folder: its dependencies are built already (or will be).
        .env("CARGO_TARGET_DIR", scratch.join("scratch-game/target"))
        .env_remove("RUSTFLAGS")
        .output()
        .expect("running cargo");
    let stderr = String::from_utf8_lossy(&built.stderr);
    assert!(!built.status.success(), "it built:\n{stderr}");
    assert!(
        stderr.contains("parameter `roughness` has no doc line: write `/// what it does` above it"),
        "{stderr}"
    );
    assert_eq!(
        stderr.matches("error:").count(),
        2,
        "one error and the summary:\n{stderr}"
    );
    assert!(!stderr.contains("no rules expected"), "{stderr}");
}
