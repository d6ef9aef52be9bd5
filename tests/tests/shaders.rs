//! Every WGSL file in the plugin parses and validates with naga.

use std::path::{Path, PathBuf};

fn wgsl_files(dir: &Path, found: &mut Vec<PathBuf>) {
    let entries = std::fs::read_dir(dir).unwrap_or_else(|e| panic!("{}: {e}", dir.display()));
    for entry in entries {
        let path = entry.unwrap().path();
        if path.is_dir() {
            wgsl_files(&path, found);
        } else if path.extension().is_some_and(|ext| ext == "wgsl") {
            found.push(path);
        }
    }
}

#[test]
fn every_wgsl_file_validates() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../plugin/src");
    let mut files = Vec::new();
    wgsl_files(&root, &mut files);
    assert!(
        !files.is_empty(),
        "no WGSL files under {}: did they move?",
        root.display()
    );
    let mut failures = Vec::new();
    for path in &files {
        let source = std::fs::read_to_string(path).unwrap();
        let module = match naga::front::wgsl::parse_str(&source) {
            Ok(module) => module,
            Err(error) => {
                failures.push(error.emit_to_string_with_path(&source, &path.display().to_string()));
                continue;
            }
        };
        let mut validator = naga::valid::Validator::new(
            naga::valid::ValidationFlags::all(),
            naga::valid::Capabilities::default(),
        );
        if let Err(error) = validator.validate(&module) {
            failures.push(error.emit_to_string_with_path(&source, &path.display().to_string()));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
    eprintln!("validated {} WGSL files", files.len());
}

#[test]
fn the_renderer_uses_the_validated_source() {
    // The pipeline compiles the string embedded at build time; make sure it is the file on disk.
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../plugin/src/render/forward.wgsl");
    assert_eq!(
        std::fs::read_to_string(path).unwrap(),
        pom::render::FORWARD_SHADER_SOURCE
    );
}
