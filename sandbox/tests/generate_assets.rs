//! The shipped assets are exactly what `sandbox generate-assets` makes.

use std::path::Path;
use std::process::Command;

#[test]
fn the_committed_assets_are_reproduced_byte_for_byte() {
    let out = std::env::temp_dir().join(format!("pom-generate-assets-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&out);
    let output = Command::new(env!("CARGO_BIN_EXE_sandbox"))
        .args(["generate-assets", "--out"])
        .arg(&out)
        .output()
        .expect("run the sandbox");
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let shipped = Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets");
    let written: Vec<String> = String::from_utf8_lossy(&output.stdout)
        .lines()
        .filter_map(|line| line.strip_prefix("wrote "))
        .map(str::to_owned)
        .collect();
    assert_eq!(
        written.len(),
        17,
        "5 materials × 3 maps + the street corner by day and at night"
    );
    for file in &written {
        let relative = Path::new(file)
            .strip_prefix(&out)
            .expect("written under --out");
        let fresh = std::fs::read(file).expect("generated file");
        let committed = std::fs::read(shipped.join(relative))
            .unwrap_or_else(|e| panic!("assets/{} is missing: {e}", relative.display()));
        assert!(
            fresh == committed,
            "assets/{} differs from what the generator makes now: run `cargo run -p sandbox -- generate-assets` and commit",
            relative.display()
        );
    }
    std::fs::remove_dir_all(&out).expect("clean up");
}
