//! An app's last frame read back from the GPU: the displayed image and the HDR scene.

use image::{Rgba32FImage, RgbaImage};

use crate::App;
use crate::gpu::{GpuContext, read_rgba8, read_rgba32f};
use crate::render::{RenderError, RenderTarget};

/// Reads the last rendered frame back as sRGB-encoded RGBA8 pixels.
///
/// # Example
/// ```no_run
/// # fn main() -> Result<(), Box<dyn std::error::Error>> {
/// let mut app = pom::App::new();
/// app.add_plugin(pom::RenderPlugin::new(64, 64));
/// app.update()?;
/// let image = pom::capture(&app)?;
/// assert_eq!(image.dimensions(), (64, 64));
/// # Ok(()) }
/// ```
pub fn capture(app: &App) -> Result<RgbaImage, RenderError> {
    let (gpu, target) = rendered(app)?;
    Ok(read_rgba8(gpu, &target.color)?)
}

/// Reads the last rendered frame of a [`crate::TargetFormat::Float32`] target back as floats: linear
/// display values after exposure and tonemapping (debug views' data as the shader wrote it).
pub fn capture_f32(app: &App) -> Result<Rgba32FImage, RenderError> {
    let (gpu, target) = rendered(app)?;
    Ok(read_rgba32f(gpu, &target.color)?)
}

/// Reads the HDR scene of the last frame of a [`crate::TargetFormat::Float32`] target back: the light
/// the materials computed, already exposed (the lights carry the camera's exposure), before
/// tonemapping.
pub fn capture_scene(app: &App) -> Result<Rgba32FImage, RenderError> {
    let (gpu, target) = rendered(app)?;
    Ok(read_rgba32f(gpu, &target.scene)?)
}

/// The GPU and the target an app renders into, or [`RenderError::NotRendered`] without them.
fn rendered(app: &App) -> Result<(&GpuContext, &RenderTarget), RenderError> {
    match (
        app.resources.get::<GpuContext>(),
        app.resources.get::<RenderTarget>(),
    ) {
        (Some(gpu), Some(target)) => Ok((gpu, target)),
        _ => Err(RenderError::NotRendered),
    }
}
