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
use pom_tests::render_and_capture_finite;

mod environment;
mod files;
mod gltf;
mod images;
mod lights;
mod parameters;
mod presets;
mod scripts;

fn corpus(file: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("bad_inputs")
        .join(file)
}

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

/// Renders one frame inside error scopes and checks it is finite (the HDR scene before
/// tonemapping too) and not all black.
fn renders_cleanly(app: &mut App) -> Rgba32FImage {
    let image = render_and_capture_finite(app).unwrap_or_else(|error| panic!("{error}"));
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
