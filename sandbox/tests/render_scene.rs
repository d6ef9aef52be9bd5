//! `sandbox render --scene` run as a user runs it: the built binary on small glTF files written
//! here, its exit status, its stderr and the PNG it writes. The tests that render need a Vulkan
//! driver; `tests/run` pins the software one.

mod common;

use std::path::{Path, PathBuf};
use std::process::Output;

use common::*;

/// The `warning:` lines on stderr (a software Vulkan driver may add lines of its own).
fn warnings(output: &Output) -> Vec<String> {
    String::from_utf8_lossy(&output.stderr)
        .lines()
        .filter(|line| line.starts_with("warning: "))
        .map(str::to_owned)
        .collect()
}

/// Renders `scene` at 32×32 with `extra` options; asserts success and returns the output and
/// the image.
fn render(scene: &Path, out: &Path, extra: &[&str]) -> (Output, image::DynamicImage) {
    let mut args = vec![
        "render",
        "--scene",
        path_arg(scene),
        "--out",
        path_arg(out),
        "--size",
        "32x32",
    ];
    args.extend_from_slice(extra);
    let output = sandbox(&args);
    assert_success(&output);
    let image = image::open(out).expect("the render is a readable image");
    assert_eq!((image.width(), image.height()), (32, 32));
    (output, image)
}

/// Bytes of the quad's buffer: a 2×2 quad in the XZ plane facing +Y, as positions, normals and
/// UVs (f32) and six u16 indices.
fn quad_bin() -> Vec<u8> {
    let positions = [
        -1.0, 0.0, -1.0, -1.0, 0.0, 1.0, 1.0, 0.0, 1.0, 1.0, 0.0, -1.0,
    ];
    let normals = [0.0, 1.0, 0.0].repeat(4);
    let uvs = [0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0, 0.0];
    let mut bin = Vec::new();
    for value in positions.iter().chain(&normals).chain(&uvs) {
        bin.extend_from_slice(&f32::to_le_bytes(*value));
    }
    for index in [0_u16, 1, 2, 0, 2, 3] {
        bin.extend_from_slice(&index.to_le_bytes());
    }
    assert_eq!(bin.len(), QUAD_BIN_LENGTH);
    bin
}

const QUAD_BIN_LENGTH: usize = 48 + 48 + 32 + 12;

/// The quad's one primitive (accessors 0..=3, material 0).
const QUAD_PRIMITIVE: &str =
    r#"{"attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2}, "indices": 3, "material": 0}"#;

/// A glTF document: the quad on node 0, and whatever a test adds, as JSON text.
struct Gltf {
    /// Nodes after the quad's; every node is a root of the scene.
    nodes: Vec<String>,
    /// Primitives of the quad's mesh.
    primitives: Vec<String>,
    /// The quad's material.
    material: String,
    /// More top-level members, as `"key": value`.
    members: Vec<String>,
    extensions_used: Vec<&'static str>,
    extensions_required: Vec<&'static str>,
    /// Extra files next to the document: (name, bytes).
    files: Vec<(String, Vec<u8>)>,
}

impl Gltf {
    /// The quad with a plain (lit) material; no camera, no light.
    fn quad() -> Self {
        Self {
            nodes: Vec::new(),
            primitives: vec![QUAD_PRIMITIVE.to_owned()],
            material: r#"{"name": "surface"}"#.to_owned(),
            members: Vec::new(),
            extensions_used: Vec::new(),
            extensions_required: Vec::new(),
            files: Vec::new(),
        }
    }

    /// Adds a directional light shining down and forwards (KHR_lights_punctual).
    fn with_light(mut self) -> Self {
        self.extensions_used.push("KHR_lights_punctual");
        self.members.push(
            r#""extensions": {"KHR_lights_punctual": {"lights": [{"type": "directional", "intensity": 200000.0}]}}"#
                .to_owned(),
        );
        self.nodes.push(
            r#"{"name": "sun", "rotation": [-0.5, 0.0, 0.0, 0.8660254], "extensions": {"KHR_lights_punctual": {"light": 0}}}"#
                .to_owned(),
        );
        self
    }

    /// Adds two cameras: 0 in front of the quad looking slightly down, 1 straight above it.
    fn with_two_cameras(mut self) -> Self {
        self.members.push(
            r#""cameras": [
                {"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.05, "zfar": 100.0}},
                {"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.05, "zfar": 100.0}}
            ]"#
            .to_owned(),
        );
        self.nodes.push(
            r#"{"name": "front", "camera": 0, "translation": [0.0, 1.0, 3.0], "rotation": [-0.17364818, 0.0, 0.0, 0.98480775]}"#
                .to_owned(),
        );
        self.nodes.push(
            r#"{"name": "above", "camera": 1, "translation": [0.0, 3.0, 0.0], "rotation": [-0.70710678, 0.0, 0.0, 0.70710678]}"#
                .to_owned(),
        );
        self
    }

    /// Makes the quad's material a parallax material with a 16×16 height ramp.
    fn with_parallax_material(mut self) -> Self {
        self.material =
            r#"{"name": "relief", "extras": {"pom": {"height_texture": 0, "height_scale": 0.05}}}"#
                .to_owned();
        self.members
            .push(r#""images": [{"uri": "height.png"}], "textures": [{"source": 0}]"#.to_owned());
        let ramp = image::GrayImage::from_fn(16, 16, |x, _| image::Luma([(x * 16) as u8]));
        let mut png = std::io::Cursor::new(Vec::new());
        ramp.write_to(&mut png, image::ImageFormat::Png)
            .expect("encoding the height map");
        self.files.push(("height.png".to_owned(), png.into_inner()));
        self
    }

    /// The document, with `buffer` as buffer 0.
    fn json(&self, buffer: &str) -> String {
        let roots: Vec<String> = (0..=self.nodes.len()).map(|n| n.to_string()).collect();
        let mut nodes = vec![r#"{"name": "quad", "mesh": 0}"#.to_owned()];
        nodes.extend(self.nodes.iter().cloned());
        let list = |names: &[&str]| {
            let quoted: Vec<String> = names.iter().map(|name| format!("{name:?}")).collect();
            format!("[{}]", quoted.join(", "))
        };
        let mut members = self.members.clone();
        if !self.extensions_used.is_empty() {
            members.push(format!(
                r#""extensionsUsed": {}"#,
                list(&self.extensions_used)
            ));
        }
        if !self.extensions_required.is_empty() {
            members.push(format!(
                r#""extensionsRequired": {}"#,
                list(&self.extensions_required)
            ));
        }
        let members: String = members
            .iter()
            .map(|member| format!(",\n  {member}"))
            .collect();
        format!(
            r#"{{
  "asset": {{"version": "2.0"}},
  "scene": 0,
  "scenes": [{{"nodes": [{roots}]}}],
  "nodes": [{nodes}],
  "meshes": [{{"name": "quad", "primitives": [{primitives}]}}],
  "materials": [{material}],
  "accessors": [
    {{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [-1.0, 0.0, -1.0], "max": [1.0, 0.0, 1.0]}},
    {{"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC3"}},
    {{"bufferView": 2, "componentType": 5126, "count": 4, "type": "VEC2"}},
    {{"bufferView": 3, "componentType": 5123, "count": 6, "type": "SCALAR"}}
  ],
  "bufferViews": [
    {{"buffer": 0, "byteOffset": 0, "byteLength": 48}},
    {{"buffer": 0, "byteOffset": 48, "byteLength": 48}},
    {{"buffer": 0, "byteOffset": 96, "byteLength": 32}},
    {{"buffer": 0, "byteOffset": 128, "byteLength": 12}}
  ],
  "buffers": [{buffer}]{members}
}}
"#,
            roots = roots.join(", "),
            nodes = nodes.join(",\n    "),
            primitives = self.primitives.join(", "),
            material = self.material,
        )
    }

    /// Writes `NAME.gltf`, its `quad.bin` and its other files into `dir`; returns the
    /// document's path.
    fn write(&self, dir: &TempDir, name: &str) -> PathBuf {
        let buffer = format!(r#"{{"uri": "quad.bin", "byteLength": {QUAD_BIN_LENGTH}}}"#);
        std::fs::write(dir.join("quad.bin"), quad_bin()).expect("writing the buffer");
        for (file, bytes) in &self.files {
            std::fs::write(dir.join(file), bytes).expect("writing a file");
        }
        let path = dir.join(&format!("{name}.gltf"));
        std::fs::write(&path, self.json(&buffer)).expect("writing the document");
        path
    }

    /// The bytes of a binary glTF: the 12-byte header, the JSON chunk (padded with spaces)
    /// and the BIN chunk holding the quad's buffer.
    fn glb(&self) -> Vec<u8> {
        assert!(
            self.files.is_empty(),
            "a GLB fixture carries no other files"
        );
        let mut json = self
            .json(&format!(r#"{{"byteLength": {QUAD_BIN_LENGTH}}}"#))
            .into_bytes();
        while !json.len().is_multiple_of(4) {
            json.push(b' ');
        }
        let bin = quad_bin();
        assert!(bin.len().is_multiple_of(4));
        let total = 12 + 8 + json.len() + 8 + bin.len();
        let mut glb = Vec::with_capacity(total);
        glb.extend_from_slice(b"glTF");
        glb.extend_from_slice(&2_u32.to_le_bytes());
        glb.extend_from_slice(&(total as u32).to_le_bytes());
        glb.extend_from_slice(&(json.len() as u32).to_le_bytes());
        glb.extend_from_slice(b"JSON");
        glb.extend_from_slice(&json);
        glb.extend_from_slice(&(bin.len() as u32).to_le_bytes());
        glb.extend_from_slice(b"BIN\0");
        glb.extend_from_slice(&bin);
        glb
    }
}

#[test]
fn the_view_options_move_the_automatic_camera_of_a_scene() {
    let dir = TempDir::new("scene-view");
    let scene = Gltf::quad()
        .with_light()
        .with_two_cameras()
        .write(&dir, "scene");
    let (_, auto) = render(&scene, &dir.join("auto.png"), &["--camera", "auto"]);
    // Given without --camera, they imply the automatic camera.
    let (output, above) = render(
        &scene,
        &dir.join("above.png"),
        &["--view-angle", "0", "--distance", "1.5"],
    );
    assert_eq!(warnings(&output), Vec::<String>::new());
    assert_ne!(auto.to_rgba8().as_raw(), above.to_rgba8().as_raw());
    let (_, turned) = render(
        &scene,
        &dir.join("turned.png"),
        &["--camera", "auto", "--view-azimuth", "120"],
    );
    assert_ne!(auto.to_rgba8().as_raw(), turned.to_rgba8().as_raw());
    // They move the automatic camera, not one of the file's.
    let out = dir.join("contradiction.png");
    let output = sandbox(&[
        "render",
        "--scene",
        path_arg(&scene),
        "--camera",
        "1",
        "--view-angle",
        "30",
        "--out",
        path_arg(&out),
    ]);
    assert_one_line_error(&output, &["--view-angle", "automatic camera", "--camera 1"]);
    assert!(!out.exists());
}

#[test]
fn a_file_camera_and_the_auto_camera_both_render_and_differ() {
    let dir = TempDir::new("cameras");
    let scene = Gltf::quad()
        .with_light()
        .with_two_cameras()
        .write(&dir, "scene");
    let (above, from_above) = render(&scene, &dir.join("above.png"), &["--camera", "1"]);
    let (auto, from_auto) = render(&scene, &dir.join("auto.png"), &["--camera", "auto"]);
    assert_eq!(warnings(&above), Vec::<String>::new());
    assert_eq!(warnings(&auto), Vec::<String>::new());
    assert_ne!(
        from_above.to_rgba8().as_raw(),
        from_auto.to_rgba8().as_raw(),
        "camera 1 and the auto camera drew the same picture"
    );

    let out = dir.join("missing.png");
    let output = sandbox(&[
        "render",
        "--scene",
        path_arg(&scene),
        "--camera",
        "5",
        "--out",
        path_arg(&out),
    ]);
    assert_one_line_error(&output, &["--camera 5", "scene.gltf", "has 2 cameras"]);
    assert!(!out.exists());
}

#[test]
fn a_scene_without_lights_gets_a_default_light_and_says_so() {
    let dir = TempDir::new("no-lights");
    let scene = Gltf::quad().write(&dir, "unlit");
    let (output, image) = render(&scene, &dir.join("unlit.png"), &[]);
    let warnings = warnings(&output);
    assert_eq!(warnings.len(), 1, "{warnings:?}");
    assert!(warnings[0].contains("default light"), "{warnings:?}");
    assert!(warnings[0].contains("unlit.gltf"), "{warnings:?}");
    // The lit quad is in the middle of the three-quarter view, brighter than the background.
    let rgba = image.to_rgba8();
    let [r, g, b, _] = rgba.get_pixel(16, 16).0;
    let [r0, g0, b0, _] = rgba.get_pixel(0, 0).0;
    assert!(
        u32::from(r) + u32::from(g) + u32::from(b) > u32::from(r0) + u32::from(g0) + u32::from(b0),
        "the middle ({r}, {g}, {b}) is not brighter than the corner ({r0}, {g0}, {b0})"
    );
}

#[test]
fn unsupported_features_are_one_warning_each_and_the_rest_renders() {
    let dir = TempDir::new("unsupported");
    let mut gltf = Gltf::quad().with_light();
    gltf.primitives.push(
        r#"{"attributes": {"POSITION": 0}, "indices": 3, "material": 0, "mode": 1}"#.to_owned(),
    );
    gltf.extensions_used.push("EXT_made_up");
    gltf.extensions_required.push("EXT_made_up");
    let scene = gltf.write(&dir, "unsupported");
    let out = dir.join("unsupported.png");
    let (output, _) = render(&scene, &out, &[]);
    let warnings = warnings(&output);
    assert_eq!(warnings.len(), 2, "{warnings:?}");
    assert_eq!(
        warnings
            .iter()
            .filter(|line| line.contains("EXT_made_up"))
            .count(),
        1,
        "{warnings:?}"
    );
    assert_eq!(
        warnings.iter().filter(|line| line.contains("mode")).count(),
        1,
        "{warnings:?}"
    );
    assert!(out.exists());
}

#[test]
fn a_truncated_glb_is_one_error_naming_the_file() {
    let dir = TempDir::new("truncated-glb");
    let glb = Gltf::quad().with_light().glb();
    // The whole file renders, so what breaks below is the truncation alone.
    let whole = dir.join("whole.glb");
    std::fs::write(&whole, &glb).unwrap();
    render(&whole, &dir.join("whole.png"), &[]);

    let truncated = dir.join("truncated.glb");
    std::fs::write(&truncated, &glb[..glb.len() / 2]).unwrap();
    let out = dir.join("truncated.png");
    let output = sandbox(&[
        "render",
        "--scene",
        path_arg(&truncated),
        "--out",
        path_arg(&out),
    ]);
    assert_one_line_error(&output, &["truncated.glb"]);
    assert!(!out.exists());
}

#[test]
fn material_preview_options_with_a_scene_are_a_usage_error() {
    let dir = TempDir::new("conflict");
    let out = dir.join("out.png");
    let output = sandbox(&[
        "render",
        "--scene",
        "scene.gltf",
        "--height",
        "x.png",
        "--out",
        path_arg(&out),
    ]);
    assert_one_line_error(&output, &["--scene", "--height"]);
    assert_eq!(output.status.code(), Some(2), "clap's usage-error status");
    assert!(!out.exists());

    let output = sandbox(&["render", "--camera", "1", "--out", path_arg(&out)]);
    assert_one_line_error(&output, &["--scene"]);
    assert!(!out.exists());
}

#[test]
fn the_uv_view_of_a_scene_is_a_raw_16_bit_png() {
    let dir = TempDir::new("uv");
    let scene = Gltf::quad()
        .with_light()
        .with_parallax_material()
        .write(&dir, "relief");
    let out = dir.join("uv.png");
    let output = sandbox(&[
        "render",
        "--debug-view",
        "uv",
        "--scene",
        path_arg(&scene),
        "--out",
        path_arg(&out),
        "--size",
        "32x32",
    ]);
    assert_success(&output);
    let image = image::open(&out).expect("the render is a readable image");
    let image::DynamicImage::ImageRgb16(pixels) = image else {
        panic!("expected a 16-bit RGB PNG, got {:?}", image.color());
    };
    assert_eq!(pixels.dimensions(), (32, 32));
    let [_u, _v, region] = pixels.get_pixel(16, 16).0;
    assert_eq!(region, 65535, "B = 1 where the full march ran");
}

#[test]
fn a_scene_without_meshes_frames_a_unit_box_with_a_warning() {
    let dir = TempDir::new("empty");
    let scene = dir.join("empty.gltf");
    std::fs::write(
        &scene,
        r#"{"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"name": "empty"}]}"#,
    )
    .unwrap();
    let (output, _) = render(&scene, &dir.join("empty.png"), &[]);
    let warnings = warnings(&output);
    assert_eq!(warnings.len(), 2, "{warnings:?}");
    assert!(warnings[0].contains("unit box"), "{warnings:?}");
    assert!(warnings[1].contains("default light"), "{warnings:?}");
}

/// `render --scene` of the shipped street corner, with `extra` flags, against a reference of
/// tests/golden (the library's golden tests compare the same references with FLIP).
fn street_corner_matches(extra: &[&str], reference_name: &str) {
    let repository = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let out = std::env::temp_dir().join(format!(
        "pom-street-corner-{}-{reference_name}",
        std::process::id()
    ));
    let output = std::process::Command::new(env!("CARGO_BIN_EXE_sandbox"))
        .args(["render", "--scene"])
        .arg(repository.join("assets/street_corner.glb"))
        .args(["--size", "384x216"])
        .args(extra)
        .arg("--out")
        .arg(&out)
        .output()
        .expect("run the sandbox");
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let rendered = image::open(&out).expect("the render").to_rgba8();
    let reference = image::open(repository.join("tests/golden").join(reference_name))
        .expect("the reference")
        .to_rgba8();
    assert_eq!(rendered.dimensions(), reference.dimensions());
    let total: u64 = rendered
        .as_raw()
        .iter()
        .zip(reference.as_raw())
        .map(|(a, b)| u64::from(a.abs_diff(*b)))
        .sum();
    let mean = total as f64 / rendered.as_raw().len() as f64;
    assert!(
        mean < 1.0,
        "{extra:?}: mean difference {mean} levels from {reference_name}"
    );
}

#[test]
fn the_shipped_street_corner_renders_like_its_reference() {
    // Scene shadows are on by default in `render`.
    street_corner_matches(&[], "street_corner_shadows.png");
    street_corner_matches(&["--scene-shadows", "off"], "street_corner.png");
}
