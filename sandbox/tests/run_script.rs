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

/// A script named by its bare file name from its own folder (`Path::parent` of "twice.ron" is
/// the empty path) finds its reference there, blessing it and then passing.
#[test]
fn a_script_named_without_a_folder_runs_from_its_own() {
    let fixtures = Path::new(env!("CARGO_MANIFEST_DIR")).join("../tests/scene_fixtures");
    let dir = std::env::temp_dir().join(format!("sandbox-bare-script-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::copy(fixtures.join("determinism.ron"), dir.join("twice.ron")).unwrap();
    for args in [&["--bless", "twice.ron"][..], &["twice.ron"]] {
        let output = Command::new(env!("CARGO_BIN_EXE_sandbox"))
            .arg("run-script")
            .args(args)
            .current_dir(&dir)
            .output()
            .expect("run the sandbox");
        let stdout = String::from_utf8_lossy(&output.stdout);
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert!(output.status.success(), "{args:?}: {stdout}\n{stderr}");
    }
    assert!(dir.join("twice.png").is_file(), "the blessed reference");
    std::fs::remove_dir_all(&dir).unwrap();
}
