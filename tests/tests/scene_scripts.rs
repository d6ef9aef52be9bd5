//! Every scene script under tests/scenes runs and passes, on the forward and the deferred path
//! (every capture of the deferred run shaded deferred, not on a silent forward fallback);
//! a wrong expectation fails readably;
//! the same script gives the same pixels twice. `UPDATE_GOLDENS=1` blesses missing references.

use std::path::{Path, PathBuf};

use pom::script::{CapturePath, Outcome, Report};
use pom::{RenderPath, RunOptions, ScriptError, run_script_with};
use pom_tests::PATHS_AGREE_MEAN;

fn scenes() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes")
}

fn bless() -> bool {
    std::env::var_os("UPDATE_GOLDENS").is_some_and(|v| v != "0" && !v.is_empty())
}

#[test]
fn every_shipped_script_passes() {
    let mut scripts: Vec<PathBuf> = std::fs::read_dir(scenes())
        .unwrap()
        .map(|entry| entry.unwrap().path())
        .filter(|path| path.extension().is_some_and(|ext| ext == "ron"))
        .collect();
    scripts.sort();
    assert!(
        scripts.len() >= 7,
        "found only {} scripts in {}",
        scripts.len(),
        scenes().display()
    );
    let mut failures = Vec::new();
    // Each script on both paths, every capture shaded on the path asked for: the references
    // (made forward on this driver) hold for the deferred frame too, within FLIP mean
    // PATHS_AGREE_MEAN.
    for (path, shaded_on) in [
        (RenderPath::Forward, CapturePath::Forward),
        (RenderPath::Deferred, CapturePath::Deferred),
    ] {
        let options = RunOptions {
            bless: bless() && path == RenderPath::Forward,
            out_dir: None,
            path,
            // The scripts share the repository's assets, outside their own folder.
            file_access: pom::files::FileAccess::AnyPath,
        };
        for script in &scripts {
            match run_script_with(script, &options) {
                Ok(report) => {
                    eprint!("{report}");
                    if !report.passed() {
                        failures.push(format!(
                            "{} ({path}): {} failed expectations",
                            script.display(),
                            report.failures()
                        ));
                    }
                    failures.extend(captures_off_path(&report, path, shaded_on));
                    if path == RenderPath::Deferred {
                        failures.extend(
                            reference_means(&report)
                                .filter(|mean| *mean > PATHS_AGREE_MEAN)
                                .map(|mean| {
                                    format!(
                                        "{} (deferred): FLIP mean {mean} against a reference",
                                        script.display()
                                    )
                                }),
                        );
                    }
                }
                Err(error) => failures.push(error.to_string()),
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// What of a script run on `path` was not shaded on `expected`: each capture whose frame ran on
/// another path (a deferred request falls back to forward silently, with the same images), or
/// the script itself if it captured nothing, so that no frame of it was checked.
fn captures_off_path(report: &Report, path: RenderPath, expected: CapturePath) -> Vec<String> {
    let script = report.script.display();
    let mut captures = report.capture_paths().peekable();
    if captures.peek().is_none() {
        return vec![format!(
            "{script} ({path}): no capture, so no frame checked"
        )];
    }
    captures
        .filter(|(_, ran)| *ran != expected)
        .map(|(step, ran)| {
            format!(
                "{script} ({path}): step {} {} ran {ran}",
                step.number, step.description
            )
        })
        .collect()
}

/// The FLIP means of a report's reference comparisons ("FLIP mean 0.0012 (max ...").
fn reference_means(report: &Report) -> impl Iterator<Item = f32> + '_ {
    report.steps.iter().filter_map(|step| match &step.outcome {
        Outcome::Passed(detail) | Outcome::Failed(detail) => detail
            .strip_prefix("FLIP mean ")?
            .split_whitespace()
            .next()?
            .parse()
            .ok(),
        _ => None,
    })
}

fn fixture(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("scene_fixtures")
        .join(name)
}

#[test]
fn a_wrong_expectation_fails_with_a_readable_report() {
    let report = run_script_with(fixture("wrong_expectation.ron"), &RunOptions::default()).unwrap();
    assert!(!report.passed());
    assert_eq!(report.failures(), 1);
    let text = report.to_string();
    assert!(
        text.contains("ExpectStat \"plane\": FAIL (mean luminance = "),
        "{text}"
    );
    assert!(text.contains("bounds 0.9..=1"), "{text}");
}

#[test]
fn the_same_script_gives_the_same_pixels() {
    let dir = std::env::temp_dir().join(format!("pom-determinism-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let script = dir.join("twice.ron");
    std::fs::copy(fixture("determinism.ron"), &script).unwrap();
    // The first run writes the reference, the second must match it exactly (FLIP 0).
    let first = run_script_with(
        &script,
        &RunOptions {
            bless: true,
            ..RunOptions::default()
        },
    )
    .unwrap();
    assert!(matches!(
        first.steps.last().unwrap().outcome,
        Outcome::Blessed(_)
    ));
    let second = run_script_with(&script, &RunOptions::default()).unwrap();
    assert!(second.passed(), "{second}");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn lights_with_shadow_settings_run() {
    let report = run_script_with(fixture("light_shadows.ron"), &RunOptions::default()).unwrap();
    assert!(report.passed(), "{report}");
}

fn error_of(source: &str) -> String {
    let dir = std::env::temp_dir().join(format!(
        "pom-script-errors-{}-{}",
        std::process::id(),
        source.len()
    ));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("bad.ron");
    std::fs::write(&path, source).unwrap();
    let error = run_script_with(&path, &RunOptions::default()).unwrap_err();
    std::fs::remove_dir_all(&dir).unwrap();
    assert!(!matches!(error, ScriptError::Step { .. }), "{error}");
    error.to_string()
}

const CAMERA: &str = "camera: (position: (0.0, 1.0, 1.0), target: (0.0, 0.0, 0.0))";

#[test]
fn bad_scripts_name_the_file_line_and_column() {
    let unknown = error_of(&format!("(\n  {CAMERA},\n  stepz: [],\n)"));
    assert!(
        unknown.contains("bad.ron:3:") && unknown.contains("stepz"),
        "{unknown}"
    );
    let wrong_type = error_of(&format!(
        "(\n  {CAMERA},\n  size: \"big\",\n  steps: [],\n)"
    ));
    assert!(wrong_type.contains("bad.ron:3:"), "{wrong_type}");
    let syntax = error_of(&format!("(\n  {CAMERA},\n  steps: [Advance(frames: 1)\n"));
    assert!(syntax.contains("bad.ron:"), "{syntax}");
    let ghost = error_of(&format!(
        "(\n  {CAMERA},\n  steps: [\n    Set(entity: \"ghost\", material: ()),\n  ],\n)"
    ));
    assert!(
        ghost.contains("bad.ron:4:17") && ghost.contains("no entity is named \"ghost\""),
        "{ghost}"
    );
    let missing_file = error_of(&format!(
        "(\n  {CAMERA},\n  entities: [(name: \"x\", gltf: Some(\"nowhere.glb\"))],\n  steps: [],\n)"
    ));
    assert!(
        missing_file.contains("bad.ron:3:") && missing_file.contains("nowhere.glb"),
        "{missing_file}"
    );
    let tiny_shadow_map = error_of(&format!(
        "(\n  {CAMERA},\n  lights: [Point(position: (0.0, 1.0, 0.0),\n    shadows: (map_size: 0))],\n  steps: [],\n)"
    ));
    assert!(
        tiny_shadow_map.contains("bad.ron:4:15")
            && tiny_shadow_map.contains("light 0 shadows: map_size 0 is outside 16..=8192"),
        "{tiny_shadow_map}"
    );
    let missing_capture = error_of(&format!(
        "(\n  {CAMERA},\n  steps: [ExpectMatch(capture: \"never\", reference: \"r.png\")],\n)"
    ));
    assert!(
        missing_capture.contains("no capture named \"never\""),
        "{missing_capture}"
    );
}
