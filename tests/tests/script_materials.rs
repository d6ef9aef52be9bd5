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

#[test]
fn a_preset_with_layers_builds_them_from_its_files_and_names_a_bad_one() {
    let dir = std::env::temp_dir().join(format!("pom-script-layers-{}", std::process::id()));
    std::fs::create_dir_all(dir.join("maps")).unwrap();
    let assets = Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets/bricks");
    for map in ["albedo.png", "normal.png", "height.png"] {
        std::fs::copy(assets.join(map), dir.join("maps").join(map)).unwrap();
    }
    // A bright and a dark layer, the bright one weighing on the plane's first half in u.
    for (name, grey) in [("bright.png", 240), ("dark.png", 20)] {
        image::RgbaImage::from_pixel(4, 4, image::Rgba([grey, grey, grey, 255]))
            .save(dir.join(name))
            .unwrap();
    }
    image::RgbaImage::from_fn(16, 4, |x, _| {
        image::Rgba(if x < 8 {
            [255, 0, 0, 0]
        } else {
            [0, 255, 0, 0]
        })
    })
    .save(dir.join("weights.png"))
    .unwrap();
    std::fs::write(
        dir.join("layers.ron"),
        "(layers: [(base_color_texture: \"bright.png\"), (base_color_texture: \"dark.png\")], \
          layer_weights_texture: \"weights.png\")",
    )
    .unwrap();
    std::fs::write(
        dir.join("outside.ron"),
        "(layers: [(base_color_texture: \"../x.png\")])",
    )
    .unwrap();
    // Looking straight down at the plane, whose u runs from the image's right to its left: the
    // dark layer on the left, the bright one on the right.
    let script = |preset: &str, left: (f32, f32), right: (f32, f32)| {
        format!(
            r#"(
            size: (64, 64),
            camera: (position: (0.0, 3.0, 0.001), target: (0.0, 0.0, 0.0), fov_degrees: 30.0),
            lights: [Directional(direction: (0.0, -1.0, 0.0), intensity: 100000.0)],
            entities: [(name: "floor", shape: Some(Plane(size: 2.0)),
                        material: Some(Pom(maps: "maps", preset: "{preset}")))],
            steps: [
                Capture(name: "lit"),
                ExpectStat(capture: "lit", stat: MeanLuminance, rect: Some((4, 4, 24, 56)), min: Some({}), max: Some({})),
                ExpectStat(capture: "lit", stat: MeanLuminance, rect: Some((36, 4, 24, 56)), min: Some({}), max: Some({})),
            ],
        )"#,
            left.0, left.1, right.0, right.1
        )
    };
    let path = dir.join("layers-scene.ron");
    std::fs::write(&path, script("layers.ron", (0.0, 0.25), (0.6, 1.0))).unwrap();
    let report = pom::run_script_with(&path, &pom::RunOptions::default());
    std::fs::write(&path, script("outside.ron", (0.0, 1.0), (0.0, 1.0))).unwrap();
    let error = pom::run_script_with(&path, &pom::RunOptions::default());
    std::fs::remove_dir_all(&dir).unwrap();
    let report = report.expect("runs");
    assert_eq!(report.failures(), 0, "{report:?}");
    let message = error
        .expect_err("a layer file outside the preset's folder")
        .to_string();
    assert!(
        message.contains("../x.png") && message.contains("leads out"),
        "{message}"
    );
}
