//! Cargo finds no test of this crate by itself (`autotests = false`), so a file of `tests/tests/`
//! that neither `integration.rs` nor `tests/Cargo.toml` names would never be compiled or run.

use std::collections::BTreeSet;
use std::path::Path;

/// The tests' folder of this crate.
fn tests_dir() -> &'static Path {
    Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/tests"))
}

/// The file names a test could start from: each `.rs` file of the folder, and each sub-folder's
/// `main.rs` (a folder without one holds modules of the files beside it).
fn test_files() -> BTreeSet<String> {
    let mut files = BTreeSet::new();
    for entry in std::fs::read_dir(tests_dir()).expect("reading tests/tests") {
        let path = entry.expect("a folder entry").path();
        let name = path.file_name().unwrap().to_string_lossy().into_owned();
        if path.extension().is_some_and(|extension| extension == "rs") {
            files.insert(name);
        } else if path.join("main.rs").is_file() {
            files.insert(format!("{name}/main.rs"));
        }
    }
    files
}

#[test]
fn every_file_of_the_tests_folder_is_a_module_of_the_integration_binary_or_a_binary_of_its_own() {
    let integration = std::fs::read_to_string(tests_dir().join("integration.rs")).unwrap();
    let modules: BTreeSet<String> = integration
        .lines()
        .filter_map(|line| line.strip_prefix("mod ")?.strip_suffix(';'))
        .map(|module| format!("{module}.rs"))
        .collect();
    let manifest =
        std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/Cargo.toml")).unwrap();
    let binaries: BTreeSet<String> = manifest
        .lines()
        .filter_map(|line| line.strip_prefix("path = \"tests/")?.strip_suffix('"'))
        .map(str::to_owned)
        .collect();
    assert!(binaries.contains("integration.rs"), "{binaries:?}");
    let both: Vec<_> = modules.intersection(&binaries).collect();
    assert!(
        both.is_empty(),
        "in integration.rs and a binary of their own too: {both:?}"
    );
    let named: BTreeSet<String> = modules.union(&binaries).cloned().collect();
    let unnamed: Vec<_> = test_files().difference(&named).cloned().collect();
    assert!(
        unnamed.is_empty(),
        "never compiled: add a `mod` line to tests/tests/integration.rs (or a [[test]] to \
         tests/Cargo.toml for a test that owns its process): {unnamed:?}"
    );
    let missing: Vec<_> = named.difference(&test_files()).cloned().collect();
    assert!(missing.is_empty(), "named but not there: {missing:?}");
}
