//! `--preset` run as a user runs it: `render` with a preset draws what the same values given as
//! flags draw, and `snapshot` puts the preset on the street corner's materials. They render, so
//! they need a Vulkan driver; `tests/run` pins the software one.

mod common;

use common::*;

const PRESET: &str =
    "(height_scale: 0.09, max_samples: 64, method: relief, lighting: ggx_lambert, roughness: 0.25)";

/// Runs the sandbox with `args` and `--out DIR/name`; returns the PNG it wrote.
fn rendered(dir: &TempDir, name: &str, args: &[&str]) -> image::RgbaImage {
    let out = dir.join(name);
    let mut all = args.to_vec();
    all.extend(["--out", path_arg(&out)]);
    let output = sandbox(&all);
    assert!(
        output.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&output.stderr)
    );
    image::open(&out).unwrap().to_rgba8()
}

#[test]
fn render_with_a_preset_draws_what_its_values_as_flags_draw() {
    let dir = TempDir::new("render-preset");
    let preset = dir.join("tuned.ron");
    std::fs::write(&preset, PRESET).unwrap();
    let size = ["render", "--size", "64x64"];
    let from_preset = rendered(
        &dir,
        "preset.png",
        &[&size[..], &["--preset", path_arg(&preset)]].concat(),
    );
    let from_flags = rendered(
        &dir,
        "flags.png",
        &[
            &size[..],
            &[
                "--height-scale",
                "0.09",
                "--max-samples",
                "64",
                "--method",
                "relief",
            ],
            &["--lighting", "ggx_lambert", "--roughness", "0.25"],
        ]
        .concat(),
    );
    let default = rendered(&dir, "default.png", &size);
    assert!(
        from_preset == from_flags,
        "the preset and its flags draw differently"
    );
    assert!(from_preset != default, "the preset changed nothing");
}

#[test]
fn snapshot_with_a_preset_puts_it_on_the_scenes_materials() {
    let dir = TempDir::new("snapshot-preset");
    let preset = dir.join("tuned.ron");
    std::fs::write(&preset, PRESET).unwrap();
    let size = ["snapshot", "--size", "160x90"];
    let with = rendered(
        &dir,
        "with.png",
        &[&size[..], &["--preset", path_arg(&preset)]].concat(),
    );
    let without = rendered(&dir, "without.png", &size);
    assert!(with != without, "the preset changed nothing in the scene");
}
