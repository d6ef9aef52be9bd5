//! A sandbox binary copied to another machine works there: nothing it runs reads a path baked
//! in at build time (`env!("CARGO_MANIFEST_DIR")`), which points into the build tree. Tests may.
//! The sandbox's own sources and the library's, outside their `#[cfg(test)]` items, are read.

use std::path::{Path, PathBuf};

const BUILD_TREE_PATH: &str = "CARGO_MANIFEST_DIR";

/// Every `.rs` file under `dir`.
fn rust_files(dir: &Path, files: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            rust_files(&path, files);
        } else if path.extension().is_some_and(|ext| ext == "rs") {
            files.push(path);
        }
    }
}

/// `source` without its `#[cfg(test)]` items (a `mod x;` line or a braced item), and the names
/// of the test-only modules it declares in files of their own.
fn without_test_items(source: &str) -> (String, Vec<String>) {
    let mut kept = String::new();
    let mut test_modules = Vec::new();
    let mut lines = source.lines();
    while let Some(line) = lines.next() {
        if line.trim() != "#[cfg(test)]" {
            kept.push_str(line);
            kept.push('\n');
            continue;
        }
        let Some(item) = lines.next() else { break };
        if let Some(name) = item
            .trim()
            .strip_prefix("mod ")
            .and_then(|rest| rest.strip_suffix(';'))
        {
            test_modules.push(name.trim().to_owned());
            continue;
        }
        // A braced item: skip to the line that closes it.
        let mut depth = item.matches('{').count() as i64 - item.matches('}').count() as i64;
        while depth > 0 {
            let Some(inner) = lines.next() else { break };
            depth += inner.matches('{').count() as i64 - inner.matches('}').count() as i64;
        }
    }
    (kept, test_modules)
}

/// How many sources `crate_dir/src` has, and the lines outside tests that name the build tree.
fn build_tree_paths(crate_dir: &Path) -> (usize, Vec<String>) {
    let mut files = Vec::new();
    rust_files(&crate_dir.join("src"), &mut files);
    let mut test_only = Vec::new();
    let mut kept = Vec::new();
    for file in &files {
        let (source, test_modules) = without_test_items(&std::fs::read_to_string(file).unwrap());
        test_only.extend(test_modules);
        kept.push((file, source));
    }
    let mut found = Vec::new();
    for (file, source) in &kept {
        let stem = file
            .file_stem()
            .and_then(|stem| stem.to_str())
            .unwrap_or("");
        if test_only.iter().any(|name| name == stem) {
            continue;
        }
        for line in source.lines() {
            if line.contains(BUILD_TREE_PATH) && !line.trim_start().starts_with("//") {
                found.push(format!("{}: {}", file.display(), line.trim()));
            }
        }
    }
    (files.len(), found)
}

#[test]
fn no_sandbox_binary_reads_a_path_baked_in_at_build_time() {
    let sandbox = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut found = Vec::new();
    for crate_dir in [sandbox.to_path_buf(), sandbox.join("../plugin")] {
        let (files, in_crate) = build_tree_paths(&crate_dir);
        assert!(
            files > 10,
            "{} has only {files} sources: moved?",
            crate_dir.display()
        );
        found.extend(in_crate);
    }
    assert!(
        found.is_empty(),
        "paths into the build tree, which a binary copied elsewhere cannot read:\n{}",
        found.join("\n")
    );
}

#[test]
fn the_scan_sees_through_test_items_only() {
    let source = "fn a() {}\n#[cfg(test)]\nmod tests {\n    fn b() { env!(\"CARGO_MANIFEST_DIR\"); }\n}\n#[cfg(test)]\nmod panel_tests;\nfn c() { env!(\"CARGO_MANIFEST_DIR\"); }\n";
    let (kept, test_modules) = without_test_items(source);
    assert_eq!(test_modules, ["panel_tests"]);
    assert_eq!(kept.matches(BUILD_TREE_PATH).count(), 1, "{kept}");
    assert!(
        kept.contains("fn c()") && !kept.contains("fn b()"),
        "{kept}"
    );
}
