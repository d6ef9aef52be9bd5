//! Every statistic and expectation of the scene-script format fails when what it checks is
//! wrong, the debug-view statistics count only the parallax surface (not the background), a
//! statistic with nothing to count is an error, and blessing leaves no stale failure images.

use std::path::{Path, PathBuf};

use pom::files::FileAccess;
use pom::script::{Outcome, Report};
use pom::{RunOptions, ScriptError, run_script_with};

/// A brick floor seen from low down: the background above its far edge fills the top half of
/// the image, the floor the bottom half (normal mapping only in its far rows, the LOD band
/// across rows 36..42, the full march below). The floor is captured flat and deep in the uv view, lit, and in the
/// shadow view without and with self-shadowing under a grazing light.
fn scene(steps: &str) -> String {
    let bricks = Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets/bricks");
    format!(
        r#"(
    size: (64, 48),
    camera: (position: (0.0, 0.5, 1.5), target: (0.0, 0.0, -1.0), fov_degrees: 60.0),
    lights: [Directional(direction: (-1.0, -0.3, 0.0), intensity: 100000.0)],
    entities: [(name: "floor", shape: Plane(size: 4.0, tiling: 4.0),
                material: Pom(maps: {bricks:?}, set: (shadows: off)))],
    steps: [
        Set(entity: "floor", material: (height_scale: 0.0)),
        Capture(name: "flat", debug_view: uv),
        Set(entity: "floor", material: (height_scale: 0.08)),
        Capture(name: "deep", debug_view: uv),
        Capture(name: "lit"),
        Capture(name: "unshadowed", debug_view: shadow),
        Set(entity: "floor", material: (shadows: hard)),
        Capture(name: "shadowed", debug_view: shadow),
        {steps}
    ],
)"#
    )
}

/// The number of the first step after the scene's eight.
const FIRST: usize = 9;

/// A fresh folder for one test's files.
fn folder(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("pom-statistics-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn run_in(dir: &Path, text: &str, bless: bool) -> Result<Report, ScriptError> {
    let script = dir.join("scene.ron");
    std::fs::write(&script, text).unwrap();
    let options = RunOptions {
        bless,
        file_access: FileAccess::AnyPath,
        ..RunOptions::default()
    };
    run_script_with(&script, &options)
}

/// The outcome of step `number` of `report`.
fn outcome(report: &Report, number: usize) -> &Outcome {
    &report.steps[number - 1].outcome
}

#[test]
fn every_statistic_fails_when_its_bound_is_wrong() {
    let dir = folder("wrong");
    let report = run_in(
        &dir,
        &scene(
            r#"ExpectStat(capture: "lit", stat: MeanLuminance, min: 0.99),
        ExpectStat(capture: "deep", stat: LodBandFraction, min: 0.99),
        ExpectStat(capture: "deep", stat: NormalMappingFraction, min: 0.99),
        ExpectStat(capture: "shadowed", stat: ShadowedFraction, max: 0.0),
        ExpectStat(capture: "deep", stat: UvShift(baseline: "flat"), max: 0.0),
        ExpectMonotonic(captures: ["flat", "deep"], stat: UvShift(baseline: "flat"), increasing: false),
        ExpectMonotonic(captures: ["unshadowed", "shadowed"], stat: ShadowedFraction, rect: (0, 24, 64, 24), increasing: false),"#,
        ),
        false,
    )
    .unwrap();
    std::fs::remove_dir_all(&dir).unwrap();
    for number in FIRST..FIRST + 7 {
        assert!(
            matches!(outcome(&report, number), Outcome::Failed(_)),
            "step {number} should fail:\n{report}"
        );
    }
}

#[test]
fn the_same_statistics_pass_when_their_bounds_are_right() {
    let dir = folder("right");
    let report = run_in(
        &dir,
        &scene(
            r#"ExpectStat(capture: "lit", stat: MeanLuminance, min: 0.01, max: 0.99),
        ExpectStat(capture: "deep", stat: NormalMappingFraction, rect: (0, 24, 64, 8), min: 0.9),
        ExpectStat(capture: "deep", stat: NormalMappingFraction, rect: (0, 42, 64, 6), max: 0.01),
        ExpectStat(capture: "deep", stat: LodBandFraction, min: 0.05, max: 0.5),
        ExpectStat(capture: "shadowed", stat: ShadowedFraction, min: 0.01, max: 0.9),
        ExpectStat(capture: "deep", stat: UvShift(baseline: "flat"), min: 0.001),
        ExpectMonotonic(captures: ["flat", "deep"], stat: UvShift(baseline: "flat")),
        ExpectMonotonic(captures: ["unshadowed", "shadowed"], stat: ShadowedFraction, rect: (0, 24, 64, 24)),"#,
        ),
        false,
    )
    .unwrap();
    std::fs::remove_dir_all(&dir).unwrap();
    assert!(report.passed(), "{report}");
}

#[test]
fn the_background_is_not_counted_as_shadowed() {
    // Without self-shadowing no floor pixel is in shadow; the dark background above the floor
    // is no surface of the material and must not count.
    let dir = folder("background");
    let report = run_in(
        &dir,
        &scene(r#"ExpectStat(capture: "unshadowed", stat: ShadowedFraction, max: 0.0),"#),
        false,
    )
    .unwrap();
    std::fs::remove_dir_all(&dir).unwrap();
    assert!(report.passed(), "{report}");
}

#[test]
fn a_statistic_with_nothing_to_count_is_an_error() {
    // The top rows show only the background: no parallax surface to measure.
    let dir = folder("nothing");
    let error = run_in(
        &dir,
        &scene(
            r#"ExpectStat(capture: "unshadowed", stat: ShadowedFraction, rect: (0, 0, 64, 2), max: 0.5),"#,
        ),
        false,
    )
    .unwrap_err();
    std::fs::remove_dir_all(&dir).unwrap();
    let message = error.to_string();
    assert!(
        matches!(error, ScriptError::Step { step: FIRST, .. })
            && message.contains(
                "shadowed fraction of capture \"unshadowed\" over rect (0, 0, 64, 2): no pixel of a parallax surface to count"
            ),
        "{message}"
    );
}

#[test]
fn a_wrong_reference_fails_and_blessing_it_removes_the_failure_images() {
    let dir = folder("bless");
    let reference = dir.join("lit.png");
    image::RgbaImage::from_pixel(64, 48, image::Rgba([0, 0, 0, 255]))
        .save(&reference)
        .unwrap();
    let text = scene(r#"ExpectMatch(capture: "lit", reference: "lit.png"),"#);
    let failed = run_in(&dir, &text, false).unwrap();
    assert!(
        matches!(outcome(&failed, FIRST), Outcome::Failed(_)),
        "{failed}"
    );
    let (actual, difference) = (dir.join("lit-actual.png"), dir.join("lit-difference.png"));
    assert!(actual.exists() && difference.exists());
    let blessed = run_in(&dir, &text, true).unwrap();
    assert!(
        matches!(outcome(&blessed, FIRST), Outcome::Blessed(_)),
        "{blessed}"
    );
    let stale = [&actual, &difference].map(|path| path.exists());
    let passed = run_in(&dir, &text, false).unwrap();
    std::fs::remove_dir_all(&dir).unwrap();
    assert_eq!(
        stale,
        [false, false],
        "failure images left beside the reference"
    );
    assert!(passed.passed(), "{passed}");
}
