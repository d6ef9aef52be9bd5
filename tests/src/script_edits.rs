//! A scene script edited in one place must fail to load with an error at a given line naming
//! given words: how the tests of what the script loader refuses are written.

use std::path::Path;

use pom::ScriptError;
use pom::script::parse_script;

/// Asserts that `script` (named `file` in messages) with its first `from` replaced by `to`
/// fails to load, at line `at_line`, with a reason containing every one of `needles`.
pub fn assert_load_error(
    (script, file): (&str, &str),
    (from, to): (&str, &str),
    at_line: usize,
    needles: &[&str],
) {
    assert!(script.contains(from), "{from:?}");
    let text = script.replacen(from, to, 1);
    let (line, reason) = match parse_script(&text, Path::new(file)) {
        Err(ScriptError::Parse { line, reason, .. }) => (line, reason),
        other => panic!("{from:?} → {to:?}: expected a load error, got {other:?}"),
    };
    assert_eq!(line, at_line, "{reason}");
    for needle in needles {
        assert!(reason.contains(needle), "{reason:?} should name {needle:?}");
    }
}
