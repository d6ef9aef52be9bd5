//! Expectations that could pass on nothing are errors when the script is loaded, naming the
//! line, the step and the field: rectangles outside the image, empty or overflowing, bounds
//! missing or inverted, orders over fewer than two captures, tolerances that mean nothing, and
//! statistics over captures without the debug view they read.

use std::path::Path;

use pom::script::parse_script;
use pom_tests::script_edits::assert_load_error;

/// A script every test changes one expectation of; it loads as it is.
const SCRIPT: &str = r#"(
    size: (64, 48),
    camera: (position: (0.0, 1.0, 3.0), target: (0.0, 0.0, 0.0)),
    steps: [
        Capture(name: "lit"),
        Capture(name: "uv", debug_view: uv),
        Capture(name: "uv2", debug_view: uv),
        Capture(name: "shadow", debug_view: shadow),
        ExpectStat(capture: "lit", stat: MeanLuminance, rect: (0, 0, 64, 48), min: 0.1),
        ExpectStat(capture: "shadow", stat: ShadowedFraction, max: 0.5),
        ExpectMonotonic(captures: ["uv", "uv2"], stat: NormalMappingFraction),
        ExpectMatch(capture: "lit", reference: "lit.png",
            tolerance: (mean: 0.01, percentile: 0.99, percentile_max: 0.1)),
    ],
)"#;

fn assert_error(from: &str, to: &str, at_line: usize, needles: &[&str]) {
    assert_load_error((SCRIPT, "expectations.ron"), (from, to), at_line, needles);
}

#[test]
fn the_unchanged_script_loads() {
    parse_script(SCRIPT, Path::new("expectations.ron")).unwrap();
}

#[test]
fn a_rectangle_outside_the_image_is_an_error() {
    assert_error(
        "rect: (0, 0, 64, 48)",
        "rect: (100, 100, 10, 10)",
        9,
        &[
            "step 5 (ExpectStat): rect (100, 100, 10, 10) (x, y, width, height) reaches (110, 110), outside the 64×48 image",
        ],
    );
}

#[test]
fn a_rectangle_reaching_past_the_image_is_an_error() {
    assert_error(
        "rect: (0, 0, 64, 48)",
        "rect: (0, 0, 65, 48)",
        9,
        &["reaches (65, 48), outside the 64×48 image"],
    );
}

#[test]
fn an_empty_rectangle_is_an_error() {
    assert_error(
        "rect: (0, 0, 64, 48)",
        "rect: (4, 4, 0, 10)",
        9,
        &["rect (4, 4, 0, 10) (x, y, width, height) has no pixels"],
    );
}

#[test]
fn a_rectangle_overflowing_u32_is_an_error() {
    assert_error(
        "rect: (0, 0, 64, 48)",
        "rect: (4294967295, 0, 2, 10)",
        9,
        &["reaches (4294967297, 10), outside the 64×48 image"],
    );
}

#[test]
fn a_monotonic_rectangle_outside_the_image_is_an_error() {
    assert_error(
        "ExpectMonotonic(captures: [\"uv\", \"uv2\"], stat: NormalMappingFraction)",
        "ExpectMonotonic(captures: [\"uv\", \"uv2\"], stat: NormalMappingFraction, rect: (60, 0, 8, 8))",
        11,
        &[
            "step 7 (ExpectMonotonic): rect (60, 0, 8, 8)",
            "outside the 64×48 image",
        ],
    );
}

#[test]
fn a_stat_without_bounds_is_an_error() {
    assert_error(
        "stat: ShadowedFraction, max: 0.5",
        "stat: ShadowedFraction",
        10,
        &["step 6 (ExpectStat): gives neither min nor max: it would pass on any value"],
    );
}

#[test]
fn a_stat_with_min_above_max_is_an_error() {
    assert_error(
        "stat: ShadowedFraction, max: 0.5",
        "stat: ShadowedFraction, min: 0.6, max: 0.5",
        10,
        &["step 6 (ExpectStat): min 0.6 is above max 0.5: no value can pass"],
    );
}

#[test]
fn a_nan_bound_is_an_error() {
    assert_error(
        "stat: ShadowedFraction, max: 0.5",
        "stat: ShadowedFraction, max: NaN",
        10,
        &["step 6 (ExpectStat): max NaN is not a finite number"],
    );
}

#[test]
fn an_order_over_one_capture_is_an_error() {
    assert_error(
        "captures: [\"uv\", \"uv2\"]",
        "captures: [\"uv\"]",
        11,
        &["step 7 (ExpectMonotonic): captures [\"uv\"] order nothing: an order needs at least 2"],
    );
    assert_error(
        "captures: [\"uv\", \"uv2\"]",
        "captures: []",
        11,
        &["captures [] order nothing"],
    );
}

#[test]
fn a_nan_tolerance_is_an_error() {
    assert_error(
        "mean: 0.01",
        "mean: NaN",
        13,
        &["step 8 (ExpectMatch): tolerance mean NaN is not a finite number ≥ 0"],
    );
}

#[test]
fn a_percentile_above_one_is_an_error() {
    assert_error(
        "percentile: 0.99",
        "percentile: 2.0",
        13,
        &["step 8 (ExpectMatch): tolerance percentile 2 is outside 0..=1"],
    );
    // Written as a percentage, it would print as "p9500".
    assert_error(
        "percentile: 0.99",
        "percentile: 95.0",
        13,
        &["percentile 95 is outside 0..=1 (a fraction: 0.99 is the 99th percentile)"],
    );
}

#[test]
fn a_negative_percentile_max_is_an_error() {
    assert_error(
        "percentile_max: 0.1",
        "percentile_max: -0.1",
        13,
        &["step 8 (ExpectMatch): tolerance percentile_max -0.1 is not a finite number ≥ 0"],
    );
}

#[test]
fn a_partial_tolerance_is_an_error() {
    let text = SCRIPT.replacen("percentile: 0.99, percentile_max: 0.1", "", 1);
    let error = parse_script(&text, Path::new("expectations.ron")).unwrap_err();
    assert!(
        error.to_string().contains("percentile"),
        "a tolerance gives all three fields: {error}"
    );
}

#[test]
fn a_statistic_over_a_capture_without_its_debug_view_is_an_error_at_load() {
    assert_error(
        "ExpectStat(capture: \"shadow\", stat: ShadowedFraction",
        "ExpectStat(capture: \"lit\", stat: ShadowedFraction",
        10,
        &[
            "step 6 (ExpectStat): shadowed fraction needs capture \"lit\" taken with debug_view: shadow, but it was taken with no debug view",
        ],
    );
    assert_error(
        "captures: [\"uv\", \"uv2\"]",
        "captures: [\"uv\", \"shadow\"]",
        11,
        &["needs capture \"shadow\" taken with debug_view: uv, but it was taken with shadow"],
    );
}

#[test]
fn a_uv_shift_baseline_without_the_uv_view_is_an_error_at_load() {
    assert_error(
        "stat: NormalMappingFraction",
        "stat: UvShift(baseline: \"lit\")",
        11,
        &["needs capture \"lit\" taken with debug_view: uv"],
    );
}

#[test]
fn the_debug_view_a_statistic_names_is_the_one_a_capture_accepts() {
    // The spelling the error asks for loads.
    let text = SCRIPT.replacen(
        "Capture(name: \"lit\")",
        "Capture(name: \"lit\", debug_view: shadow)",
        1,
    );
    let text = text.replacen("stat: MeanLuminance", "stat: ShadowedFraction", 1);
    parse_script(&text, Path::new("expectations.ron")).unwrap();
}
