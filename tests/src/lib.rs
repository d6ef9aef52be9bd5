//! Helpers for the integration tests: a headless app whose GPU work runs inside validation
//! error scopes, reference-image comparison with NVIDIA FLIP, and procedural test textures.

pub mod anti_aliasing;
pub mod edge_error;
mod finite;
pub mod fixtures;
pub mod fuzz_entry;
pub mod gltf_fixture;
mod golden;
pub mod memory;
pub mod nan_injection;
pub mod parameters;
pub mod pom_scene;
pub mod scratch_crate;
pub mod script_edits;
pub mod sources;
pub mod xvfb;

pub use finite::{NonFinitePixels, non_finite_pixels, render_and_capture_finite};
pub use golden::{
    FlipTolerance, GoldenError, ImagesDiffer, check_golden, compare_images, differing_pixels,
    golden_dir,
};

use pom::render::Renderer;
use pom::{App, AppError, GpuContext, RenderPath, RenderPlugin};

/// What can fail while driving a test app.
#[derive(Debug, thiserror::Error)]
pub enum HarnessError {
    /// An update returned an error.
    #[error(transparent)]
    App(#[from] AppError),
    /// wgpu reported a validation or out-of-memory error inside the scope.
    #[error("wgpu error during {during}: {error}")]
    Gpu {
        /// What was running.
        during: &'static str,
        /// The error.
        error: String,
    },
    /// Capture failed.
    #[error(transparent)]
    Render(#[from] pom::RenderError),
    /// A frame held NaN or ±∞ ([`render_and_capture_finite`]).
    #[error("{0}")]
    NonFinite(NonFinitePixels),
}

/// An app with the render plugin at `width`×`height`, finished (GPU created), with any setup
/// validation error turned into a failure.
pub fn headless_app(width: u32, height: u32) -> Result<App, HarnessError> {
    let mut app = App::new();
    app.add_plugin(RenderPlugin::new(width, height))
        .add_plugin(pom::LitPlugin);
    app.finish()?;
    let gpu = app
        .resources
        .get::<GpuContext>()
        .expect("render plugin inserts the GPU context");
    let info = gpu.adapter_info();
    if info.device_type != pom::wgpu::DeviceType::Cpu {
        eprintln!(
            "note: reference images were made on lavapipe; this run uses {} ({:?}). \
             Run tests/run to pin the software driver.",
            info.name, info.device_type
        );
    }
    check_uncaptured(&app, "setup")?;
    Ok(app)
}

fn gpu(app: &App) -> &GpuContext {
    app.resources
        .get::<GpuContext>()
        .expect("render plugin inserts the GPU context")
}

fn check_uncaptured(app: &App, during: &'static str) -> Result<(), HarnessError> {
    let errors = gpu(app).take_uncaptured_errors();
    match errors.first() {
        Some(error) => Err(HarnessError::Gpu {
            during,
            error: error.clone(),
        }),
        None => Ok(()),
    }
}

/// Runs `f` with validation and out-of-memory error scopes pushed on the app's device, and fails
/// if either caught an error.
pub fn in_error_scopes<T>(
    app: &mut App,
    during: &'static str,
    f: impl FnOnce(&mut App) -> Result<T, HarnessError>,
) -> Result<T, HarnessError> {
    // The device exists once the plugins have finished.
    app.finish()?;
    let device = gpu(app).device.clone();
    let out_of_memory = device.push_error_scope(pom::wgpu::ErrorFilter::OutOfMemory);
    let validation = device.push_error_scope(pom::wgpu::ErrorFilter::Validation);
    let result = f(app);
    let validation_error = pollster::block_on(validation.pop());
    let memory_error = pollster::block_on(out_of_memory.pop());
    if let Some(error) = validation_error.or(memory_error) {
        return Err(HarnessError::Gpu {
            during,
            error: error.to_string(),
        });
    }
    check_uncaptured(app, during)?;
    result
}

/// Runs `frames` updates inside error scopes.
pub fn run_frames(app: &mut App, frames: usize) -> Result<(), HarnessError> {
    in_error_scopes(app, "update", |app| {
        for _ in 0..frames {
            app.update()?;
        }
        Ok(())
    })
}

/// Runs one update and captures the result, all inside error scopes.
pub fn render_and_capture(app: &mut App) -> Result<image::RgbaImage, HarnessError> {
    in_error_scopes(app, "render and capture", |app| {
        app.update()?;
        Ok(pom::capture(app)?)
    })
}

/// Runs one update and reads a float target back, all inside error scopes.
pub fn render_and_capture_f32(app: &mut App) -> Result<image::Rgba32FImage, HarnessError> {
    in_error_scopes(app, "render and capture", |app| {
        app.update()?;
        Ok(pom::capture_f32(app)?)
    })
}

/// Most a deferred frame may differ from the forward one (mean FLIP): the deferred path's
/// acceptance target.
pub const PATHS_AGREE_MEAN: f32 = 0.005;

/// Most the 99th percentile of the FLIP error may reach between the two paths: a few pixels
/// differ where a march takes one step more or less (0.16 at worst in the references), a
/// wrongly resolved triangle much more.
pub const PATHS_AGREE_P99: f32 = 0.25;

/// Renders the app's next frame on the forward path and the one after on the deferred path
/// (inside error scopes), checks that the two agree (mean FLIP ≤ [`PATHS_AGREE_MEAN`]; on a
/// failure both images and the FLIP error map are written under `target/deferred-path/NAME-*`),
/// and returns the forward image. The app keeps the forward path afterwards. Scenes must be
/// still from one frame to the next.
pub fn render_both_paths(app: &mut App, name: &str) -> Result<image::RgbaImage, PathsDiffer> {
    let forward = render_on_path(app, RenderPath::Forward)?;
    let deferred = render_on_path(app, RenderPath::Deferred)?;
    set_path(app, RenderPath::Forward);
    let ran_deferred = app
        .resources
        .get::<Renderer>()
        .is_some_and(Renderer::runs_deferred);
    if !ran_deferred {
        return Err(PathsDiffer::NotDeferred(name.to_owned()));
    }
    let comparison = pom::flip_compare(&forward, &deferred, 0.99)
        .ok_or_else(|| PathsDiffer::SizesDiffer(name.to_owned()))?;
    eprintln!(
        "{name}: forward vs deferred FLIP mean {:.5}, p99 {:.4}",
        comparison.mean, comparison.at_percentile
    );
    if comparison.mean > PATHS_AGREE_MEAN || comparison.at_percentile > PATHS_AGREE_P99 {
        let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../target/deferred-path");
        let _ = std::fs::create_dir_all(&dir);
        let _ = forward.save(dir.join(format!("{name}-forward.png")));
        let _ = deferred.save(dir.join(format!("{name}-deferred.png")));
        let _ = comparison
            .error_map
            .save(dir.join(format!("{name}-difference.png")));
        return Err(PathsDiffer::Images {
            name: name.to_owned(),
            mean: comparison.mean,
            p99: comparison.at_percentile,
        });
    }
    Ok(forward)
}

/// Why [`render_both_paths`] failed.
#[derive(Debug, thiserror::Error)]
pub enum PathsDiffer {
    /// Rendering failed.
    #[error(transparent)]
    Harness(#[from] HarnessError),
    /// The deferred frame ran forward (the adapter or a material cannot run it).
    #[error("{0}: the deferred frame ran forward")]
    NotDeferred(String),
    /// The two frames have different sizes.
    #[error("{0}: the forward and deferred frames differ in size")]
    SizesDiffer(String),
    /// The two frames differ.
    #[error(
        "{name}: forward and deferred differ, FLIP mean {mean:.5} (max {PATHS_AGREE_MEAN}), p99 {p99:.4} (max {PATHS_AGREE_P99})"
    )]
    Images {
        /// The scene.
        name: String,
        /// Their mean FLIP error.
        mean: f32,
        /// Their FLIP error at the 99th percentile.
        p99: f32,
    },
}

/// Asks `app`'s renderer for `path` from the next frame on.
pub fn set_path(app: &mut App, path: RenderPath) {
    if let Some(renderer) = app.resources.get_mut::<Renderer>() {
        renderer.set_path(path);
    }
}

/// Renders one frame on `path` and captures it.
pub fn render_on_path(app: &mut App, path: RenderPath) -> Result<image::RgbaImage, HarnessError> {
    app.finish()?;
    set_path(app, path);
    render_and_capture(app)
}

/// Renders one frame on `path` and reads the float target back.
pub fn render_on_path_f32(
    app: &mut App,
    path: RenderPath,
) -> Result<image::Rgba32FImage, HarnessError> {
    app.finish()?;
    set_path(app, path);
    render_and_capture_f32(app)
}
