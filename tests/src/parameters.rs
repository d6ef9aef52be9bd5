//! Materials for round-trip tests: every declared parameter set to a value that is valid and
//! differs from its default, found from the declarations, so a new parameter is covered without
//! an edit here.

use pom::ParallaxOcclusionMaterial;
use pom::material::{ParamKind, ParamValue};

/// A value of `kind` other than `default`, exactly representable in text (multiples of 1/64).
fn other_value(kind: &ParamKind, default: ParamValue) -> ParamValue {
    match (*kind, default) {
        (ParamKind::Float { min, editor, .. }, ParamValue::Float(default)) => {
            let pick = |t: f32| (((min + (editor.1 - min) * t) * 64.0).round() / 64.0).max(min);
            let first = pick(0.375);
            ParamValue::Float(if first == default { pick(0.625) } else { first })
        }
        (ParamKind::Integer { min, max, .. }, ParamValue::Integer(default)) => {
            let first = min + (max - min) / 3;
            ParamValue::Integer(if first == default { first + 1 } else { first })
        }
        (ParamKind::Toggle, ParamValue::Toggle(on)) => ParamValue::Toggle(!on),
        (ParamKind::Choice(choices), ParamValue::Choice(name)) => {
            let index = choices.iter().position(|c| c.name == name).unwrap_or(0);
            ParamValue::Choice(choices[(index + 1) % choices.len()].name)
        }
        (ParamKind::Color, _) => ParamValue::Color([0.25, 0.5, 0.75, 0.875]),
        (kind, value) => panic!("no test value for {kind:?} (default {value})"),
    }
}

/// A valid parallax material whose every parameter differs from the default.
pub fn every_parameter_changed() -> ParallaxOcclusionMaterial {
    let mut material = ParallaxOcclusionMaterial::default();
    for param in ParallaxOcclusionMaterial::PARAMETERS {
        let value = other_value(&param.spec.kind, param.default_value());
        (param.set)(&mut material, value).unwrap();
    }
    assert_eq!(material.validate(), Ok(()), "{material:?}");
    material
}

/// Asserts every declared parameter of `actual` equals `expected`'s, naming the first that
/// does not.
pub fn assert_same_parameters(
    actual: &ParallaxOcclusionMaterial,
    expected: &ParallaxOcclusionMaterial,
    through: &str,
) {
    for param in ParallaxOcclusionMaterial::PARAMETERS {
        assert_eq!(
            (param.get)(actual),
            (param.get)(expected),
            "{} did not survive {through}",
            param.name
        );
    }
}
