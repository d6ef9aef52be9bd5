//! `sandbox run-script`: passing and failing scripts, and a bad file.

use std::path::Path;
use std::process::Command;

fn run(args: &[&std::ffi::OsStr]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_sandbox"))
        .arg("run-script")
        .args(args)
        .output()
        .expect("run the sandbox")
}

#[test]
fn a_failing_expectation_exits_non_zero_with_one_line_per_step() {
    let fixtures = Path::new(env!("CARGO_MANIFEST_DIR")).join("../tests/scene_fixtures");
    let output = run(&[fixtures.join("wrong_expectation.ron").as_os_str()]);
    assert!(!output.status.success());
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert_eq!(stdout.lines().count(), 3, "{stdout}");
    assert!(
        stdout.contains("step 2 ExpectStat \"plane\": FAIL"),
        "{stdout}"
    );
    assert!(
        stdout.contains("step 3 ExpectStat \"plane\": pass"),
        "{stdout}"
    );
}

#[test]
fn a_missing_script_is_one_clear_error() {
    let output = run(&[std::ffi::OsStr::new("/nonexistent/scene.ron")]);
    assert!(!output.status.success());
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(stderr.contains("/nonexistent/scene.ron"), "{stderr}");
}

#[test]
fn a_script_that_fails_midway_still_prints_the_steps_it_ran() {
    let script =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../tests/bad_inputs/scripts/fails_midway.ron");
    let output = run(&[script.as_os_str()]);
    assert!(!output.status.success());
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert_eq!(stdout.lines().count(), 3, "{stdout}");
    assert!(
        stdout.contains("fails_midway.ron step 3 ExpectStat \"before\": pass"),
        "{stdout}"
    );
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(
        stderr.contains(
            "fails_midway.ron: step 4: shadowed fraction of capture \"before\" over the whole \
             image: no pixel of a parallax surface to count"
        ),
        "{stderr}"
    );
}
