//! What a game's programmer reads when a `material_parameters!` declaration is malformed: a
//! scratch crate outside the workspace declares a material whose second parameter has no doc
//! line, and its build must fail with one error naming that parameter and the fix.

use std::path::PathBuf;

use pom_tests::scratch_crate;

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

#[test]
fn a_parameter_without_a_doc_line_is_named_in_one_readable_error() {
    let scratch = PathBuf::from(env!("CARGO_TARGET_TMPDIR"));
    let dir = scratch.join("macro-errors");
    let dependency = format!(
        "[dependencies]\npom = {{ package = \"parallax-occlusion\", path = {:?}, features = [\"window\"] }}\n",
        scratch_crate::plugin_dir()
    );
    scratch_crate::write(&dir, "macro-errors", &dependency, UNDOCUMENTED_PARAMETER);
    // The scratch game's target folder and the README's features: its dependencies are built
    // already (or will be), with none built a second time for other features.
    let built = scratch_crate::build(&dir, &scratch.join("scratch-game/target"));
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
