//! Comments say why, not when: no code comment of the library, the sandbox or the tests names a
//! GPU model, an issue number, an issue's closing remarks or a date. Measurements and their dates belong in
//! `sandbox/BENCHMARKS.md` and the commit log, where they can be kept current; a comment keeps
//! the reason the figure supported. The benchmark code (`sandbox/src/bench`) reports
//! measurements by nature and is left out.

use std::path::{Path, PathBuf};

/// The folders scanned, relative to the workspace root.
const SCANNED: [&str; 4] = ["plugin/src", "sandbox/src", "tests/src", "tests/tests"];

/// Folders under [`SCANNED`] left out.
const LEFT_OUT: [&str; 1] = ["sandbox/src/bench"];

fn workspace_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

/// Every `.rs` and `.wgsl` file under `dir` not in a left-out folder.
fn source_files(root: &Path, dir: &Path) -> Vec<PathBuf> {
    let mut files = Vec::new();
    for entry in std::fs::read_dir(dir).expect("reading a source folder") {
        let path = entry.expect("a directory entry").path();
        let relative = path.strip_prefix(root).unwrap_or(&path);
        if LEFT_OUT.iter().any(|left| relative == Path::new(left)) {
            continue;
        }
        if path.is_dir() {
            files.extend(source_files(root, &path));
        } else if path
            .extension()
            .is_some_and(|ext| ext == "rs" || ext == "wgsl")
        {
            files.push(path);
        }
    }
    files
}

/// The comment of `line`: from the first `//` outside a string literal to the end of the line.
/// A string that spans lines is not followed; the lines that matter do not have one.
fn comment_of(line: &str) -> Option<&str> {
    let bytes = line.as_bytes();
    let mut in_string = false;
    let mut index = 0;
    while index < bytes.len() {
        match bytes[index] {
            b'\\' if in_string => index += 1,
            b'"' => in_string = !in_string,
            // A char literal `'"'` does not open a string.
            b'\'' if !in_string && bytes.get(index + 2) == Some(&b'\'') => index += 2,
            b'/' if !in_string && bytes.get(index + 1) == Some(&b'/') => {
                return Some(&line[index..]);
            }
            _ => {}
        }
        index += 1;
    }
    None
}

/// Whether `text` has `digits` ASCII digits at `at`.
fn digits_at(text: &[u8], at: usize, digits: usize) -> bool {
    text.len() >= at + digits && text[at..at + digits].iter().all(u8::is_ascii_digit)
}

/// What of `comment` does not belong in a comment, if anything: a GPU model of the benchmark
/// machines, an issue number, a reference to an issue's closing remarks or a date (YYYY-MM-DD).
fn offence(comment: &str) -> Option<&'static str> {
    let lower = comment.to_ascii_lowercase();
    let text = lower.as_bytes();
    if lower.contains("h100") || lower.contains("h200") {
        return Some("a GPU model");
    }
    if lower.contains("closing note") {
        return Some("a closing note");
    }
    for (at, _) in lower.match_indices("issue") {
        let mut after = at + "issue".len();
        if text.get(after) == Some(&b's') {
            after += 1;
        }
        while matches!(text.get(after), Some(b' ' | b'#')) {
            after += 1;
        }
        if after > at + "issue".len() && digits_at(text, after, 1) {
            return Some("an issue number");
        }
    }
    for at in 0..text.len() {
        let date = digits_at(text, at, 4)
            && text.get(at + 4) == Some(&b'-')
            && digits_at(text, at + 5, 2)
            && text.get(at + 7) == Some(&b'-')
            && digits_at(text, at + 8, 2);
        if date {
            return Some("a date");
        }
    }
    None
}

#[test]
fn code_comments_name_no_machine_issue_or_date() {
    let root = workspace_root();
    let root = root.canonicalize().unwrap_or(root);
    let mut problems = Vec::new();
    for dir in SCANNED {
        let mut files = source_files(&root, &root.join(dir));
        files.sort();
        for file in files {
            let source = std::fs::read_to_string(&file).expect("reading a source file");
            let shown = file.strip_prefix(&root).unwrap_or(&file).display();
            for (number, line) in source.lines().enumerate() {
                if let Some(what) = comment_of(line).and_then(offence) {
                    problems.push(format!("{shown}:{}: {what}: {}", number + 1, line.trim()));
                }
            }
        }
    }
    assert!(
        problems.is_empty(),
        "comments say why, not when (figures and dates go to sandbox/BENCHMARKS.md or the \
         commit log):\n{}",
        problems.join("\n")
    );
}

#[test]
fn the_scan_finds_what_it_should_and_nothing_else() {
    let flagged = [
        "// on the H200 this costs less",
        "    /// see Issue 16",
        "//! the closing note of the review",
        "let x = 1; // measured 2026-11-29",
        "// issues #12 and #14",
    ];
    for line in flagged {
        assert!(comment_of(line).and_then(offence).is_some(), "{line}");
    }
    let passed = [
        "let s = \"// issue 16\";",
        "// the issue is the sampler, not the texture",
        "// 16 issues per warp",
        "let c = '\"'; // a quote",
        "let date = \"2026-11-29\";",
        "// steps of 2026-11",
    ];
    for line in passed {
        assert!(comment_of(line).and_then(offence).is_none(), "{line}");
    }
}
