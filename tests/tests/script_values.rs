//! NaN, infinity and meaningless numbers in a scene script: each is an error when the script
//! is loaded, before anything renders, naming the line, the element and the field.

use std::path::Path;

use pom::script::parse_script;
use pom_tests::script_edits::assert_load_error;

/// A script every test changes one number of; it loads as it is.
const SCRIPT: &str = r#"(
    camera: (position: (0.0, 1.0, 3.0), target: (0.0, 0.0, 0.0), fov_degrees: 45.0),
    lights: [
        Directional(direction: (0.0, -1.0, 0.0), intensity: 100000.0),
        Spot(position: (0.0, 2.0, 0.0), direction: (0.0, -1.0, 0.0),
             inner_degrees: 10.0, outer_degrees: 30.0),
    ],
    entities: [(name: "floor", shape: Plane(size: 2.0))],
    steps: [
        Spin(entity: "floor", degrees_per_frame: 1.0),
        OrbitCamera(degrees: 15.0),
        Camera(position: (0.0, 1.0, 3.0), target: (0.0, 0.0, 0.0)),
        Capture(name: "a"),
    ],
)"#;

fn assert_error(from: &str, to: &str, at_line: usize, needles: &[&str]) {
    assert_load_error((SCRIPT, "values.ron"), (from, to), at_line, needles);
}

#[test]
fn the_unchanged_script_loads() {
    parse_script(SCRIPT, Path::new("values.ron")).unwrap();
}

#[test]
fn a_nan_field_of_view_is_an_error_naming_it() {
    assert_error(
        "fov_degrees: 45.0",
        "fov_degrees: NaN",
        2,
        &["camera fov_degrees NaN"],
    );
}

#[test]
fn a_nan_camera_position_is_an_error_naming_it() {
    assert_error(
        "position: (0.0, 1.0, 3.0), target: (0.0, 0.0, 0.0), fov",
        "position: (NaN, 1.0, 3.0), target: (0.0, 0.0, 0.0), fov",
        2,
        &["camera position [NaN, 1.0, 3.0] is not finite"],
    );
}

#[test]
fn a_zero_directional_light_direction_is_an_error_naming_the_light() {
    assert_error(
        "Directional(direction: (0.0, -1.0, 0.0)",
        "Directional(direction: (0.0, 0.0, 0.0)",
        4,
        &["light 0: direction [0.0, 0.0, 0.0] has no length"],
    );
}

#[test]
fn an_infinite_light_intensity_is_an_error_naming_the_light() {
    assert_error(
        "intensity: 100000.0",
        "intensity: inf",
        4,
        &["light 0: intensity inf"],
    );
}

#[test]
fn a_light_over_the_output_limit_is_an_error_naming_it() {
    assert_error(
        "intensity: 100000.0",
        "intensity: 1e38",
        4,
        &["light 0: color [1.0, 1.0, 1.0] × intensity 1e38 is over the limit"],
    );
}

#[test]
fn a_spot_cone_of_170_inside_minus_10_is_an_error_naming_the_field() {
    assert_error(
        "inner_degrees: 10.0, outer_degrees: 30.0",
        "inner_degrees: 170.0, outer_degrees: -10.0",
        6,
        &["light 1: outer_degrees -10 is outside 0 < outer ≤ 90"],
    );
    assert_error(
        "inner_degrees: 10.0",
        "inner_degrees: 40.0",
        6,
        &["light 1: inner_degrees 40 is outside 0 ≤ inner ≤ outer_degrees 30"],
    );
}

#[test]
fn a_nan_plane_size_is_an_error_naming_the_entity() {
    assert_error(
        "Plane(size: 2.0)",
        "Plane(size: NaN)",
        8,
        &["entity \"floor\": size NaN is not finite and > 0"],
    );
}

#[test]
fn a_nan_spin_is_an_error_naming_the_step() {
    assert_error(
        "degrees_per_frame: 1.0",
        "degrees_per_frame: NaN",
        10,
        &["step 1 (Spin): degrees_per_frame [NaN] is not finite"],
    );
}

#[test]
fn an_infinite_orbit_is_an_error_naming_the_step() {
    assert_error(
        "OrbitCamera(degrees: 15.0)",
        "OrbitCamera(degrees: inf)",
        11,
        &["step 2 (OrbitCamera): degrees [inf] is not finite"],
    );
}

#[test]
fn a_camera_step_looking_at_its_own_position_is_an_error_naming_the_step() {
    assert_error(
        "Camera(position: (0.0, 1.0, 3.0), target: (0.0, 0.0, 0.0))",
        "Camera(position: (0.0, 1.0, 3.0), target: (0.0, 1.0, 3.0))",
        12,
        &["step 3 (Camera): target [0.0, 1.0, 3.0] is its position"],
    );
}
