//! Every RON example of plugin/docs/scene-tests.md does what the page says: a block starting
//! `// file: NAME` is written as that file, one starting `// refused: TEXT` is refused with
//! TEXT when loaded, and every other block runs and passes. They run from a folder holding
//! copies of the page's maps and glTF file; missing references are written (blessed) first.

use std::path::{Path, PathBuf};

use pom::script::{Outcome, parse_script};
use pom::{RunOptions, run_script_with};

fn repository() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

/// The ```` ```ron ```` blocks of the page, in order.
fn ron_blocks(page: &str) -> Vec<String> {
    let mut blocks = Vec::new();
    let mut current: Option<String> = None;
    for line in page.lines() {
        match (&mut current, line.trim_end()) {
            (None, "```ron") => current = Some(String::new()),
            (Some(block), "```") => {
                blocks.push(std::mem::take(block));
                current = None;
            }
            (Some(block), text) => {
                block.push_str(text);
                block.push('\n');
            }
            (None, _) => {}
        }
    }
    blocks
}

/// A folder as the page describes: the maps under `textures/` and the street corner.
fn example_folder() -> PathBuf {
    let dir = std::env::temp_dir().join(format!("pom-scene-docs-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let assets = repository().join("assets");
    for set in ["cobblestone", "bricks"] {
        std::fs::create_dir_all(dir.join("textures").join(set)).unwrap();
        for map in ["albedo.png", "normal.png", "height.png"] {
            std::fs::copy(
                assets.join(set).join(map),
                dir.join("textures").join(set).join(map),
            )
            .unwrap();
        }
    }
    std::fs::copy(
        assets.join("street_corner.glb"),
        dir.join("street_corner.glb"),
    )
    .unwrap();
    dir
}

#[test]
fn every_ron_example_of_the_scene_test_page_does_what_it_says() {
    let page = std::fs::read_to_string(repository().join("plugin/docs/scene-tests.md")).unwrap();
    let blocks = ron_blocks(&page);
    assert!(blocks.len() >= 6, "found only {} RON blocks", blocks.len());
    let dir = example_folder();
    let mut failures = Vec::new();
    let mut scripts_run = 0;
    for (index, block) in blocks.iter().enumerate() {
        let first = block.lines().next().unwrap_or_default();
        let script = dir.join(format!("example_{index}.ron"));
        if let Some(name) = first.strip_prefix("// file: ") {
            let path = dir.join(name);
            std::fs::create_dir_all(path.parent().unwrap()).unwrap();
            std::fs::write(path, block).unwrap();
        } else if let Some(expected) = first.strip_prefix("// refused: ") {
            match parse_script(block, &script) {
                Err(error) if error.to_string().contains(expected) => {}
                other => failures.push(format!(
                    "block {index}: expected {expected:?}, got {other:?}"
                )),
            }
        } else {
            std::fs::write(&script, block).unwrap();
            let options = RunOptions {
                bless: true,
                ..RunOptions::default()
            };
            scripts_run += 1;
            match run_script_with(&script, &options) {
                Ok(report) => {
                    eprint!("{report}");
                    let failed = report
                        .steps
                        .iter()
                        .any(|step| matches!(step.outcome, Outcome::Failed(_)));
                    if failed {
                        failures.push(format!("block {index} failed:\n{report}"));
                    }
                    // The page promises this line for a capture on the default path here.
                    if !report.to_string().contains(": ok (forward)\n") {
                        failures.push(format!("block {index}: no capture ran forward:\n{report}"));
                    }
                }
                Err(error) => failures.push(format!("block {index}: {error}")),
            }
        }
    }
    std::fs::remove_dir_all(&dir).unwrap();
    assert!(scripts_run >= 4, "only {scripts_run} examples ran");
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
