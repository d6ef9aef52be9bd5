//! The library's source files and documents, for the tests that read them (layering, code
//! shape, the README's and the docs' code kept verbatim).

use std::path::{Path, PathBuf};

/// `plugin/src` of this repository.
pub fn plugin_src() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../plugin/src")
}

/// Every `.rs` file under `dir`, at any depth.
pub fn rust_files(dir: &Path) -> Vec<PathBuf> {
    let mut files = Vec::new();
    for entry in std::fs::read_dir(dir).expect("reading plugin/src") {
        let path = entry.expect("a directory entry").path();
        if path.is_dir() {
            files.extend(rust_files(&path));
        } else if path.extension().is_some_and(|ext| ext == "rs") {
            files.push(path);
        }
    }
    files
}

/// The text of the first fenced block of `language` (```` ```rust ````, ```` ```wgsl ````; an
/// info string such as `rust,ignore` counts) after `heading` in `document`.
pub fn fenced_block<'a>(document: &'a str, heading: &str, language: &str) -> &'a str {
    let section = &document[document.find(heading).expect(heading)..];
    let fence = format!("```{language}");
    let code = &section[section.find(&fence).expect(&fence) + fence.len()..];
    let code = &code[code.find('\n').expect("the fence ends its line") + 1..];
    &code[..code.find("```").expect("the block is closed")]
}
