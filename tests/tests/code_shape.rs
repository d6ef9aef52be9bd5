//! The library stays readable in pieces: no file of `plugin/src` over [`MAX_FILE_LINES`] lines
//! and no function over [`MAX_FUNCTION_LINES`] (from its `fn` line to its closing brace, as
//! rustfmt lays it out), tests included.

use pom_tests::sources::{plugin_src, rust_files};

const MAX_FILE_LINES: usize = 600;
const MAX_FUNCTION_LINES: usize = 80;

/// The name of the function `line` starts, if it starts one with a body.
fn function_name(line: &str) -> Option<&str> {
    let mut words = line.split_whitespace().peekable();
    while let Some(word) = words.peek() {
        if ["pub", "const", "async", "unsafe", "extern"].contains(word) || word.starts_with("pub(")
        {
            words.next();
        } else {
            break;
        }
    }
    if words.next() != Some("fn") {
        return None;
    }
    let name = words.next()?;
    Some(name.split(['(', '<']).next().unwrap_or(name))
}

/// Every function of `source` longer than the limit: (name, first line, lines).
fn long_functions(source: &str) -> Vec<(String, usize, usize)> {
    let lines: Vec<&str> = source.lines().collect();
    let mut found = Vec::new();
    let mut index = 0;
    while index < lines.len() {
        let line = lines[index];
        let Some(name) = function_name(line.trim_start()) else {
            index += 1;
            continue;
        };
        let indent = line.len() - line.trim_start().len();
        // A declaration without a body (a trait's required method) ends with `;`.
        let mut open = index;
        while open < lines.len() && !lines[open].contains('{') && !lines[open].ends_with(';') {
            open += 1;
        }
        if open >= lines.len() || lines[open].ends_with(';') {
            index = open + 1;
            continue;
        }
        let one_line = open == index && lines[index].trim_end().ends_with('}');
        let close = if one_line {
            index
        } else {
            (open + 1..lines.len())
                .find(|&at| {
                    let text = lines[at];
                    text.len() - text.trim_start().len() == indent
                        && text.trim_start().starts_with('}')
                })
                .unwrap_or(lines.len() - 1)
        };
        let length = close - index + 1;
        if length > MAX_FUNCTION_LINES {
            found.push((name.to_owned(), index + 1, length));
        }
        index = close + 1;
    }
    found
}

#[test]
fn no_file_or_function_of_the_library_is_too_long() {
    let src = plugin_src();
    let mut problems = Vec::new();
    for file in rust_files(&src) {
        let source = std::fs::read_to_string(&file).expect("reading a source file");
        let shown = file
            .strip_prefix(&src)
            .unwrap_or(&file)
            .display()
            .to_string();
        let lines = source.lines().count();
        if lines > MAX_FILE_LINES {
            problems.push(format!("{shown}: {lines} lines (at most {MAX_FILE_LINES})"));
        }
        for (name, line, length) in long_functions(&source) {
            problems.push(format!(
                "{shown}:{line}: fn {name} is {length} lines (at most {MAX_FUNCTION_LINES})"
            ));
        }
    }
    assert!(problems.is_empty(), "{}", problems.join("\n"));
}

#[test]
fn a_long_function_is_found_and_a_short_one_is_not() {
    let body = "    let x = 1;\n".repeat(MAX_FUNCTION_LINES);
    let source = format!(
        "fn short() {{ 1 }}\n\npub(crate) fn long(a: u32) -> u32 {{\n{body}    a\n}}\n\ntrait T {{\n    fn required(&self);\n}}\n"
    );
    let found = long_functions(&source);
    assert_eq!(found.len(), 1, "{found:?}");
    assert_eq!(found[0].0, "long");
    assert_eq!(found[0].2, MAX_FUNCTION_LINES + 3);
}
