//! The bad-input corpus (tests/bad_inputs/, listed in its README.md): one test per case, each
//! asserting the specific error (variant, and that the message names the file, field or limit)
//! or the documented clamp with its warning; where a case ends in a usable value, a small frame
//! renders afterwards with no wgpu validation error and no NaN.

use std::path::{Path, PathBuf};
use std::sync::Mutex;

use image::{DynamicImage, GrayImage, Luma, Rgba, Rgba32FImage};
use pom::parallax::MaterialWarnings;
use pom::preview::{PreviewView, spawn_preview};
use pom::{
    App, Assets, Channel, GltfError, HeightSource, Image, ImageError, ParallaxMethod,
    ParallaxOcclusionMaterial, Pixels, PomMaterialError, PomPreset, PresetError, RunOptions,
    ScriptError, TargetFormat, TextureKind, load_gltf, run_script_with,
};
use pom_tests::pom_scene::pom_app;
use pom_tests::render_and_capture_f32;

fn corpus(file: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("bad_inputs")
        .join(file)
}

// ---------------------------------------------------------------- helpers

/// Warnings logged by the library while this test binary runs (tests run in parallel, so each
/// test looks for a message only it can cause).
static WARNINGS: Mutex<Vec<String>> = Mutex::new(Vec::new());

struct WarningLog;

impl log::Log for WarningLog {
    fn enabled(&self, metadata: &log::Metadata<'_>) -> bool {
        metadata.level() <= log::Level::Warn
    }
    fn log(&self, record: &log::Record<'_>) {
        if self.enabled(record.metadata()) {
            let mut warnings = WARNINGS.lock().unwrap_or_else(|e| e.into_inner());
            warnings.push(record.args().to_string());
        }
    }
    fn flush(&self) {}
}

fn warnings_containing(needle: &str) -> Vec<String> {
    static LOGGER: WarningLog = WarningLog;
    // Only the first call installs it; later calls fail harmlessly.
    let _ = log::set_logger(&LOGGER).map(|()| log::set_max_level(log::LevelFilter::Warn));
    WARNINGS
        .lock()
        .unwrap_or_else(|e| e.into_inner())
        .iter()
        .filter(|w| w.contains(needle))
        .cloned()
        .collect()
}

fn install_logger() {
    warnings_containing("");
}

/// A 32² Float32 app showing a plane with `material` at 60°, the sun at 40°.
fn material_app(configure: impl FnOnce(&mut Assets<Image>) -> ParallaxOcclusionMaterial) -> App {
    let mut app = pom_app(32, TargetFormat::Float32).unwrap();
    let images = app.resources.get_mut::<Assets<Image>>().unwrap();
    let material = configure(images);
    let view = PreviewView {
        view_angle: 60.0,
        light_angle: 40.0,
        ..PreviewView::default()
    };
    spawn_preview(&mut app, material, &view).unwrap();
    app
}

/// Renders one frame inside error scopes and checks it is finite and not all black.
fn renders_cleanly(app: &mut App) -> Rgba32FImage {
    let image = render_and_capture_f32(app).unwrap();
    assert!(
        image.pixels().all(|p| p.0.iter().all(|c| c.is_finite())),
        "NaN or ∞ in the frame"
    );
    assert!(
        image.pixels().any(|p| p.0[..3].iter().any(|c| *c > 0.0)),
        "the frame is black"
    );
    image
}

/// A plane whose parallax material takes its height from `height`.
fn render_height_map(height: Image) {
    let mut app = material_app(|images| ParallaxOcclusionMaterial {
        height_map: Some(HeightSource::Texture(images.add(height))),
        ..ParallaxOcclusionMaterial::default()
    });
    renders_cleanly(&mut app);
}

fn image_error(file: &str, kind: TextureKind) -> ImageError {
    let error = Image::load(corpus(file), kind).unwrap_err();
    let name = Path::new(file).file_name().unwrap().to_str().unwrap();
    assert!(error.to_string().contains(name), "{error}");
    error
}

fn assert_load_error(file: &str, reason: &str) {
    match image_error(file, TextureKind::Height) {
        ImageError::Load { path, reason: said } => {
            assert_eq!(path, corpus(file));
            assert!(said.contains(reason), "{said}");
        }
        other => panic!("{file}: expected ImageError::Load, got {other:?}"),
    }
}

// ---------------------------------------------------------------- images

#[test]
fn truncated_png() {
    assert_load_error("images/truncated.png", "unexpected end of file");
}

#[test]
fn corrupt_png_data() {
    assert_load_error("images/corrupt_idat.png", "Corrupt deflate stream");
}

#[test]
fn truncated_jpeg() {
    assert_load_error("images/truncated.jpg", "Not enough bytes");
}

#[test]
fn corrupt_jpeg_huffman_table() {
    assert_load_error("images/corrupt_huffman.jpg", "Huffman table");
}

#[test]
fn zero_byte_png() {
    assert_load_error("images/empty.png", "unexpected end of file");
}

#[test]
fn zero_byte_jpeg() {
    assert_load_error("images/empty.jpg", "Not enough bytes");
}

#[test]
fn text_file_named_png() {
    assert_load_error("images/text_named.png", "Invalid PNG signature");
}

#[test]
fn png_with_zero_width() {
    assert_load_error("images/zero_width.png", "Invalid image dimensions");
}

#[test]
fn missing_image_file() {
    assert_load_error("images/no_such_file.png", "No such file");
}

#[test]
fn float_radiance_hdr_file() {
    // The loader decodes PNG and JPEG only; a float HDR file is named and refused.
    assert_load_error("images/float_radiance.hdr", "format Hdr is not supported");
}

#[test]
fn png_declaring_an_enormous_size_is_refused_before_allocating() {
    let error = image_error("images/declares_enormous_size.png", TextureKind::Color);
    assert!(
        matches!(
            error,
            ImageError::TooLarge {
                width: 1_000_000,
                height: 1_000_000,
                max_side: pom::MAX_IMAGE_SIDE,
                ..
            }
        ),
        "{error:?}"
    );
    assert!(error.to_string().contains("32768 per side"), "{error}");
}

#[test]
fn one_by_one_height_map() {
    let height = Image::load(corpus("images/one_by_one_height.png"), TextureKind::Height).unwrap();
    assert_eq!(height.size(), (1, 1));
    assert_eq!(height.mip_chain().len(), 1);
    render_height_map(height);
}

#[test]
fn non_square_non_power_of_two_height_map() {
    let path = corpus("images/non_square_npot_height.png");
    let height = Image::load(path, TextureKind::Height).unwrap();
    assert_eq!(height.size(), (37, 23));
    let sizes: Vec<_> = height.mip_chain().iter().map(Pixels::dimensions).collect();
    assert_eq!(sizes.last(), Some(&(1, 1)));
    render_height_map(height);
}

#[test]
fn sixteen_bit_height_map() {
    let path = corpus("images/sixteen_bit_height.png");
    let height = Image::load(path, TextureKind::Height).unwrap();
    assert!(matches!(height.pixels(), Pixels::Gray16(_)), "stays 16-bit");
    render_height_map(height);
}

#[test]
fn sixteen_bit_rgba_normal_map_with_alpha_height() {
    let path = corpus("images/sixteen_bit_rgba_normal.png");
    let normal = Image::load(&path, TextureKind::Normal).unwrap();
    assert!(
        matches!(normal.pixels(), Pixels::Rgba8(_)),
        "normals become RGBA8"
    );
    let alpha = Image::load_height(&path, Channel::Alpha).unwrap();
    assert!(
        matches!(alpha.pixels(), Pixels::Gray16(_)),
        "heights keep 16 bits"
    );
    let mut app = material_app(|images| ParallaxOcclusionMaterial {
        normal_map: Some(images.add(normal)),
        height_map: Some(HeightSource::Texture(images.add(alpha))),
        ..ParallaxOcclusionMaterial::default()
    });
    renders_cleanly(&mut app);
}

#[test]
fn float_image_in_memory_with_nan_and_out_of_range_values() {
    // Float images reach the library through `Image::from_decoded` (the file loader has no
    // float format): values are clamped to 0..=1 (NaN becomes 0) at 16 bits.
    let values = [f32::NAN, f32::INFINITY, -5.0, 1e30, 0.25, f32::NEG_INFINITY];
    let float = Rgba32FImage::from_fn(6, 3, |x, _| {
        let v = values[x as usize];
        Rgba([v, v, v, v])
    });
    let decoded = DynamicImage::ImageRgba32F(float);
    let height =
        Image::from_decoded(decoded.clone(), TextureKind::Height, Channel::Red, "float").unwrap();
    let Pixels::Gray16(pixels) = height.pixels() else {
        panic!("a float height becomes 16-bit, got {:?}", height.pixels());
    };
    let row: Vec<u16> = (0..6).map(|x| pixels.get_pixel(x, 0).0[0]).collect();
    assert_eq!(row[1], 65535, "+∞ clamps to white: {row:?}");
    assert_eq!(row[2], 0, "negative clamps to black: {row:?}");
    assert_eq!(row[4], 16384, "0.25: {row:?}");
    let colour = Image::from_decoded(decoded, TextureKind::Color, Channel::Red, "float").unwrap();
    let mut app = material_app(|images| ParallaxOcclusionMaterial {
        base_color_texture: Some(images.add(colour)),
        height_map: Some(HeightSource::Texture(images.add(height))),
        ..ParallaxOcclusionMaterial::default()
    });
    renders_cleanly(&mut app);
}

#[test]
fn palette_png_height_map() {
    let path = corpus("images/palette_height.png");
    let height = Image::load(path, TextureKind::Height).unwrap();
    assert!(matches!(height.pixels(), Pixels::Gray8(_)));
    render_height_map(height);
}

#[test]
fn normal_map_without_alpha_asked_for_an_alpha_height() {
    let error =
        Image::load_height(corpus("images/normal_without_alpha.png"), Channel::Alpha).unwrap_err();
    assert!(matches!(error, ImageError::NoAlpha { .. }), "{error:?}");
    assert!(
        error
            .to_string()
            .contains("normal_without_alpha.png has no alpha channel"),
        "{error}"
    );
}

#[test]
fn grey_with_alpha_gives_an_alpha_height() {
    let height =
        Image::load_height(corpus("images/grey_alpha_height.png"), Channel::Alpha).unwrap();
    let Pixels::Gray8(pixels) = height.pixels() else {
        panic!("8-bit");
    };
    assert_eq!(pixels.get_pixel(3, 0).0, [96], "alpha, not the grey");
    render_height_map(height);
}

#[test]
fn height_map_beyond_the_devices_texture_limit() {
    // Generated at run time: its size depends on the device (lavapipe allows 16384).
    install_logger();
    let probe = pom_app(32, TargetFormat::Float32).unwrap();
    let limit = probe
        .resources
        .get::<pom::GpuContext>()
        .unwrap()
        .device
        .limits()
        .max_texture_dimension_2d;
    drop(probe);
    let width = limit + 1;
    let dir = std::env::temp_dir().join(format!("pom-bad-inputs-wide-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("too_wide.png");
    GrayImage::from_fn(width, 3, |x, _| Luma([(x % 251) as u8]))
        .save(&path)
        .unwrap();
    let height = Image::load(&path, TextureKind::Height).unwrap();
    std::fs::remove_dir_all(&dir).unwrap();
    assert_eq!(height.size(), (width, 3));
    render_height_map(height);
    let expected = format!("is {width}×3, over the device's limit of {limit} texels per side");
    let warned = warnings_containing(&expected);
    assert_eq!(warned.len(), 1, "{warned:?}");
    assert!(
        warned[0].contains(&format!("uploaded at {}×1", width / 2)),
        "{warned:?}"
    );
}

// ---------------------------------------------------------------- glTF

fn gltf_error(file: &str) -> GltfError {
    let mut app = pom_app(8, TargetFormat::Float32).unwrap();
    let error = load_gltf(&mut app, corpus(file)).unwrap_err();
    let name = Path::new(file).file_name().unwrap().to_str().unwrap();
    assert!(error.to_string().contains(name), "{error}");
    assert_eq!(app.world.len(), 0, "nothing half-loaded is left behind");
    error
}

fn assert_mesh_error(file: &str, reason: &str) {
    match gltf_error(file) {
        GltfError::Mesh {
            mesh,
            primitive: 0,
            reason: said,
            ..
        } => {
            assert_eq!(mesh, "\"quad\" (#0)");
            assert!(said.contains(reason), "{said}");
        }
        other => panic!("{file}: expected GltfError::Mesh, got {other:?}"),
    }
}

fn assert_open_error(file: &str, reason: &str) {
    match gltf_error(file) {
        GltfError::Open { reason: said, .. } => assert!(said.contains(reason), "{said}"),
        other => panic!("{file}: expected GltfError::Open, got {other:?}"),
    }
}

fn assert_material_error(file: &str, reason: &str) {
    match gltf_error(file) {
        GltfError::Material {
            material,
            reason: said,
            ..
        } => {
            assert_eq!(material, "\"surface\" (#0)");
            assert!(said.contains(reason), "{said}");
        }
        other => panic!("{file}: expected GltfError::Material, got {other:?}"),
    }
}

/// Loads `file` next to the preview plane and renders; returns the load's warnings.
fn gltf_renders(file: &str) -> Vec<String> {
    let mut app = material_app(|_| ParallaxOcclusionMaterial::default());
    let scene = load_gltf(&mut app, corpus(file)).unwrap();
    assert!(!scene.entities.is_empty());
    renders_cleanly(&mut app);
    scene.warnings
}

fn only_mesh(app: &App) -> pom::Mesh {
    let meshes = app.resources.get::<Assets<pom::Mesh>>().unwrap();
    let mut handles = app.world.query::<&pom::Handle<pom::Mesh>>();
    let handles: Vec<_> = handles.iter().cloned().collect();
    // The preview plane is the first mesh; the file's is the last.
    meshes.get(handles.last().unwrap().id()).unwrap().clone()
}

#[test]
fn gltf_missing_buffer_file() {
    match gltf_error("gltf/missing_buffer.gltf") {
        GltfError::Buffer {
            index: 0, reason, ..
        } => {
            assert!(reason.contains("absent.bin"), "{reason}")
        }
        other => panic!("expected GltfError::Buffer, got {other:?}"),
    }
}

#[test]
fn gltf_buffer_shorter_than_declared() {
    match gltf_error("gltf/short_buffer.gltf") {
        GltfError::Buffer {
            index: 0, reason, ..
        } => {
            assert!(reason.contains("bytes but declares"), "{reason}")
        }
        other => panic!("expected GltfError::Buffer, got {other:?}"),
    }
}

#[test]
fn gltf_index_out_of_range() {
    assert_mesh_error(
        "gltf/index_out_of_range.gltf",
        "index 40 at position 5 is out of range for 4 vertices",
    );
}

#[test]
fn gltf_accessor_past_its_buffer() {
    assert_open_error(
        "gltf/accessor_past_buffer.gltf",
        "accessor 0: 400 elements run past the 48 bytes of its buffer view",
    );
}

#[test]
fn gltf_nan_positions() {
    assert_mesh_error("gltf/nan_positions.gltf", "position 1 is not finite");
}

#[test]
fn gltf_infinite_positions() {
    assert_mesh_error("gltf/infinite_positions.gltf", "position 1 is not finite");
}

#[test]
fn gltf_without_positions() {
    assert_open_error(
        "gltf/no_positions.gltf",
        "attributes[\"POSITION\"]: Missing data",
    );
}

#[test]
fn gltf_without_normals_gets_flat_normals() {
    assert!(gltf_renders("gltf/no_normals.gltf").is_empty());
    let mut app = pom_app(8, TargetFormat::Float32).unwrap();
    load_gltf(&mut app, corpus("gltf/no_normals.gltf")).unwrap();
    let mesh = only_mesh(&app);
    assert!(
        mesh.normals.iter().all(|n| n[1] > 0.999),
        "{:?}",
        mesh.normals
    );
}

#[test]
fn gltf_without_uvs_gets_zero_uvs() {
    assert!(gltf_renders("gltf/no_uvs.gltf").is_empty());
    let mut app = pom_app(8, TargetFormat::Float32).unwrap();
    load_gltf(&mut app, corpus("gltf/no_uvs.gltf")).unwrap();
    assert!(only_mesh(&app).uvs.iter().all(|uv| *uv == [0.0, 0.0]));
}

#[test]
fn gltf_without_tangents_gets_generated_ones() {
    assert!(gltf_renders("gltf/no_tangents.gltf").is_empty());
    let mut app = pom_app(8, TargetFormat::Float32).unwrap();
    load_gltf(&mut app, corpus("gltf/no_tangents.gltf")).unwrap();
    let mesh = only_mesh(&app);
    assert_eq!(mesh.tangents.len(), mesh.positions.len());
    assert!(mesh.tangents.iter().flatten().all(|c| c.is_finite()));
}

#[test]
fn gltf_degenerate_triangles() {
    assert!(gltf_renders("gltf/degenerate_triangles.gltf").is_empty());
}

#[test]
fn gltf_all_vertices_at_one_point() {
    assert!(gltf_renders("gltf/all_vertices_at_one_point.gltf").is_empty());
    let mut app = pom_app(8, TargetFormat::Float32).unwrap();
    load_gltf(&mut app, corpus("gltf/all_vertices_at_one_point.gltf")).unwrap();
    let mesh = only_mesh(&app);
    assert!(mesh.normals.iter().flatten().all(|c| c.is_finite()));
    assert!(mesh.tangents.iter().flatten().all(|c| c.is_finite()));
}

#[test]
fn gltf_points_mode_is_skipped_with_a_warning() {
    let warnings = gltf_renders("gltf/points_mode.gltf");
    assert_eq!(
        warnings,
        ["mesh \"quad\" (#0), primitive 0: mode Points is not supported; skipped"]
    );
}

#[test]
fn gltf_lines_mode_is_skipped_with_a_warning() {
    let warnings = gltf_renders("gltf/lines_mode.gltf");
    assert_eq!(
        warnings,
        ["mesh \"quad\" (#0), primitive 0: mode Lines is not supported; skipped"]
    );
}

#[test]
fn gltf_invalid_primitive_mode() {
    assert_open_error(
        "gltf/invalid_mode.gltf",
        "meshes[0].primitives[0].mode: Invalid value",
    );
}

#[test]
fn gltf_extras_unknown_key() {
    assert_material_error(
        "gltf/extras_unknown_key.gltf",
        "extras.pom: unknown field `hieght_scale`",
    );
}

#[test]
fn gltf_extras_wrong_type() {
    assert_material_error(
        "gltf/extras_wrong_type.gltf",
        "extras.pom: invalid type: string \"many\", expected u32",
    );
}

#[test]
fn gltf_extras_unknown_method() {
    assert_material_error(
        "gltf/extras_unknown_method.gltf",
        "extras.pom.method is \"magic\"; expected one of",
    );
}

#[test]
fn gltf_extras_height_texture_out_of_range() {
    assert_material_error(
        "gltf/extras_missing_texture.gltf",
        "extras.pom.height_texture is 7 but the file has 0 textures",
    );
}

#[test]
fn gltf_extras_without_a_height() {
    assert_material_error(
        "gltf/extras_no_height.gltf",
        "extras.pom needs height_texture (or height_in_normal_alpha: true)",
    );
}

#[test]
fn gltf_extras_negative_height_scale() {
    assert_material_error("gltf/extras_negative_height.gltf", "height_scale");
}

#[test]
fn gltf_extras_min_samples_over_max() {
    assert_material_error(
        "gltf/extras_min_over_max.gltf",
        "min_samples (9) is greater than max_samples (3)",
    );
}

#[test]
fn gltf_missing_image_file() {
    match gltf_error("gltf/missing_image.gltf") {
        GltfError::Image { image, reason, .. } => {
            assert_eq!(image, "#0");
            assert!(reason.contains("No such file"), "{reason}");
        }
        other => panic!("expected GltfError::Image, got {other:?}"),
    }
}

#[test]
fn gltf_without_a_scene() {
    let error = gltf_error("gltf/no_scene.gltf");
    assert!(matches!(error, GltfError::NoScene { .. }), "{error:?}");
}

#[test]
fn gltf_default_scene_out_of_range() {
    assert_open_error("gltf/scene_out_of_range.gltf", "scene");
}

#[test]
fn gltf_node_that_is_its_own_child() {
    assert_open_error(
        "gltf/node_is_its_own_child.gltf",
        "node \"quad\" (#0) is reached twice",
    );
}

#[test]
fn gltf_zero_byte_file() {
    assert_open_error("gltf/empty.gltf", "EOF while parsing");
}

#[test]
fn gltf_broken_json() {
    assert_open_error("gltf/not_json.gltf", "EOF while parsing");
}

#[test]
fn gltf_truncated_glb() {
    let error = gltf_error("gltf/truncated.glb");
    assert!(matches!(error, GltfError::Open { .. }), "{error:?}");
}

#[test]
fn gltf_missing_file() {
    assert_open_error("gltf/no_such_scene.gltf", "No such file");
}

// ---------------------------------------------------------------- presets

fn preset_error(file: &str) -> PresetError {
    let error = PomPreset::load(corpus(file)).unwrap_err();
    let name = Path::new(file).file_name().unwrap().to_str().unwrap();
    assert!(error.to_string().contains(name), "{error}");
    error
}

fn assert_preset_syntax(file: &str, at_line: usize, reason: &str) {
    match preset_error(file) {
        PresetError::Syntax {
            line, reason: said, ..
        } => {
            assert_eq!(line, at_line, "{said}");
            assert!(said.contains(reason), "{said}");
        }
        other => panic!("{file}: expected PresetError::Syntax, got {other:?}"),
    }
}

#[test]
fn preset_syntax_error() {
    assert_preset_syntax("presets/syntax_error.ron", 4, "Unexpected end of RON");
}

#[test]
fn preset_wrong_type() {
    assert_preset_syntax("presets/wrong_type.ron", 4, "Expected integer");
}

#[test]
fn preset_unknown_field() {
    assert_preset_syntax("presets/unknown_field.ron", 4, "hieght_scale");
}

#[test]
fn preset_unknown_variant() {
    assert_preset_syntax("presets/unknown_variant.ron", 3, "Fuzzy");
}

#[test]
fn preset_negative_samples() {
    assert_preset_syntax(
        "presets/negative_samples.ron",
        3,
        "Integer is out of bounds",
    );
}

#[test]
fn preset_zero_byte_file() {
    let error = preset_error("presets/empty.ron");
    assert!(
        matches!(error, PresetError::Syntax { line: 1, .. }),
        "{error:?}"
    );
}

#[test]
fn preset_min_samples_over_max() {
    match preset_error("presets/min_over_max.ron") {
        PresetError::Invalid { source, .. } => assert_eq!(
            source,
            PomMaterialError::SamplesInverted { min: 60, max: 4 }
        ),
        other => panic!("expected PresetError::Invalid, got {other:?}"),
    }
}

#[test]
fn preset_nan_height() {
    match preset_error("presets/nan_height.ron") {
        PresetError::Invalid {
            source: PomMaterialError::NotFinite { field, value },
            ..
        } => {
            assert_eq!(field, "height_scale");
            assert!(value.is_nan());
        }
        other => panic!("expected PresetError::Invalid(NotFinite), got {other:?}"),
    }
}

#[test]
fn preset_missing_file() {
    let error = preset_error("presets/no_such_preset.ron");
    assert!(matches!(error, PresetError::Io { .. }), "{error:?}");
}

// ---------------------------------------------------------------- scene scripts

fn script_error(file: &str) -> ScriptError {
    let error = run_script_with(corpus(file), &RunOptions::default()).unwrap_err();
    let name = Path::new(file).file_name().unwrap().to_str().unwrap();
    assert!(error.to_string().contains(name), "{error}");
    error
}

fn assert_script_parse(file: &str, at_line: usize, reason: &str) {
    match script_error(file) {
        ScriptError::Parse {
            line, reason: said, ..
        } => {
            assert_eq!(line, at_line, "{said}");
            assert!(said.contains(reason), "{said}");
        }
        other => panic!("{file}: expected ScriptError::Parse, got {other:?}"),
    }
}

fn assert_script_reference(file: &str, at_line: usize, reason: &str) {
    match script_error(file) {
        ScriptError::Reference {
            line, reason: said, ..
        } => {
            assert_eq!(line, at_line, "{said}");
            assert!(said.contains(reason), "{said}");
        }
        other => panic!("{file}: expected ScriptError::Reference, got {other:?}"),
    }
}

#[test]
fn script_syntax_error() {
    assert_script_parse("scripts/syntax_error.ron", 5, "Expected comma");
}

#[test]
fn script_wrong_type() {
    assert_script_parse("scripts/wrong_type.ron", 3, "Expected opening `(`");
}

#[test]
fn script_unknown_field() {
    assert_script_parse("scripts/unknown_field.ron", 4, "stepz");
}

#[test]
fn script_missing_steps() {
    match script_error("scripts/missing_steps.ron") {
        ScriptError::Parse { reason, .. } => assert!(reason.contains("steps"), "{reason}"),
        other => panic!("expected ScriptError::Parse, got {other:?}"),
    }
}

#[test]
fn script_missing_map_folder() {
    assert_script_reference(
        "scripts/missing_maps.ron",
        5,
        "no_such_folder/albedo.png does not exist",
    );
}

#[test]
fn script_missing_preset_file() {
    assert_script_reference(
        "scripts/missing_preset.ron",
        5,
        "preset file \"no_such_preset.ron\" does not exist",
    );
}

#[test]
fn script_missing_gltf_file() {
    assert_script_reference("scripts/missing_gltf.ron", 5, "nowhere.glb");
}

#[test]
fn script_with_an_invalid_preset() {
    match script_error("scripts/bad_preset_inside.ron") {
        ScriptError::Setup { reason, .. } => assert!(
            reason.contains("min_over_max.ron")
                && reason.contains("min_samples (60) is greater than max_samples (4)"),
            "{reason}"
        ),
        other => panic!("expected ScriptError::Setup, got {other:?}"),
    }
}

#[test]
fn script_with_a_broken_map_file() {
    match script_error("scripts/broken_map_file.ron") {
        ScriptError::Setup { reason, .. } => assert!(
            reason.contains("broken_maps/height.png") && reason.contains("unexpected end of file"),
            "{reason}"
        ),
        other => panic!("expected ScriptError::Setup, got {other:?}"),
    }
}

#[test]
fn script_that_fails_midway_still_reports_the_steps_it_ran() {
    match script_error("scripts/fails_midway.ron") {
        ScriptError::Step {
            step,
            reason,
            report,
            ..
        } => {
            assert_eq!(step, 4);
            assert!(reason.contains("has no parallax material"), "{reason}");
            let numbers: Vec<usize> = report.steps.iter().map(|s| s.number).collect();
            assert_eq!(numbers, [1, 2, 3], "{report}");
            assert!(report.passed(), "{report}");
            let text = report.to_string();
            assert!(
                text.contains("fails_midway.ron step 3 ExpectStat"),
                "{text}"
            );
        }
        other => panic!("expected ScriptError::Step, got {other:?}"),
    }
}

#[test]
fn script_missing_file() {
    let error = script_error("scripts/no_such_script.ron");
    assert!(matches!(error, ScriptError::Io { .. }), "{error:?}");
}

// ---------------------------------------------------------------- material parameters

/// Renders the bad material (its `validate` names `field`), checks the frame is clean and that
/// the clamp was recorded for a warning (logged once per change).
fn clamped_with_a_warning(field: &str, spoil: impl FnOnce(&mut ParallaxOcclusionMaterial)) {
    let mut app = material_app(|images| {
        let height = images.add(pom::patterns::bricks(32, 2.0, 4.0).to_image());
        let mut material = ParallaxOcclusionMaterial {
            height_map: Some(HeightSource::Texture(height)),
            ..ParallaxOcclusionMaterial::default()
        };
        spoil(&mut material);
        let error = material.validate().unwrap_err();
        assert!(error.to_string().contains(field), "{error}");
        assert!(material.sanitized().validate().is_ok());
        material
    });
    renders_cleanly(&mut app);
    renders_cleanly(&mut app);
    let warned = app.resources.get::<MaterialWarnings>().unwrap();
    assert_eq!(warned.len(), 1, "the clamp was not recorded for a warning");
}

#[test]
fn material_nan_height_scale() {
    clamped_with_a_warning("height_scale is NaN", |m| m.height_scale = f32::NAN);
}

#[test]
fn material_infinite_height_scale() {
    clamped_with_a_warning("height_scale is inf", |m| m.height_scale = f32::INFINITY);
}

#[test]
fn material_negative_infinite_height_scale() {
    clamped_with_a_warning("height_scale is -inf", |m| {
        m.height_scale = f32::NEG_INFINITY
    });
}

#[test]
fn material_negative_height_scale() {
    clamped_with_a_warning("height_scale is -0.3", |m| m.height_scale = -0.3);
}

#[test]
fn material_zero_samples() {
    clamped_with_a_warning("min_samples is 0", |m| {
        m.min_samples = 0;
        m.max_samples = 0;
    });
}

#[test]
fn material_min_samples_over_max() {
    clamped_with_a_warning("min_samples (60) is greater than max_samples (4)", |m| {
        m.min_samples = 60;
        m.max_samples = 4;
    });
}

#[test]
fn material_absurd_sample_count() {
    clamped_with_a_warning("max_samples is 4294967300 but must be at most 256", |m| {
        m.max_samples = u32::MAX
    });
    let clamped = ParallaxOcclusionMaterial {
        max_samples: u32::MAX,
        ..ParallaxOcclusionMaterial::default()
    }
    .sanitized();
    assert_eq!(clamped.max_samples, pom::parallax::MAX_SAMPLES_LIMIT);
}

#[test]
fn material_nan_shadow_softening() {
    clamped_with_a_warning("shadow_softening is NaN", |m| m.shadow_softening = f32::NAN);
}

#[test]
fn material_negative_lod_threshold() {
    clamped_with_a_warning("lod_threshold is -2", |m| m.lod_threshold = -2.0);
}

#[test]
fn material_relief_with_zero_binary_steps() {
    clamped_with_a_warning("method.binary_steps is 0", |m| {
        m.method = ParallaxMethod::Relief { binary_steps: 0 }
    });
}

#[test]
fn material_nan_base_colour() {
    clamped_with_a_warning("base_color is NaN", |m| m.base_color.g = f32::NAN);
}
