//! The benchmark figures can be reproduced from the repository alone: nothing under
//! `sandbox/bench-results/` and nothing in `sandbox/BENCHMARKS.md` names a file outside it (the
//! project's shared folder beside the checkout, one machine's absolute paths, unpacked binaries),
//! every `assets/...` path they name exists, and so does every relative link of the page and
//! every test binary its commands run. A figure whose inputs only one machine had cannot be
//! checked by anyone else.

use std::path::{Path, PathBuf};

/// Text that names a file outside the repository.
const OUTSIDE: [&str; 3] = ["../shared/", "/work/", ".devbin"];

fn repository() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

/// Every file under `dir`, sorted.
fn files_under(dir: &Path) -> Vec<PathBuf> {
    let mut files = Vec::new();
    for entry in std::fs::read_dir(dir).expect("reading a results folder") {
        let path = entry.expect("a directory entry").path();
        if path.is_dir() {
            files.extend(files_under(&path));
        } else {
            files.push(path);
        }
    }
    files.sort();
    files
}

/// The `assets/...` paths `text` names, relative to the repository root (a `../` before one is
/// the way up to it), each up to the first character that cannot be part of a path.
fn asset_paths(text: &str) -> Vec<&str> {
    let mut paths = Vec::new();
    for (at, _) in text.match_indices("assets/") {
        // `bench_assets/` or `my-assets/` is some other folder.
        let before = text[..at].chars().next_back();
        if before.is_some_and(|c| c.is_alphanumeric() || c == '_' || c == '-') {
            continue;
        }
        let rest = &text[at..];
        let end = rest
            .find(|c: char| c.is_whitespace() || "`'\"()[]<>,;|{}*".contains(c))
            .unwrap_or(rest.len());
        paths.push(rest[..end].trim_end_matches(['.', ':']));
    }
    paths
}

/// The files `text` passes to `--height`, `--normal` and `--albedo`: a bare name there worked
/// only beside the binary of the run that used it.
fn map_arguments(text: &str) -> Vec<&str> {
    let words: Vec<&str> = text.split_whitespace().collect();
    words
        .windows(2)
        .filter(|pair| {
            // `COB="--height` opens a command; "without `--height`" only names the option.
            let flag = pair[0].rsplit(['"', '=', '`']).next().unwrap_or(pair[0]);
            ["--height", "--normal", "--albedo"].contains(&flag) && !pair[0].ends_with('`')
        })
        .map(|pair| pair[1].trim_matches(['`', '"', '\'']))
        .collect()
}

/// The targets of the Markdown links `[text](target)` in `page` that lead to a file of the
/// repository (not a web address or an anchor of the page), without their `#anchor`.
fn relative_links(page: &str) -> Vec<&str> {
    page.match_indices("](")
        .filter_map(|(at, _)| {
            let rest = &page[at + 2..];
            let target = &rest[..rest.find(')')?];
            let target = target.split('#').next().unwrap_or(target);
            let external = target.contains("://") || target.starts_with("mailto:");
            (!target.is_empty() && !external).then_some(target)
        })
        .collect()
}

/// What is wrong with `text` (the contents of `shown`): each name of an outside file, each
/// `assets/...` path and each map argument that does not exist.
fn problems_of(root: &Path, shown: &str, text: &str) -> Vec<String> {
    let mut problems = Vec::new();
    for (number, line) in text.lines().enumerate() {
        for outside in OUTSIDE.iter().filter(|outside| line.contains(*outside)) {
            problems.push(format!(
                "{shown}:{}: names `{outside}`, outside the repository: {}",
                number + 1,
                line.trim()
            ));
        }
        let mut paths = asset_paths(line);
        paths.extend(map_arguments(line));
        paths.sort_unstable();
        paths.dedup();
        for path in paths {
            if !root.join(path).exists() {
                problems.push(format!("{shown}:{}: {path} does not exist", number + 1));
            }
        }
    }
    problems
}

/// The `--test NAME` arguments of `text` that name no test binary of tests/Cargo.toml (its
/// integration tests share one binary: a module is run as `--test integration MODULE::`).
fn unknown_test_targets(root: &Path, text: &str) -> Vec<String> {
    let manifest =
        std::fs::read_to_string(root.join("tests/Cargo.toml")).expect("reading tests/Cargo.toml");
    let targets: Vec<&str> = manifest
        .split("[[test]]")
        .skip(1)
        .filter_map(|entry| entry.split('"').nth(1))
        .collect();
    text.split("--test ")
        .skip(1)
        .filter_map(|rest| {
            rest.split(|c: char| !(c.is_alphanumeric() || c == '_'))
                .next()
        })
        .filter(|name| !targets.contains(name))
        .map(|name| format!("`--test {name}` names no test binary of tests/Cargo.toml"))
        .collect()
}

#[test]
fn bench_results_and_benchmarks_md_name_only_files_of_the_repository() {
    let root = repository();
    let results = root.join("sandbox/bench-results");
    let mut problems = Vec::new();
    for file in files_under(&results) {
        let shown = file
            .strip_prefix(&root)
            .unwrap_or(&file)
            .display()
            .to_string();
        let bytes = std::fs::read(&file).expect("reading a result");
        if bytes.is_empty() {
            problems.push(format!("{shown}: empty"));
        }
        // Charts and other binary files name no files.
        if let Ok(text) = String::from_utf8(bytes) {
            problems.extend(problems_of(&root, &shown, &text));
        }
    }
    let page_path = root.join("sandbox/BENCHMARKS.md");
    let page = std::fs::read_to_string(&page_path).expect("reading sandbox/BENCHMARKS.md");
    problems.extend(problems_of(&root, "sandbox/BENCHMARKS.md", &page));
    problems.extend(unknown_test_targets(&root, &page));
    for link in relative_links(&page) {
        if !root.join("sandbox").join(link).exists() {
            problems.push(format!(
                "sandbox/BENCHMARKS.md: the link to {link} leads nowhere"
            ));
        }
    }
    assert!(
        problems.is_empty(),
        "a benchmark result must be reproducible from the repository (copy its inputs into \
         assets/ or drop it):\n{}",
        problems.join("\n")
    );
}

#[test]
fn the_scan_finds_what_it_should_and_nothing_else() {
    let root = repository();
    let flagged = [
        "COB=\"--height ../shared/bench/cobblestone_height.png\"",
        "unpacked /work/release-target/release/sandbox",
        "./sandbox.devbin bench",
        "--height assets/bench_cobblestone/missing.png --tiling 4",
        "copy `assets/no-such-folder/` first",
        "COB=\"--height cobblestone_height.png --normal cobblestone_normal.png",
    ];
    for line in flagged {
        assert!(!problems_of(&root, "t", line).is_empty(), "{line}");
    }
    let passed = [
        "--height assets/bench_cobblestone/cobblestone_height.png --tiling 4",
        "[the maps](../assets/bench_cobblestone/README.md), `assets/bricks/`.",
        "copy `assets/street_corner.glb` and assets/cobblestone/*.png",
        "`sandbox bench --height-scale 0.05 --height assets/bricks/height.png`",
        "without `--height` the shipped bricks are used",
        "wrote bench.json, bench.csv, bench.png to /tmp/r/cobble-45",
        "not_assets/x and bench_assets/y are other folders",
    ];
    for line in passed {
        let problems = problems_of(&root, "t", line);
        assert!(problems.is_empty(), "{line}: {problems:?}");
    }
    assert_eq!(
        unknown_test_targets(&root, "`cargo test -p pom-tests --test anti_aliasing`"),
        ["`--test anti_aliasing` names no test binary of tests/Cargo.toml"]
    );
    assert!(unknown_test_targets(&root, "--test integration anti_aliasing::").is_empty());
    assert_eq!(
        relative_links(
            "[a](bench-results/memory/) [b](https://x.org/a) [c](#how-to-run) [d](../x.md#s)"
        ),
        ["bench-results/memory/", "../x.md"]
    );
}
