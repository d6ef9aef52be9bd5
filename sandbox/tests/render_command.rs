//! `sandbox render` run as a user runs it: the built binary, its exit status, its stderr and the
//! PNG it writes. The tests that render need a Vulkan driver; `tests/run` pins the software one.

mod common;

use common::*;

#[test]
fn an_unknown_method_is_rejected_with_the_valid_ones() {
    let dir = TempDir::new("unknown-method");
    let out = dir.join("out.png");
    let output = sandbox(&["render", "--out", path_arg(&out), "--method", "raymarch"]);
    assert_one_line_error(&output, &["raymarch", "--method", "pom"]);
    assert!(!out.exists());
}

#[test]
fn a_bad_size_is_rejected() {
    let dir = TempDir::new("bad-size");
    let out = dir.join("out.png");
    let output = sandbox(&["render", "--out", path_arg(&out), "--size", "64by48"]);
    assert_one_line_error(&output, &["--size", "64by48", "WIDTHxHEIGHT"]);
    assert!(!out.exists());
}

#[test]
fn a_missing_height_file_is_named() {
    let dir = TempDir::new("missing-height");
    let out = dir.join("out.png");
    let missing = dir.join("no-such-height.png");
    let output = sandbox(&[
        "render",
        "--out",
        path_arg(&out),
        "--height",
        path_arg(&missing),
    ]);
    assert_one_line_error(&output, &["--height", "no-such-height.png"]);
    assert!(!out.exists());
}

#[test]
fn a_truncated_height_png_is_named() {
    let dir = TempDir::new("truncated-height");
    let out = dir.join("out.png");
    let truncated = dir.join("truncated-height.png");
    // A PNG signature and the start of a header, then nothing.
    std::fs::write(&truncated, b"\x89PNG\r\n\x1a\n\0\0\0\rIHDR").unwrap();
    let output = sandbox(&[
        "render",
        "--out",
        path_arg(&out),
        "--height",
        path_arg(&truncated),
    ]);
    assert_one_line_error(&output, &["--height", "truncated-height.png"]);
    assert!(!out.exists());
}

#[test]
fn a_device_or_a_fifo_as_height_is_refused_at_once() {
    let dir = TempDir::new("special-height");
    let out = dir.join("out.png");
    let fifo = dir.join("pipe.png");
    mkfifo(&fifo);
    for (height, kind) in [
        ("/dev/zero", "a character device"),
        ("/dev/urandom", "a character device"),
        (path_arg(&fifo), "a FIFO"),
    ] {
        let output = sandbox_within_20_s(&["render", "--out", path_arg(&out), "--height", height]);
        assert_one_line_error(&output, &["--height", height, kind, "not a regular file"]);
        assert!(!out.exists());
    }
}

#[test]
fn a_scene_that_is_a_symlink_to_a_device_or_a_fifo_is_refused_at_once() {
    let dir = TempDir::new("special-scene");
    let out = dir.join("out.png");
    let link = dir.join("level.glb");
    std::os::unix::fs::symlink("/dev/zero", &link).unwrap();
    let fifo = dir.join("level.gltf");
    mkfifo(&fifo);
    for (scene, kind) in [(&link, "a character device"), (&fifo, "a FIFO")] {
        let output = sandbox_within_20_s(&[
            "render",
            "--out",
            path_arg(&out),
            "--scene",
            path_arg(scene),
        ]);
        assert_one_line_error(&output, &[path_arg(scene), kind]);
        assert!(!out.exists());
    }
}

#[test]
fn inverted_sample_bounds_are_rejected() {
    let dir = TempDir::new("inverted-samples");
    let out = dir.join("out.png");
    let output = sandbox(&[
        "render",
        "--out",
        path_arg(&out),
        "--min-samples",
        "60",
        "--max-samples",
        "10",
    ]);
    assert_one_line_error(&output, &["min_samples (60)", "max_samples (10)"]);
    assert!(!out.exists());
}

#[test]
fn a_sample_count_out_of_range_is_printed_as_the_whole_number_given() {
    let dir = TempDir::new("huge-samples");
    let out = dir.join("out.png");
    let output = sandbox(&[
        "render",
        "--out",
        path_arg(&out),
        "--max-samples",
        "4294967295",
    ]);
    assert_one_line_error(&output, &["max_samples is 4294967295", "at most 256"]);
    assert!(!out.exists());
}

/// Renders the MaxMip method over a 34×34 height map, whose maximum pyramid stops at 17×17
/// cells: the library logs a warning that such a march is slow.
fn render_odd_sized_max_mip(dir: &TempDir, rust_log: Option<&str>) -> std::process::Output {
    let height = dir.join("odd-height.png");
    image::GrayImage::from_fn(34, 34, |x, y| image::Luma([((x * 7 + y * 3) % 256) as u8]))
        .save(&height)
        .unwrap();
    let out = dir.join("out.png");
    let mut command = std::process::Command::new(env!("CARGO_BIN_EXE_sandbox"));
    command.args([
        "render",
        "--size",
        "16x16",
        "--method",
        "maxmip",
        "--height",
        path_arg(&height),
        "--out",
        path_arg(&out),
    ]);
    command.env_remove("RUST_LOG");
    if let Some(level) = rust_log {
        command.env("RUST_LOG", level);
    }
    command.output().unwrap()
}

#[test]
fn the_library_warnings_reach_stderr_by_default() {
    let dir = TempDir::new("warning-shown");
    let output = render_odd_sized_max_mip(&dir, None);
    assert_success(&output);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(
        stderr.contains("warning: a 34×34 height map's maximum pyramid stops at 17×17"),
        "{stderr}"
    );
}

#[test]
fn rust_log_error_hides_the_library_warnings() {
    let dir = TempDir::new("warning-hidden");
    let output = render_odd_sized_max_mip(&dir, Some("error"));
    assert_success(&output);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(!stderr.contains("maximum pyramid"), "{stderr}");
}

#[test]
fn texture_bounds_of_no_area_are_rejected() {
    let dir = TempDir::new("inverted-bounds");
    let out = dir.join("out.png");
    let output = sandbox(&[
        "render",
        "--out",
        path_arg(&out),
        "--silhouette",
        "uv_bounds",
        "--bounds-u-min",
        "1",
        "--bounds-u-max",
        "0",
    ]);
    assert_one_line_error(
        &output,
        &["bounds_u_min (1)", "bounds_u_max (0)", "no area"],
    );
    assert!(!out.exists());
}

#[test]
fn an_unknown_silhouette_is_rejected_with_the_valid_ones() {
    let dir = TempDir::new("unknown-silhouette");
    let out = dir.join("out.png");
    let output = sandbox(&["render", "--out", path_arg(&out), "--silhouette", "outline"]);
    assert_one_line_error(&output, &["outline", "--silhouette", "uv_bounds", "curved"]);
    assert!(!out.exists());
}

#[test]
fn an_unknown_shape_is_rejected_with_the_valid_ones() {
    let dir = TempDir::new("unknown-shape");
    let out = dir.join("out.png");
    let output = sandbox(&["render", "--out", path_arg(&out), "--shape", "torus"]);
    assert_one_line_error(&output, &["torus", "--shape", "cube", "cylinder"]);
    assert!(!out.exists());
}

#[test]
fn a_shape_is_framed_whole_and_its_clipped_outline_shows_what_lies_behind() {
    let dir = TempDir::new("shape");
    let coverage = |silhouette: &str| {
        let out = dir.join(&format!("cube-{silhouette}.png"));
        let args = [
            "render",
            "--out",
            path_arg(&out),
            "--size",
            "96x96",
            "--shape",
            "cube",
            "--view-angle",
            "60",
            "--height-scale",
            "0.1",
            "--silhouette",
            silhouette,
        ];
        assert_success(&sandbox(&args));
        let image = image::open(&out).unwrap().to_rgba8();
        // The corners are background: the solid is framed whole, with a margin.
        for (x, y) in [(0, 0), (95, 0), (0, 95), (95, 95)] {
            assert!(
                brightness(image.get_pixel(x, y)) < 30,
                "{silhouette}: corner ({x}, {y})"
            );
        }
        image
            .pixels()
            .filter(|pixel| brightness(pixel) >= 30)
            .count()
    };
    let (off, clipped) = (coverage("off"), coverage("uv_bounds"));
    assert!(clipped < off, "clipped {clipped} pixels, off {off}");
}

#[test]
fn a_negative_height_scale_is_rejected() {
    let dir = TempDir::new("negative-height-scale");
    let out = dir.join("out.png");
    let output = sandbox(&["render", "--out", path_arg(&out), "--height-scale", "-1"]);
    assert_one_line_error(&output, &["height_scale", "-1"]);
    assert!(!out.exists());
}

#[test]
fn a_nan_height_scale_is_rejected() {
    let dir = TempDir::new("nan-height-scale");
    let out = dir.join("out.png");
    let output = sandbox(&["render", "--out", path_arg(&out), "--height-scale", "NaN"]);
    assert_one_line_error(&output, &["height_scale", "NaN", "finite"]);
    assert!(!out.exists());
}

#[test]
fn bad_triplanar_flags_are_rejected_naming_the_parameter() {
    for (name, args, expected) in [
        (
            "triplanar-negative-scale",
            ["--triplanar-scale", "-1"],
            ["triplanar_scale", "-1", "0.001"],
        ),
        (
            "triplanar-nan-scale",
            ["--triplanar-scale", "NaN"],
            ["triplanar_scale", "NaN", "finite"],
        ),
        (
            "triplanar-sharpness",
            ["--triplanar-sharpness", "0.5"],
            ["triplanar_sharpness", "0.5", "at least 1"],
        ),
        (
            "unknown-mapping",
            ["--triplanar-scale", "2"],
            ["cubic", "--mapping", "triplanar"],
        ),
    ] {
        let dir = TempDir::new(name);
        let out = dir.join("out.png");
        let mapping = if name == "unknown-mapping" {
            "cubic"
        } else {
            "triplanar"
        };
        let mut command = vec!["render", "--out", path_arg(&out), "--mapping", mapping];
        command.extend(args);
        let output = sandbox(&command);
        assert_one_line_error(&output, &expected);
        assert!(!out.exists());
    }
}

#[test]
fn a_bad_exposure_is_rejected() {
    let dir = TempDir::new("bad-exposure");
    let out = dir.join("out.png");
    let output = sandbox(&["render", "--out", path_arg(&out), "--exposure", "NaN"]);
    assert_one_line_error(&output, &["--exposure", "NaN"]);
    let output = sandbox(&["render", "--out", path_arg(&out), "--exposure", "99"]);
    assert_one_line_error(&output, &["--exposure", "99", "-16..=24"]);
    assert!(!out.exists());
}

#[test]
fn a_bad_shadow_map_size_is_rejected_naming_the_flag_and_the_limit() {
    let dir = TempDir::new("bad-shadow-map-size");
    let out = dir.join("out.png");
    for command in ["render", "snapshot"] {
        for bad in ["0", "9000", "big"] {
            let output = sandbox(&[command, "--out", path_arg(&out), "--shadow-map-size", bad]);
            assert_one_line_error(&output, &["--shadow-map-size", bad, "16..=8192"]);
        }
    }
    assert!(!out.exists());
}

#[test]
fn an_unknown_scene_shadows_switch_is_rejected_with_the_valid_ones() {
    let dir = TempDir::new("bad-scene-shadows");
    let out = dir.join("out.png");
    for command in ["render", "snapshot"] {
        let output = sandbox(&[command, "--out", path_arg(&out), "--scene-shadows", "maybe"]);
        assert_one_line_error(&output, &["maybe", "--scene-shadows", "on", "off"]);
    }
    assert!(!out.exists());
}

/// Runs `sandbox COMMAND --out DIR/NAME ARGS…`, checks it succeeded and returns the PNG it wrote.
fn rendered(dir: &TempDir, name: &str, command: &str, args: &[&str]) -> image::RgbaImage {
    let out = dir.join(name);
    let mut all = vec![command, "--out", path_arg(&out)];
    all.extend_from_slice(args);
    assert_success(&sandbox(&all));
    image::open(&out)
        .unwrap_or_else(|error| panic!("{name}: {error}"))
        .to_rgba8()
}

/// R + G + B of a pixel.
fn brightness(pixel: &image::Rgba<u8>) -> i32 {
    pixel.0[..3].iter().map(|&c| i32::from(c)).sum()
}

#[test]
fn scene_shadows_darken_the_picture_and_the_map_size_changes_them() {
    let dir = TempDir::new("shadow-flags");
    // The preview with its self-shadows off and a low light, so the relief's shadows come from
    // the shadow map alone; and the street corner, whose objects shadow each other.
    for (command, size, view) in [
        (
            "render",
            "64x64",
            &["--shadows", "off", "--light-angle", "70"][..],
        ),
        ("snapshot", "96x54", &[][..]),
    ] {
        let render = |name: &str, switch: &str, map_size: &str| {
            let mut args = vec![
                "--size",
                size,
                "--scene-shadows",
                switch,
                "--shadow-map-size",
                map_size,
            ];
            args.extend_from_slice(view);
            rendered(&dir, &format!("{command}-{name}.png"), command, &args)
        };
        let off = render("off", "off", "512");
        let on = render("on", "on", "512");
        let coarse = render("coarse", "on", "64");
        // Shadows only take light away: no pixel gets brighter (beyond rounding), and some get
        // much darker.
        let changes: Vec<i32> = on
            .pixels()
            .zip(off.pixels())
            .map(|(on, off)| brightness(on) - brightness(off))
            .collect();
        let brighter = changes.iter().filter(|&&change| change > 6).count();
        let darker = changes.iter().filter(|&&change| change < -30).count();
        eprintln!("{command}: with scene shadows {darker} pixels darker, {brighter} brighter");
        assert_eq!(brighter, 0, "{command}: scene shadows brightened pixels");
        assert!(
            darker >= 20,
            "{command}: --scene-shadows on darkens only {darker} pixels"
        );
        // A 64-texel map places the shadows differently (coarser, and biased by its larger
        // texels) from a 512-texel one.
        let moved = on
            .pixels()
            .zip(coarse.pixels())
            .filter(|(fine, coarse)| (brightness(fine) - brightness(coarse)).abs() > 30)
            .count();
        eprintln!("{command}: {moved} pixels differ between 512- and 64-texel maps");
        assert!(
            moved >= 20,
            "{command}: --shadow-map-size 64 changes only {moved} pixels from 512"
        );
    }
}

#[test]
fn an_unknown_tonemap_is_rejected_with_the_valid_ones() {
    let dir = TempDir::new("unknown-tonemap");
    let out = dir.join("out.png");
    let output = sandbox(&["render", "--out", path_arg(&out), "--tonemap", "filmic"]);
    assert_one_line_error(&output, &["filmic", "--tonemap", "agx", "neutral"]);
    assert!(!out.exists());
}

#[test]
fn exposure_darkens_the_render_and_tonemap_none_clips() {
    let dir = TempDir::new("exposure");
    let render = |name: &str, extra: &[&str]| {
        let mut args = vec!["--size", "32x32"];
        args.extend_from_slice(extra);
        let image = rendered(&dir, name, "render", &args);
        image.pixels().map(|p| u64::from(p.0[1])).sum::<u64>()
    };
    let base = render("base.png", &[]);
    let darker = render("darker.png", &["--exposure", "16.7"]);
    let clamped = render("clamped.png", &["--tonemap", "none"]);
    assert!(darker < base * 9 / 10, "{darker} vs {base}");
    assert_ne!(clamped, base, "the operator changes the image");
}

#[test]
fn a_headless_run_prints_only_what_it_means_to_say() {
    // As on a machine without a desktop session: no runtime folder, no display, and no variable
    // that quiets Mesa's device-select layer (which tests/run sets for the other tests).
    let dir = TempDir::new("quiet");
    let out = dir.join("quiet.png");
    let output = std::process::Command::new(env!("CARGO_BIN_EXE_sandbox"))
        .args(["snapshot", "--size", "32x16", "--out", path_arg(&out)])
        .env_remove("NODEVICE_SELECT")
        .env_remove("XDG_RUNTIME_DIR")
        .env_remove("WAYLAND_DISPLAY")
        .env_remove("DISPLAY")
        .output()
        .unwrap();
    assert_success(&output);
    assert_eq!(String::from_utf8_lossy(&output.stderr), "", "stderr");
    assert!(out.exists());
}

#[test]
fn render_writes_a_png_of_the_asked_size() {
    let dir = TempDir::new("size");
    let out = dir.join("nested/preview.png");
    let output = sandbox(&["render", "--out", path_arg(&out), "--size", "64x48"]);
    assert_success(&output);
    let image = image::open(&out).expect("the preview is a readable image");
    assert!(matches!(image, image::DynamicImage::ImageRgba8(_)));
    assert_eq!((image.width(), image.height()), (64, 48));
}

#[test]
fn the_uv_view_is_a_raw_16_bit_png_with_a_full_march_in_the_middle() {
    let dir = TempDir::new("uv");
    let out = dir.join("uv.png");
    let output = sandbox(&[
        "render",
        "--debug-view",
        "uv",
        "--out",
        path_arg(&out),
        // 256-texel bricks on 64 pixels: mip level 2, clear of the LOD band starting at 3.
        "--size",
        "64x64",
    ]);
    assert_success(&output);
    let image = image::open(&out).expect("the preview is a readable image");
    let image::DynamicImage::ImageRgb16(pixels) = image else {
        panic!("expected a 16-bit RGB PNG, got {:?}", image.color());
    };
    assert_eq!(pixels.dimensions(), (64, 64));
    let [_u, _v, region] = pixels.get_pixel(32, 32).0;
    assert_eq!(region, 65535, "B = 1 where the full march ran");
}

#[test]
fn a_depth_map_renders_with_normal_mapping_that_sinks_its_white() {
    let dir = TempDir::new("depth-map");
    // A depth map: a white (deep) square in a black (top) tile, so a pit.
    let depth = dir.join("depth-map.png");
    image::GrayImage::from_fn(32, 32, |x, y| {
        let inside = (8..24).contains(&x) && (8..24).contains(&y);
        image::Luma([if inside { 255 } else { 0 }])
    })
    .save(&depth)
    .unwrap();
    let image = rendered(
        &dir,
        "depth.png",
        "render",
        &[
            "--method",
            "normal",
            "--height",
            path_arg(&depth),
            "--height-convention",
            "depth",
            "--size",
            "32x32",
        ],
    );
    assert_eq!(image.dimensions(), (32, 32));
    // The preview's defaults (`render --help`): looking straight down at the tile filling the
    // image, +u up it and +v to the right, the light 45° from the −u side. The pit's walls
    // across u lie on rows 8 (u = ¾) and 24 (u = ¼); the middle columns cross neither v wall.
    let row = |y: u32| {
        (11..21)
            .map(|x| brightness(image.get_pixel(x, y)))
            .sum::<i32>()
            / 10
    };
    let flat = row(16);
    let darkest = |rows: std::ops::Range<u32>| rows.map(row).min().unwrap();
    let (far_wall, near_wall) = (darkest(5..11), darkest(21..27));
    eprintln!("flat {flat}, far wall {far_wall}, near wall {near_wall}");
    // The wall nearer the light climbs out of the pit away from it, so it turns from the
    // light; the far wall faces it. A raised square (white read as top) swaps them.
    assert!(
        near_wall * 10 < flat * 6,
        "the pit's wall turned from the light is not dark: {near_wall} vs {flat} on the flat"
    );
    assert!(
        far_wall * 10 > flat * 9,
        "the pit's wall facing the light is dark: {far_wall} vs {flat} on the flat"
    );
}

#[test]
fn an_unknown_anti_aliasing_is_rejected_with_the_valid_ones() {
    let dir = TempDir::new("bad-aa");
    let out = dir.join("out.png");
    for command in ["render", "snapshot"] {
        let output = sandbox(&[command, "--out", path_arg(&out), "--aa", "msaa"]);
        assert_one_line_error(&output, &["msaa", "--aa", "off", "fxaa", "taa"]);
    }
    assert!(!out.exists());
}

#[test]
fn out_of_range_anti_aliasing_parameters_are_rejected_naming_the_flag_and_the_limit() {
    let dir = TempDir::new("bad-taa");
    let out = dir.join("out.png");
    for (flag, bad, limit) in [
        ("--taa-current-weight", "5", "at most 1"),
        ("--taa-current-weight", "NaN", "NaN"),
        ("--taa-jitter-samples", "100", "at most 64"),
        ("--taa-jitter-samples", "2.5", "whole number"),
        ("--taa-clip-gamma", "0", "at least 0.25"),
        ("--taa-mip-bias", "1", "at most 0"),
        ("--taa-mip-bias", "-3", "at least -2"),
        ("--taa-still-weight", "0", "at least 0.01"),
        ("--fxaa-subpixel-blending", "2", "at most 1"),
        ("--fxaa-contrast-threshold", "-0.5", "at least 0"),
        ("--fxaa-relative-threshold", "inf", "not a finite number"),
    ] {
        let output = sandbox(&["render", "--out", path_arg(&out), "--aa", "taa", flag, bad]);
        assert_one_line_error(&output, &[flag, limit]);
    }
    assert!(!out.exists());
}

#[test]
fn the_post_filter_and_taa_soften_the_previews_edges() {
    let dir = TempDir::new("aa");
    // The cube's outline against the background, and the relief's edges: anti-aliasing
    // spreads each step over more pixels, so the sum of the steps between neighbours falls.
    let render = |aa: &str| {
        rendered(
            &dir,
            &format!("cube-{aa}.png"),
            "render",
            &[
                "--size",
                "48x48",
                "--shape",
                "cube",
                "--view-angle",
                "30",
                "--aa",
                aa,
            ],
        )
    };
    let total_variation = |image: &image::RgbaImage| -> i64 {
        let (width, height) = image.dimensions();
        let mut total = 0;
        for y in 0..height {
            for x in 1..width {
                let step =
                    brightness(image.get_pixel(x, y)) - brightness(image.get_pixel(x - 1, y));
                total += i64::from(step.abs());
            }
        }
        total
    };
    let [off, fxaa, taa] = ["off", "fxaa", "taa"].map(|aa| total_variation(&render(aa)));
    assert!(fxaa < off, "fxaa {fxaa}, off {off}");
    assert!(taa < off, "taa {taa}, off {off}");
}

#[test]
fn a_preset_with_layers_renders_them_from_its_files_and_names_a_bad_one() {
    let dir = TempDir::new("layered-preset");
    // Two solid colours, a flat height each, and a weight map: red (the first layer) on the
    // left half of the plane, green (the second) on the right.
    let solid = |name: &str, rgb: [u8; 3]| {
        image::RgbaImage::from_pixel(4, 4, image::Rgba([rgb[0], rgb[1], rgb[2], 255]))
            .save(dir.join(name))
            .unwrap();
    };
    solid("warm.png", [220, 80, 40]);
    solid("cool.png", [40, 90, 220]);
    image::GrayImage::from_pixel(4, 4, image::Luma([200]))
        .save(dir.join("height.png"))
        .unwrap();
    image::RgbaImage::from_fn(16, 4, |x, _| {
        if x < 8 {
            image::Rgba([255, 0, 0, 0])
        } else {
            image::Rgba([0, 255, 0, 0])
        }
    })
    .save(dir.join("weights.png"))
    .unwrap();
    let preset = dir.join("layers.ron");
    std::fs::write(
        &preset,
        "(layers: [(base_color_texture: \"warm.png\", height_texture: \"height.png\"), \
          (base_color_texture: \"cool.png\", height_texture: \"height.png\", tiling: 2)], \
          layer_weights_texture: \"weights.png\", shadows: off)",
    )
    .unwrap();
    let image = rendered(
        &dir,
        "layers.png",
        "render",
        &["--size", "64x64", "--preset", path_arg(&preset)],
    );
    let warm = image.pixels().filter(|p| p.0[0] > p.0[2] + 60).count();
    let cool = image.pixels().filter(|p| p.0[2] > p.0[0] + 60).count();
    assert!(
        warm > 800 && cool > 800,
        "warm {warm}, cool {cool} of 4096 pixels"
    );

    let outside = dir.join("outside.ron");
    std::fs::write(&outside, "(layers: [(height_texture: \"../height.png\")])").unwrap();
    let out = dir.join("never.png");
    let output = sandbox(&[
        "render",
        "--out",
        path_arg(&out),
        "--preset",
        path_arg(&outside),
    ]);
    assert_one_line_error(
        &output,
        &["--preset", "../height.png", "`..` leads out of it"],
    );
    assert!(!out.exists());
}
