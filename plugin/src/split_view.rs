//! Split view: the same world rendered a second time into its own target, with some entities'
//! parallax materials replaced, so two methods or two parameter sets can be compared side by
//! side (a UI shows the two images with a wipe between them).

use std::collections::HashMap;

use hecs::Entity;

use crate::gpu::GpuTimer;
use crate::render::{RenderTarget, TargetFormat};
use crate::{App, AppError, GpuContext, ParallaxOcclusionMaterial, Stage};

/// The second image of a split view and what differs in it. A resource: insert it to turn the
/// split view on, then call [`render_split_view`] after each [`App::update`].
#[derive(Debug, Default)]
pub struct SplitView {
    /// Per entity, the material it has in the second image (entities not listed, or without a
    /// parallax material, look the same in both).
    pub overrides: HashMap<Entity, ParallaxOcclusionMaterial>,
    /// The second image; made (or remade) at the main target's size by [`render_split_view`].
    pub target: Option<RenderTarget>,
}

/// Why the second image could not be rendered.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum SplitViewError {
    /// The app has no render target or GPU context (RenderPlugin missing or not finished).
    #[error("split view needs RenderPlugin's target and GPU context: add RenderPlugin first")]
    NotRendering,
    /// A system of the second render failed.
    #[error("rendering the split view's second image: {0}")]
    Render(#[from] AppError),
}

/// Renders the world again into the [`SplitView`]'s target with its material overrides (runs
/// the Extract, Prepare and Render stages a second time). Without a `SplitView` resource it
/// does nothing. The world's materials and the main target are the same afterwards, even when
/// a system fails. The second image is not timed: [`crate::GpuTimings`] stays the main image's.
pub fn render_split_view(app: &mut App) -> Result<(), SplitViewError> {
    app.resource_scope(render_with).unwrap_or(Ok(()))
}

fn render_with(app: &mut App, split: &mut SplitView) -> Result<(), SplitViewError> {
    let (Some(gpu), Some(main)) = (
        app.resources.get::<GpuContext>(),
        app.resources.get::<RenderTarget>(),
    ) else {
        return Err(SplitViewError::NotRendering);
    };
    let format = if main.format() == TargetFormat::Float32.texture_format() {
        TargetFormat::Float32
    } else {
        TargetFormat::Srgb8
    };
    let fits = split.target.as_ref().is_some_and(|target| {
        target.size() == main.size() && target.format() == main.format() && target.made_on(gpu)
    });
    if !fits {
        let (width, height) = main.size();
        split.target = Some(RenderTarget::new(gpu, width, height, format));
    }
    let Some(second) = split.target.take() else {
        return Err(SplitViewError::NotRendering);
    };
    let Some(main) = app.resources.insert(second) else {
        return Err(SplitViewError::NotRendering);
    };
    swap_materials(app, &mut split.overrides);
    // The second image goes untimed, so `GpuTimings` keeps describing the main image.
    let stages = [Stage::Extract, Stage::Prepare, Stage::Render];
    let result = app
        .resource_scope(|app, _: &mut GpuTimer| app.run_stages(&stages))
        .unwrap_or_else(|| app.run_stages(&stages));
    swap_materials(app, &mut split.overrides);
    split.target = app.resources.insert(main);
    Ok(result?)
}

/// Exchanges each overridden entity's material with its override (twice restores both).
fn swap_materials(app: &mut App, overrides: &mut HashMap<Entity, ParallaxOcclusionMaterial>) {
    for (entity, material) in overrides.iter_mut() {
        if let Ok(mut current) = app.world.get::<&mut ParallaxOcclusionMaterial>(*entity) {
            std::mem::swap(&mut *current, material);
        }
    }
}
