//! Materials for round-trip tests: every declared parameter set to a value that is valid and
//! differs from its default, found from the declarations, so a new parameter is covered without
//! an edit here.

use pom::ParallaxOcclusionMaterial;

/// A valid parallax material whose every parameter differs from the default.
pub fn every_parameter_changed() -> ParallaxOcclusionMaterial {
    let material = pom::material::every_parameter_changed(ParallaxOcclusionMaterial::PARAMETERS);
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
