//! Writes that fail (a full device, a read-only folder, a file size limit) end in an error
//! naming the file and a non-zero exit, never in "wrote" or "blessed", and never leave a
//! truncated file in place of a good one. The tests that render need a Vulkan driver.

mod common;

use std::path::Path;
use std::process::{Command, Output};

use common::*;

/// A scene script (a copy of the determinism fixture) in `dir`, whose one `ExpectMatch`
/// compares against `twice.png` beside it; `size` is its image size.
fn script_in(dir: &TempDir, size: u32) -> std::path::PathBuf {
    let fixture = Path::new(env!("CARGO_MANIFEST_DIR")).join("../tests/scene_fixtures");
    let text = std::fs::read_to_string(fixture.join("determinism.ron")).unwrap();
    let script = dir.join("twice.ron");
    std::fs::write(
        &script,
        text.replace("(64, 64)", &format!("({size}, {size})")),
    )
    .unwrap();
    script
}

/// `link` made a symbolic link to `/dev/full`, where every write fails with ENOSPC.
fn link_to_full_device(link: &Path) {
    std::os::unix::fs::symlink("/dev/full", link).unwrap();
}

/// Asserts a failed run whose stderr names `file` and `reason` and whose stdout does not claim
/// the file was written or blessed.
fn assert_write_failed(output: &Output, file: &str, reason: &str) {
    let stdout = String::from_utf8_lossy(&output.stdout);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(!output.status.success(), "exited 0\n{stdout}\n{stderr}");
    assert!(
        stderr.contains(file) && stderr.contains(reason),
        "stderr does not name {file} and {reason:?}: {stderr}"
    );
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert!(
        !stdout.contains("wrote") && !stdout.contains("blessed"),
        "claims success: {stdout}"
    );
}

/// Whether this process can create files in a folder it made read-only (it can as root), so a
/// read-only folder cannot make a write fail.
fn read_only_folders_stop_writes(dir: &Path) -> bool {
    let probe = dir.join("probe");
    let stopped = std::fs::write(&probe, b"").is_err();
    let _ = std::fs::remove_file(&probe);
    if !stopped {
        println!("note: running as root, where a read-only folder does not stop writes: skipped");
    }
    stopped
}

/// A read-only folder `name` in `dir`.
fn read_only_folder(dir: &TempDir, name: &str) -> std::path::PathBuf {
    use std::os::unix::fs::PermissionsExt;
    let folder = dir.join(name);
    std::fs::create_dir(&folder).unwrap();
    std::fs::set_permissions(&folder, std::fs::Permissions::from_mode(0o555)).unwrap();
    folder
}

#[test]
fn render_to_a_full_device_fails_naming_the_file() {
    let dir = TempDir::new("render-full");
    let out = dir.join("x.png");
    link_to_full_device(&out);
    let output = sandbox(&["render", "--size", "16x16", "--out", path_arg(&out)]);
    assert_write_failed(&output, "x.png", "No space left on device");
    assert!(std::fs::symlink_metadata(&out).unwrap().is_symlink());
}

#[test]
fn render_into_a_read_only_folder_fails_naming_the_file() {
    let dir = TempDir::new("render-read-only");
    let folder = read_only_folder(&dir, "locked");
    if !read_only_folders_stop_writes(&folder) {
        return;
    }
    let out = folder.join("x.png");
    let output = sandbox(&["render", "--size", "16x16", "--out", path_arg(&out)]);
    assert_write_failed(&output, "locked/x.png", "Permission denied");
    assert!(!out.exists());
}

#[test]
fn blessing_onto_a_full_device_fails_naming_the_reference() {
    let dir = TempDir::new("bless-full");
    let script = script_in(&dir, 64);
    link_to_full_device(&dir.join("twice.png"));
    // The link leads out of the script's folder: allowed here, the write is what is tested.
    let output = sandbox(&[
        "run-script",
        "--bless",
        "--allow-outside-paths",
        path_arg(&script),
    ]);
    assert_write_failed(&output, "twice.png", "No space left on device");
}

#[test]
fn blessing_into_a_read_only_folder_fails_naming_the_reference() {
    let dir = TempDir::new("bless-read-only");
    let script = script_in(&dir, 64);
    let folder = read_only_folder(&dir, "locked");
    if !read_only_folders_stop_writes(&folder) {
        return;
    }
    let text = std::fs::read_to_string(&script).unwrap();
    std::fs::write(
        &script,
        text.replace("\"twice.png\"", "\"locked/twice.png\""),
    )
    .unwrap();
    let output = sandbox(&["run-script", "--bless", path_arg(&script)]);
    assert_write_failed(&output, "locked/twice.png", "Permission denied");
}

#[test]
fn a_failure_image_that_cannot_be_written_is_an_error_naming_it() {
    let dir = TempDir::new("actual-full");
    let script = script_in(&dir, 64);
    let out = dir.join("failures");
    std::fs::create_dir(&out).unwrap();
    link_to_full_device(&out.join("twice-actual.png"));
    // No reference yet: the run fails and writes the capture for a look.
    let output = sandbox(&["run-script", "--out", path_arg(&out), path_arg(&script)]);
    assert_write_failed(&output, "twice-actual.png", "No space left on device");
}

#[test]
fn a_failed_bless_leaves_the_earlier_reference_as_it_was() {
    let dir = TempDir::new("bless-keeps");
    let script = script_in(&dir, 64);
    assert_success(&sandbox(&["run-script", "--bless", path_arg(&script)]));
    let reference = dir.join("twice.png");
    let good = std::fs::read(&reference).unwrap();
    // A new size makes --bless rewrite the reference; a file size limit of 512 bytes makes
    // that write fail (EFBIG, with SIGXFSZ ignored so the process sees the error), even as
    // root.
    script_in(&dir, 48);
    let output = Command::new("sh")
        .args([
            "-c",
            "ulimit -f 1; trap '' XFSZ; exec \"$0\" \"$@\"",
            env!("CARGO_BIN_EXE_sandbox"),
            "run-script",
            "--bless",
            path_arg(&script),
        ])
        .output()
        .unwrap();
    assert_write_failed(&output, "twice.png", "File too large");
    assert_eq!(
        std::fs::read(&reference).unwrap(),
        good,
        "the reference changed"
    );
    let mut left: Vec<String> = std::fs::read_dir(dir.join(""))
        .unwrap()
        .map(|entry| entry.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    left.sort();
    assert_eq!(
        left,
        ["twice.png", "twice.ron"],
        "a temporary file was left"
    );
}
