//! Scene scripts: syntax errors, wrong types, unknown fields, missing files, failures midway.

use super::*;

fn script_error(file: &str) -> ScriptError {
    let error = run_script_with(corpus(file), &RunOptions::default()).unwrap_err();
    let name = Path::new(file).file_name().unwrap().to_str().unwrap();
    assert!(error.to_string().contains(name), "{error}");
    error
}

fn assert_script_parse(file: &str, at_line: usize, reason: &str) {
    match script_error(file) {
        ScriptError::Parse {
            line, reason: said, ..
        } => {
            assert_eq!(line, at_line, "{said}");
            assert!(said.contains(reason), "{said}");
        }
        other => panic!("{file}: expected ScriptError::Parse, got {other:?}"),
    }
}

fn assert_script_reference(file: &str, at_line: usize, reason: &str) {
    match script_error(file) {
        ScriptError::Reference {
            line, reason: said, ..
        } => {
            assert_eq!(line, at_line, "{said}");
            assert!(said.contains(reason), "{said}");
        }
        other => panic!("{file}: expected ScriptError::Reference, got {other:?}"),
    }
}

#[test]
fn script_syntax_error() {
    assert_script_parse("scripts/syntax_error.ron", 5, "Expected comma");
}

#[test]
fn script_wrong_type() {
    assert_script_parse("scripts/wrong_type.ron", 3, "Expected opening `(`");
}

#[test]
fn script_unknown_field() {
    assert_script_parse("scripts/unknown_field.ron", 4, "stepz");
}

#[test]
fn script_missing_steps() {
    match script_error("scripts/missing_steps.ron") {
        ScriptError::Parse { reason, .. } => assert!(reason.contains("steps"), "{reason}"),
        other => panic!("expected ScriptError::Parse, got {other:?}"),
    }
}

#[test]
fn script_camera_exposure_nan() {
    assert_script_parse(
        "scripts/exposure_nan.ron",
        5,
        "exposure NaN EV100 is outside -16..=24",
    );
}

#[test]
fn script_camera_exposure_out_of_range() {
    assert_script_parse(
        "scripts/exposure_out_of_range.ron",
        5,
        "exposure 1000000 EV100 is outside -16..=24",
    );
}

#[test]
fn script_camera_taa_out_of_range() {
    assert_script_parse(
        "scripts/taa_out_of_range.ron",
        5,
        "camera taa.current_weight is 5 but must be at most 1",
    );
}

#[test]
fn script_camera_taa_mip_bias_out_of_range() {
    assert_script_parse(
        "scripts/taa_mip_bias_out_of_range.ron",
        5,
        "camera taa.mip_bias is -4 but must be at least -2",
    );
}

#[test]
fn script_environment_bad_uniform() {
    assert_script_parse(
        "scripts/environment_bad_uniform.ron",
        5,
        "uniform takes one value or three",
    );
}

#[test]
fn script_environment_outside_folder() {
    assert_script_parse("scripts/environment_outside_folder.ron", 5, "is refused");
}

#[test]
fn script_environment_intensity_negative() {
    assert_script_parse(
        "scripts/environment_intensity_negative.ron",
        6,
        "environment settings.intensity is -1 but must be at least 0",
    );
}

#[test]
fn script_camera_fxaa_out_of_range() {
    assert_script_parse(
        "scripts/fxaa_out_of_range.ron",
        5,
        "camera fxaa.subpixel_blending is 2 but must be at most 1",
    );
}

#[test]
fn script_camera_unknown_anti_aliasing() {
    assert_script_parse("scripts/unknown_aa.ron", 5, "msaa");
}

#[test]
fn script_light_shadow_map_size_out_of_range() {
    assert_script_parse(
        "scripts/shadow_map_size_out_of_range.ron",
        7,
        "light 1 shadows: map_size 9000 is outside 16..=8192",
    );
}

#[test]
fn script_advance_past_the_step_limit() {
    assert_script_parse(
        "scripts/advance_too_long.ron",
        7,
        "step 3: Advance of 4294967295 frames is more than the 10000 one step may run",
    );
}

#[test]
fn script_light_shadow_softness_nan() {
    assert_script_parse(
        "scripts/shadow_softness_nan.ron",
        6,
        "light 0 shadows: softness NaN is outside 0..=8 texels",
    );
}

#[test]
fn script_light_shadow_softness_negative() {
    assert_script_parse(
        "scripts/shadow_softness_negative.ron",
        5,
        "light 0 shadows: softness -1 is outside 0..=8 texels",
    );
}

#[test]
fn script_unknown_tonemap() {
    assert_script_parse("scripts/unknown_tonemap.ron", 5, "filmic");
}

#[test]
fn script_missing_map_folder() {
    assert_script_reference(
        "scripts/missing_maps.ron",
        5,
        "no_such_folder/albedo.png does not exist",
    );
}

#[test]
fn script_missing_preset_file() {
    assert_script_reference(
        "scripts/missing_preset.ron",
        5,
        "preset file \"no_such_preset.ron\" does not exist",
    );
}

#[test]
fn script_missing_gltf_file() {
    assert_script_reference("scripts/missing_gltf.ron", 5, "nowhere.glb");
}

#[test]
fn script_with_an_invalid_preset() {
    // The corpus's presets live beside the scripts' folder, which only the opt-in reaches.
    let options = RunOptions {
        file_access: pom::files::FileAccess::AnyPath,
        ..RunOptions::default()
    };
    // Found when the script is loaded, before anything renders, at the entity's line.
    match run_script_with(corpus("scripts/bad_preset_inside.ron"), &options).unwrap_err() {
        ScriptError::Parse { line, reason, .. } => assert!(
            line == 5
                && reason.contains("min_over_max.ron")
                && reason.contains("min_samples (60) is greater than max_samples (4)"),
            "{line}: {reason}"
        ),
        other => panic!("expected ScriptError::Parse, got {other:?}"),
    }
}

#[test]
fn script_with_a_broken_map_file() {
    match script_error("scripts/broken_map_file.ron") {
        ScriptError::Setup { reason, .. } => assert!(
            reason.contains("broken_maps/height.png") && reason.contains("unexpected end of file"),
            "{reason}"
        ),
        other => panic!("expected ScriptError::Setup, got {other:?}"),
    }
}

#[test]
fn script_that_fails_midway_still_reports_the_steps_it_ran() {
    match script_error("scripts/fails_midway.ron") {
        ScriptError::Step {
            step,
            reason,
            report,
            ..
        } => {
            assert_eq!(step, 4);
            assert!(
                reason.contains("no pixel of a parallax surface to count"),
                "{reason}"
            );
            let numbers: Vec<usize> = report.steps.iter().map(|s| s.number).collect();
            assert_eq!(numbers, [1, 2, 3], "{report}");
            assert!(report.passed(), "{report}");
            let text = report.to_string();
            assert!(
                text.contains("fails_midway.ron step 3 ExpectStat"),
                "{text}"
            );
        }
        other => panic!("expected ScriptError::Step, got {other:?}"),
    }
}

#[test]
fn script_missing_file() {
    let error = script_error("scripts/no_such_script.ron");
    assert!(matches!(error, ScriptError::Io { .. }), "{error:?}");
}
