//! `--preset FILE.ron` on `render` and `snapshot`, parsed as the command line parses it: the
//! preset's values reach the material, flags given explicitly override them, and every bad
//! preset file is a usage error naming the file (and the field, for a bad value).

use clap::Parser;
use pom::{DebugView, LightingModel, ParallaxMethod, ParallaxOcclusionMaterial, ShadowMode};

use crate::{Cli, Command};

/// A folder of its own for one test's preset files.
fn scratch_dir(test: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("sandbox-preset-{test}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Writes `text` as `name` in `dir`; returns its path as text.
fn preset_file(dir: &std::path::Path, name: &str, text: &str) -> String {
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path.display().to_string()
}

/// The material `sandbox render ARGS` describes.
fn render_material(args: &[&str]) -> Result<ParallaxOcclusionMaterial, clap::Error> {
    let all = ["sandbox", "render", "--out", "a.png"].iter().chain(args);
    match Cli::try_parse_from(all)?.command {
        Some(Command::Render(render)) => Ok(render.material_settings()),
        other => panic!("parsed as {other:?}"),
    }
}

const TUNED: &str = "(height_scale: 0.09, min_samples: 16, max_samples: 64, method: relief, \
                     lighting: ggx_lambert, roughness: 0.25, shadows: hard, debug_view: lod)";

#[test]
fn a_presets_values_reach_the_rendered_material() {
    let dir = scratch_dir("values");
    let preset = preset_file(&dir, "tuned.ron", TUNED);
    let material = render_material(&["--preset", &preset]).unwrap();
    assert_eq!(material.height_scale, 0.09);
    assert_eq!((material.min_samples, material.max_samples), (16, 64));
    assert_eq!(material.method, ParallaxMethod::Relief);
    assert_eq!(material.lighting, LightingModel::GgxLambert);
    assert_eq!(material.roughness, 0.25);
    assert_eq!(material.shadows, ShadowMode::Hard);
    // The view is an output option: the preset's does not apply.
    assert_eq!(material.debug_view, DebugView::None);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn flags_given_override_the_preset_and_flags_left_out_do_not() {
    let dir = scratch_dir("override");
    let preset = preset_file(&dir, "tuned.ron", TUNED);
    // --min-samples 8 is the default value, given on purpose: it still overrides the 16.
    let material = render_material(&[
        "--preset",
        &preset,
        "--max-samples",
        "32",
        "--min-samples",
        "8",
        "--lighting",
        "phong",
    ])
    .unwrap();
    assert_eq!((material.min_samples, material.max_samples), (8, 32));
    assert_eq!(material.lighting, LightingModel::Phong);
    assert_eq!(material.height_scale, 0.09, "left out: the preset's value");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn snapshot_takes_a_preset() {
    let dir = scratch_dir("snapshot");
    let preset = preset_file(&dir, "tuned.ron", TUNED);
    let cli = Cli::try_parse_from(["sandbox", "snapshot", "--preset", &preset]).unwrap();
    let Some(Command::Snapshot(snapshot)) = cli.command else {
        panic!("not a snapshot");
    };
    let preset = snapshot.preset.expect("the preset was read");
    assert_eq!(preset.lighting, LightingModel::GgxLambert);
    let _ = std::fs::remove_dir_all(&dir);
}

/// Asserts that `command --preset PATH` is a usage error mentioning every one of `expected`.
fn assert_rejected(command: &str, path: &str, expected: &[&str]) {
    let mut args = vec!["sandbox", command, "--preset", path];
    if command == "render" {
        args.extend(["--out", "a.png"]);
    }
    let error = Cli::try_parse_from(args).expect_err(path);
    let text = error.to_string();
    assert_eq!(
        error.kind(),
        clap::error::ErrorKind::ValueValidation,
        "{text}"
    );
    for word in expected {
        assert!(
            text.contains(word),
            "{command}: {text:?} does not mention {word:?}"
        );
    }
}

#[test]
fn a_preset_with_an_unknown_field_is_named_with_the_field() {
    let dir = scratch_dir("unknown-field");
    let path = preset_file(&dir, "typo.ron", "(\n  hieght_scale: 0.02,\n)");
    for command in ["render", "snapshot"] {
        assert_rejected(command, &path, &["typo.ron:2:", "hieght_scale"]);
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_preset_with_a_value_out_of_range_is_named_with_the_field() {
    let dir = scratch_dir("out-of-range");
    let path = preset_file(&dir, "deep.ron", "(max_samples: 100000)");
    for command in ["render", "snapshot"] {
        assert_rejected(command, &path, &["deep.ron", "max_samples", "256"]);
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_preset_with_a_wrong_type_is_named_with_its_place() {
    let dir = scratch_dir("wrong-type");
    let path = preset_file(&dir, "words.ron", "(min_samples: \"few\")");
    for command in ["render", "snapshot"] {
        assert_rejected(command, &path, &["words.ron:1:"]);
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_missing_preset_file_is_named() {
    let dir = scratch_dir("missing");
    let path = dir.join("absent.ron").display().to_string();
    for command in ["render", "snapshot"] {
        assert_rejected(command, &path, &["absent.ron"]);
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_folder_as_preset_is_refused_naming_it() {
    let dir = scratch_dir("folder");
    let folder = dir.join("not-a-file.ron");
    std::fs::create_dir_all(&folder).unwrap();
    let path = folder.display().to_string();
    for command in ["render", "snapshot"] {
        assert_rejected(command, &path, &["not-a-file.ron", "regular file"]);
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_preset_conflicts_with_a_scene_in_render() {
    let dir = scratch_dir("scene");
    let preset = preset_file(&dir, "tuned.ron", TUNED);
    let error = render_material(&["--scene", "city.glb", "--preset", &preset]).unwrap_err();
    assert_eq!(error.kind(), clap::error::ErrorKind::ArgumentConflict);
    let _ = std::fs::remove_dir_all(&dir);
}
