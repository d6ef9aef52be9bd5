//! Material parameters a script sets (an entity's `set`, a preset file it loads, a `Set` step)
//! go through the same validation as the command line's flags: an error when the script is
//! loaded, naming the line, the entity or step, and the limit, in the command line's words.

use std::path::{Path, PathBuf};

use pom::ScriptError;
use pom::files::FileAccess;
use pom::script::parse_script_with;

/// A script every test changes one parameter of; it loads as it is.
const SCRIPT: &str = r#"(
    camera: (position: (0.0, 1.0, 3.0), target: (0.0, 0.0, 0.0)),
    entities: [
        (name: "floor", shape: Plane(size: 2.0),
         material: Pom(maps: "../../assets/bricks", set: (max_samples: 32))),
        (name: "corner", gltf: "../../assets/street_corner.glb"),
        (name: "ball", shape: Sphere(radius: 0.5), material: Lit(color: (0.5, 0.5, 0.5))),
    ],
    steps: [
        Set(entity: "floor", material: (height_scale: 0.05)),
        Set(entity: "corner", material: (min_samples: 4)),
    ],
)"#;

/// Where the script is taken to be: beside the shipped scene scripts, which share `assets/`.
fn script_path() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/materials.ron")
}

fn load(text: &str) -> Result<pom::script::Script, ScriptError> {
    parse_script_with(text, &script_path(), FileAccess::AnyPath)
}

/// `SCRIPT` with `from` replaced by `to`; the error's line and reason.
fn error_of(from: &str, to: &str) -> (usize, String) {
    assert!(SCRIPT.contains(from), "{from:?}");
    match load(&SCRIPT.replacen(from, to, 1)) {
        Err(ScriptError::Parse { line, reason, .. }) => (line, reason),
        other => panic!("{from:?} → {to:?}: expected a load error, got {other:?}"),
    }
}

#[test]
fn the_unchanged_script_loads() {
    load(SCRIPT).unwrap();
}

#[test]
fn too_many_samples_in_an_entitys_set_is_the_command_lines_error() {
    let (line, reason) = error_of("max_samples: 32", "max_samples: 9999");
    assert_eq!(line, 5, "{reason}");
    assert_eq!(
        reason,
        "entity \"floor\": max_samples is 9999 but must be at most 256"
    );
}

#[test]
fn a_negative_height_scale_in_a_set_step_is_an_error_naming_the_step() {
    let (line, reason) = error_of("height_scale: 0.05", "height_scale: -1.0");
    assert_eq!(line, 10, "{reason}");
    assert!(
        reason.starts_with("step 1 (Set): entity \"floor\": height_scale is -1"),
        "{reason}"
    );
}

#[test]
fn a_set_step_inverting_the_sample_bounds_is_an_error() {
    // The entity's own max_samples is 32: a later step's min_samples above it is refused.
    let (line, reason) = error_of("height_scale: 0.05", "min_samples: 40");
    assert_eq!(line, 10, "{reason}");
    assert!(
        reason.contains("min_samples (40) is greater than max_samples (32)"),
        "{reason}"
    );
}

#[test]
fn a_set_step_on_a_gltf_file_checks_each_limit() {
    let (line, reason) = error_of("min_samples: 4", "min_samples: 0");
    assert_eq!(line, 11, "{reason}");
    assert!(
        reason.contains("step 2 (Set): entity \"corner\": min_samples is 0"),
        "{reason}"
    );
}

#[test]
fn a_set_step_on_an_entity_without_a_parallax_material_is_an_error() {
    let (line, reason) = error_of("Set(entity: \"corner\"", "Set(entity: \"ball\"");
    assert_eq!(line, 11, "{reason}");
    assert!(
        reason.contains("entity \"ball\" has no parallax material to set"),
        "{reason}"
    );
}

#[test]
fn a_preset_out_of_range_is_an_error_naming_the_file_and_limit() {
    let dir = std::env::temp_dir().join(format!("pom-script-preset-{}", std::process::id()));
    std::fs::create_dir_all(dir.join("maps")).unwrap();
    let assets = Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets/bricks");
    for map in ["albedo.png", "normal.png", "height.png"] {
        std::fs::copy(assets.join(map), dir.join("maps").join(map)).unwrap();
    }
    std::fs::write(dir.join("deep.ron"), "(height_scale: 50.0)").unwrap();
    let text = r#"(
        camera: (position: (0.0, 1.0, 3.0), target: (0.0, 0.0, 0.0)),
        entities: [(name: "floor", shape: Plane(size: 2.0),
                    material: Pom(maps: "maps", preset: "deep.ron"))],
        steps: [],
    )"#;
    let error = pom::script::parse_script(text, &dir.join("preset.ron")).unwrap_err();
    std::fs::remove_dir_all(&dir).unwrap();
    let message = error.to_string();
    assert!(
        message.contains("preset.ron:4:")
            && message.contains("entity \"floor\": preset ")
            && message.contains("deep.ron: height_scale is 50 but must be at most 10"),
        "{message}"
    );
}
