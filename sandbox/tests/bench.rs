//! `sandbox bench --quick` on the software driver: it runs, and its JSON, CSV and PNG parse.
//! The figures are lavapipe's and mean nothing about speed; nothing here asserts speed.

mod common;

use common::*;

#[test]
fn quick_bench_writes_json_csv_and_a_chart() {
    let dir = TempDir::new("bench-quick");
    let out = dir.join("results");
    let output = sandbox(&[
        "bench",
        "--quick",
        "--entities",
        "200",
        "--out",
        path_arg(&out),
    ]);
    assert_success(&output);
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(stdout.contains("median"), "no table printed:\n{stdout}");

    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("bench.json")).unwrap()).unwrap();
    assert!(
        json["adapter"]["name"]
            .as_str()
            .is_some_and(|n| !n.is_empty())
    );
    assert_eq!(json["quick"], true);
    let cases = json["cases"].as_array().unwrap();
    // Two sizes: 18 method × shadow cases, 5 sample counts, 6 LOD thresholds, POM for the
    // texel rate, 3 phases, 2 far-field, 6 overdraw (1 plane, 4 back to front, 4 copies of one
    // mesh; with and without depth offset), 32 scene-shadow figures (the street corner lit by
    // a sun, a spot, a point light: without shadows 3 phases and the frame, with shadows 4
    // phases and the frame; and a moving sun with shadows), 8 seed-port figures (ours, the
    // seed's listing 2 as a fragment pass and as compute passes over the plane's triangle and
    // over the plane solved on the CPU, near and far; and ours' resolve, near and far, where
    // ours ran deferred), 13 rows of the method table (steep, POM, relief at 4 sample counts; max-mip);
    // once, at the first size, max-mip's pyramid rebuilt every frame for two map sizes; and
    // 6 first-use figures (settled before, the first frame, settled after; blocking and in the
    // background), 6 silhouette figures (the cube and the sphere with each mode), and
    // 11 antialiasing figures (post for each mode, the post filter, TAA, and the march at 50
    // and at 16 jittered samples with one and with three secant steps under TAA, at 50
    // without TAA's mip bias, and at 50 under the post filter and off), 12 environment figures
    // (the street corner without an environment, 3 phases and the frame, and under the sky,
    // with the background's pass too; relief occlusion off and on; a 2K `.hdr`'s prefiltering),
    // 24 lights figures (the street corner at night with 1, 256 and 1,024 point lights, and 256
    // with one shadowed light: 3 phases, the frame, and the CPU's Extract and Prepare stages),
    // 4 layers figures (the material, and its heights as one, four alike and four differently
    // tiled layers) and 2 triplanar figures (the sphere by uv and triplanar).
    let resolve_rows = cases
        .iter()
        .filter(|c| c["group"] == "seed_port" && c["pass"] == "resolve")
        .count();
    let ours_deferred = cases
        .iter()
        .filter(|c| c["group"] == "seed_port" && c["variant"] == "ours" && c["path"] == "deferred")
        .count();
    assert_eq!(resolve_rows, 2 * ours_deferred);
    assert_eq!(
        cases.len(),
        2 * (18 + 5 + 6 + 1 + 3 + 2 + 6 + 32 + 8 + 13 + 6 + 6 + 11 + 12 + 24 + 4 + 2)
            + 2
            + resolve_rows
    );
    let first_frames = cases
        .iter()
        .filter(|c| {
            c["group"] == "first_use"
                && c["variant"]
                    .as_str()
                    .is_some_and(|v| v.starts_with("first frame of the variant"))
        })
        .count();
    assert_eq!(first_frames, 4, "two sizes, blocking and background");
    // The quick bench's own map is 256², its large map 2048².
    for map in ["256x256 map", "2048x2048 map"] {
        assert!(
            cases.iter().any(|c| c["group"] == "pyramid_build"
                && c["pass"] == "derived textures"
                && c["variant"] == map),
            "no pyramid build for the {map}"
        );
    }
    let table = json["method_table"].as_array().unwrap();
    assert_eq!(table.len(), 2 * 13);
    for row in table {
        let fetches = row["fetches_per_pixel"].as_f64().unwrap();
        assert!(fetches > 0.0, "{row}");
        // The error columns come from the CPU reference: max-mip's is the exact answer.
        if row["method"] == "maxmip" {
            assert!(row["mean_error_texels"].as_f64().unwrap() < 0.05, "{row}");
        }
    }
    for variant in [
        "ours",
        "seed port, fragment pass",
        "seed port, compute pass",
        "ours, far field",
        "seed port, far field, fragment pass",
        "seed port, far field, compute pass",
    ] {
        assert!(
            cases
                .iter()
                .any(|c| c["group"] == "seed_port" && c["variant"] == variant)
        );
    }
    for light in ["sun, 3 cascades", "spot, 1 map", "point, 6 faces"] {
        assert!(
            cases.iter().any(|c| c["group"] == "scene_shadows"
                && c["pass"] == "shadows"
                && c["variant"] == light),
            "no shadow phase for {light}"
        );
    }
    for phase in ["prepass", "opaque", "post"] {
        assert!(
            cases
                .iter()
                .any(|c| c["group"] == "phases" && c["pass"] == phase)
        );
    }
    for case in cases {
        // The seed port's compute pass runs on neither render path.
        let compute_pass = case["variant"]
            .as_str()
            .is_some_and(|v| v.contains("compute pass"));
        if compute_pass {
            assert_eq!(case["path"], "compute", "{case}");
            assert_eq!(case["pass"], "seed port compute", "{case}");
        } else {
            assert!(
                case["path"] == "forward" || case["path"] == "deferred",
                "{case}"
            );
        }
        let spread = &case["spread"];
        for field in ["median_ms", "min_ms", "p10_ms", "p90_ms", "max_ms"] {
            let ms = spread[field].as_f64().unwrap();
            assert!(ms.is_finite() && ms > 0.0, "{field} = {ms} in {case}");
        }
        assert!(spread["min_ms"].as_f64() <= spread["median_ms"].as_f64());
        assert!(spread["median_ms"].as_f64() <= spread["max_ms"].as_f64());
        // A first-use frame is one frame by nature; every other case times the quick five.
        let first_use_frame = case["variant"]
            .as_str()
            .is_some_and(|v| v.starts_with("first frame of the variant"));
        assert_eq!(
            spread["count"],
            if first_use_frame { 1 } else { 5 },
            "{case}"
        );
    }
    let ratios = json["ratios"].as_array().unwrap();
    assert!(
        ratios
            .iter()
            .any(|r| r["what"].as_str().unwrap().contains("far field"))
    );
    assert!(ratios.iter().all(|r| r["ratio"].as_f64().unwrap() > 0.0));
    assert!(
        ratios
            .iter()
            .any(|r| r["what"].as_str().unwrap().starts_with("overdraw"))
    );
    let rates = json["sample_rates"].as_array().unwrap();
    assert_eq!(rates.len(), 2, "one sample rate per size");
    for rate in rates {
        let count = &rate["count"];
        let (total, marching) = (
            count["total"].as_u64().unwrap(),
            count["marching_pixels"].as_u64().unwrap(),
        );
        assert!(marching > 0 && marching <= count["surface_pixels"].as_u64().unwrap());
        // Every marching pixel takes at least one sample.
        assert!(total >= marching, "{rate}");
        for field in [
            "gsamples_per_s",
            "fragment_path_gtexels_per_s",
            "one_tap_pass_ms",
        ] {
            assert!(rate[field].as_f64().unwrap() > 0.0, "{field} in {rate}");
        }
    }
    // One path asked for (auto): one comparison and one CPU side.
    assert_eq!(json["paths"], serde_json::json!(["auto"]));
    assert_eq!(json["versus_mesh"].as_array().unwrap().len(), 1);
    let versus = &json["versus_mesh"][0];
    let candidates = versus["candidates"].as_array().unwrap();
    for kind in ["pom", "mesh"] {
        assert!(
            candidates.iter().any(|c| c["kind"] == kind),
            "no {kind} candidate"
        );
    }
    for candidate in candidates {
        let flip = candidate["flip_mean"].as_f64().unwrap();
        assert!((0.0..=1.0).contains(&flip), "{candidate}");
    }
    assert!(versus["reference_triangles"].as_u64().unwrap() > 2);
    for file in ["versus_reference.png", "versus_pom.png"] {
        let image = image::open(out.join(file)).unwrap();
        assert!(image.width() > 0 && image.height() > 0);
    }
    // None, a tenth and all of the entities turning; then a tenth and all under TAA; then a
    // tenth walking; then none, a tenth and a tenth under TAA holding one shared material.
    let cpu_side = json["cpu_side"].as_array().unwrap();
    let cpu_cases: Vec<_> = cpu_side
        .iter()
        .map(|cpu| {
            let case = (
                &cpu["moving_percent"],
                &cpu["anti_aliasing"],
                &cpu["motion"],
                &cpu["materials"],
            );
            serde_json::json!(case)
        })
        .collect();
    let expected: Vec<_> = [
        (0, "off", "turning", "copies"),
        (10, "off", "turning", "copies"),
        (100, "off", "turning", "copies"),
        (10, "taa", "turning", "copies"),
        (100, "taa", "turning", "copies"),
        (10, "off", "walking", "copies"),
        (0, "off", "turning", "shared"),
        (10, "off", "turning", "shared"),
        (10, "taa", "turning", "shared"),
    ]
    .map(|case| serde_json::json!(case))
    .into();
    assert_eq!(cpu_cases, expected);
    for cpu in cpu_side {
        assert_eq!(cpu["entities"], 200);
        assert!(cpu["total"]["median_ms"].as_f64().unwrap() > 0.0);
        assert!(cpu["transforms"]["median_ms"].as_f64().unwrap() > 0.0);
    }
    assert!(json["adapter"]["software_driver"].is_boolean());
    // Frames whose timestamps were rejected or missing are counted, not reused.
    assert!(json["dropped_frames"].is_u64());

    let csv = std::fs::read_to_string(out.join("bench.csv")).unwrap();
    let mut lines = csv.lines();
    assert_eq!(
        lines.next().unwrap(),
        "group,method,shadows,width,height,min_samples,max_samples,lod_threshold,tiling,path,\
         pass,frames,median_ms,min_ms,p10_ms,p90_ms,max_ms,variant"
    );
    assert_eq!(lines.count(), cases.len());

    let chart = image::open(out.join("bench.png")).unwrap();
    assert_eq!((chart.width(), chart.height()), (1400, 600));
}

#[test]
fn without_timestamps_it_says_so_and_exits_cleanly() {
    let dir = TempDir::new("bench-no-timestamps");
    let out = dir.join("results");
    let output = sandbox(&[
        "bench",
        "--quick",
        "--no-timestamps",
        "--out",
        path_arg(&out),
    ]);
    assert_success(&output);
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(
        stdout.contains("GPU timestamps are not available"),
        "{stdout}"
    );
    assert!(!out.join("bench.json").exists());
}

#[test]
fn too_few_frames_are_rejected() {
    let output = sandbox(&["bench", "--frames", "5"]);
    assert_one_line_error(&output, &["--frames", "5"]);
}

#[test]
fn a_bad_size_is_rejected() {
    let output = sandbox(&["bench", "--size", "wide"]);
    assert_one_line_error(&output, &["--size", "wide"]);
}

#[test]
fn only_makes_just_the_measurements_asked_for() {
    let dir = TempDir::new("bench-only");
    let out = dir.join("results");
    let output = sandbox(&[
        "bench",
        "--quick",
        "--only",
        "far-field",
        "--only",
        "cpu-side",
        "--entities",
        "20",
        "--out",
        path_arg(&out),
    ]);
    assert_success(&output);
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("bench.json")).unwrap()).unwrap();
    let cases = json["cases"].as_array().unwrap();
    assert_eq!(cases.len(), 2 * 2, "two far-field cases per size");
    assert!(cases.iter().all(|c| c["group"] == "far_field"));
    assert!(json["sample_rates"].as_array().unwrap().is_empty());
    assert!(json["versus_mesh"].as_array().unwrap().is_empty());
    assert_eq!(json["cpu_side"][0]["entities"], 20);
    assert!(!out.join("versus_pom.png").exists());
}

#[test]
fn an_unknown_measurement_is_rejected() {
    let output = sandbox(&["bench", "--only", "everything"]);
    assert_one_line_error(&output, &["--only", "everything"]);
}

#[test]
fn both_paths_are_timed_side_by_side_in_one_run() {
    let dir = TempDir::new("bench-both-paths");
    let out = dir.join("results");
    let output = sandbox(&[
        "bench",
        "--quick",
        "--only",
        "phases",
        "--only",
        "seed-port",
        "--path",
        "forward",
        "--path",
        "deferred",
        "--out",
        path_arg(&out),
    ]);
    assert_success(&output);
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("bench.json")).unwrap()).unwrap();
    assert_eq!(json["paths"], serde_json::json!(["forward", "deferred"]));
    let cases = json["cases"].as_array().unwrap();
    let passes = |group: &str, path: &str, size: &str| -> Vec<&str> {
        cases
            .iter()
            .filter(|c| {
                c["group"] == group
                    && c["path"] == path
                    && format!("{}x{}", c["width"], c["height"]) == size
            })
            .map(|c| c["pass"].as_str().unwrap())
            .collect()
    };
    for size in ["64x36", "96x54"] {
        assert_eq!(
            passes("phases", "forward", size),
            ["prepass", "opaque", "post"]
        );
        let deferred = passes("phases", "deferred", size);
        assert!(deferred.contains(&"resolve"), "{size}: {deferred:?}");
        assert_eq!(deferred.last(), Some(&"post"), "{size}: {deferred:?}");
    }
    // The seed port has no deferred shader: its rows ran forward on both runs, ours did not.
    let ran = |variant: &str| -> Vec<&str> {
        cases
            .iter()
            .filter(|c| c["group"] == "seed_port" && c["variant"] == variant)
            .map(|c| c["path"].as_str().unwrap())
            .collect()
    };
    assert_eq!(ran("seed port, fragment pass"), ["forward"; 4]);
    assert_eq!(ran("seed port, compute pass"), ["compute"; 4]);
    assert_eq!(ran("ours"), ["forward", "forward", "deferred", "deferred"]);
    // Ours' resolve only where it ran deferred, and divided by the seed port's compute pass there.
    assert_eq!(ran("ours, resolve"), ["deferred"; 2]);
    let ratios = json["ratios"].as_array().unwrap();
    assert!(ratios.iter().any(|r| r["path"] == "deferred"));
    let over_compute: Vec<_> = ratios
        .iter()
        .filter(|r| r["what"] == "ours, resolve / seed port compute")
        .map(|r| (r["width"].as_u64().unwrap(), r["path"].as_str().unwrap()))
        .collect();
    assert_eq!(over_compute, [(64, "deferred"), (96, "deferred")]);
    let over_fragment = ratios
        .iter()
        .filter(|r| r["what"] == "ours / seed port as written (fragment pass)")
        .count();
    assert_eq!(over_fragment, 4, "both paths, both sizes");

    let csv = std::fs::read_to_string(out.join("bench.csv")).unwrap();
    let deferred_rows = csv.lines().filter(|l| l.contains(",deferred,")).count();
    let deferred_cases = cases.iter().filter(|c| c["path"] == "deferred").count();
    assert_eq!(deferred_rows, deferred_cases);
    assert!(deferred_rows > 0);

    let stdout = String::from_utf8_lossy(&output.stdout);
    let summary: Vec<&str> = stdout
        .lines()
        .skip_while(|l| !l.starts_with("phases side by side"))
        .take_while(|l| !l.starts_with("wrote "))
        .collect();
    assert_eq!(summary.len(), 3, "no side-by-side summary:\n{stdout}");
    for (line, size) in summary[1..].iter().zip(["64x36", "96x54"]) {
        assert!(line.starts_with(&format!("{size}: forward ")), "{line}");
        assert!(line.contains("resolve"), "{line}");
        assert!(line.contains("forward / deferred"), "{line}");
    }
}

#[test]
fn only_bench_takes_the_path_more_than_once() {
    let output = sandbox(&["bench", "--path", "forward", "--path", "sideways"]);
    assert_one_line_error(&output, &["--path", "sideways"]);
    let output = sandbox(&["render", "--path", "forward", "--path", "deferred"]);
    assert_one_line_error(&output, &["--path"]);
}
