//! RON material presets: syntax errors, wrong types, unknown fields, missing files.

use super::*;

fn preset_error(file: &str) -> PresetError {
    let error = PomPreset::load(corpus(file)).unwrap_err();
    let name = Path::new(file).file_name().unwrap().to_str().unwrap();
    assert!(error.to_string().contains(name), "{error}");
    error
}

fn assert_preset_syntax(file: &str, at_line: usize, reason: &str) {
    match preset_error(file) {
        PresetError::Syntax {
            line, reason: said, ..
        } => {
            assert_eq!(line, at_line, "{said}");
            assert!(said.contains(reason), "{said}");
        }
        other => panic!("{file}: expected PresetError::Syntax, got {other:?}"),
    }
}

#[test]
fn preset_syntax_error() {
    assert_preset_syntax("presets/syntax_error.ron", 4, "Unexpected end of RON");
}

#[test]
fn preset_wrong_type() {
    assert_preset_syntax("presets/wrong_type.ron", 4, "Expected integer");
}

#[test]
fn preset_unknown_field() {
    assert_preset_syntax("presets/unknown_field.ron", 4, "hieght_scale");
}

#[test]
fn preset_unknown_variant() {
    assert_preset_syntax("presets/unknown_variant.ron", 3, "Fuzzy");
}

#[test]
fn preset_negative_samples() {
    assert_preset_syntax(
        "presets/negative_samples.ron",
        3,
        "Integer is out of bounds",
    );
}

#[test]
fn preset_zero_byte_file() {
    let error = preset_error("presets/empty.ron");
    assert!(
        matches!(error, PresetError::Syntax { line: 1, .. }),
        "{error:?}"
    );
}

#[test]
fn preset_min_samples_over_max() {
    match preset_error("presets/min_over_max.ron") {
        PresetError::Invalid { source, .. } => assert_eq!(
            source,
            PomMaterialError::SamplesInverted { min: 60, max: 4 }
        ),
        other => panic!("expected PresetError::Invalid, got {other:?}"),
    }
}

#[test]
fn preset_nan_height() {
    match preset_error("presets/nan_height.ron") {
        PresetError::Invalid {
            source: PomMaterialError::Limit(pom::material::LimitError::NotFinite { field, value }),
            ..
        } => {
            assert_eq!(field, "height_scale");
            assert!(value.is_nan());
        }
        other => panic!("expected PresetError::Invalid(NotFinite), got {other:?}"),
    }
}

#[test]
fn preset_missing_file() {
    let error = preset_error("presets/no_such_preset.ron");
    assert!(matches!(error, PresetError::Io { .. }), "{error:?}");
}
