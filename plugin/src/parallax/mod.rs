//! The parallax occlusion mapping material: component, plugin, render systems.

mod extract;
mod gpu;
mod lod_switch;
mod material;
mod pass;
mod pipelines;
mod preset;

pub use extract::{ExtractedPom, MaterialWarnings, PomDraw, extract_pom};
pub use gpu::PomObject;
pub use lod_switch::{MeshLodBounds, MeshLodCache, PixelFootprint, lowest_mip};
pub use material::{
    DebugView, HeightConvention, HeightSource, HeightUnits, LightingModel, MAX_SAMPLES_LIMIT,
    ParallaxMethod, ParallaxOcclusionMaterial, PomMaterialError, ShadowMode,
};
pub use pass::PomPass;
pub use pipelines::{PomPipelineKey, PomPipelines};
pub use preset::{PomPreset, PresetError, write_atomically};

use crate::render::{MainPassDraws, RenderTarget, Renderer};
use crate::{App, AppError, Assets, BoxedError, GpuContext, Image, Mesh, Plugin, Resources, Stage};

/// Draws every entity that has a [`ParallaxOcclusionMaterial`], a `Handle<Mesh>` and a
/// transform. Add it after [`crate::RenderPlugin`].
#[derive(Clone, Copy, Debug, Default)]
pub struct PomPlugin;

/// The parallax pass's GPU state. A resource.
#[derive(Debug)]
pub struct PomRenderer {
    /// Pipelines, buffers and bind groups.
    pub pass: PomPass,
    /// Bytes of per-draw data the last Prepare stage wrote.
    pub last_upload_bytes: u64,
}

/// Why the plugin could not start.
#[derive(Debug, thiserror::Error)]
#[error("PomPlugin needs RenderPlugin: add RenderPlugin before PomPlugin")]
pub struct MissingRenderPlugin;

impl Plugin for PomPlugin {
    fn build(&self, app: &mut App) {
        app.add_system(Stage::Extract, extract_pom)
            .add_system(Stage::Prepare, prepare_pom)
            .add_system(Stage::Prepare, crate::derive_dynamic_normals);
        app.resources
            .get_or_default::<MainPassDraws>()
            .0
            .push(draw_pom);
    }

    fn finish(&self, app: &mut App) -> Result<(), BoxedError> {
        let (Some(gpu), Some(target), Some(renderer)) = (
            app.resources.get::<GpuContext>(),
            app.resources.get::<RenderTarget>(),
            app.resources.get::<Renderer>(),
        ) else {
            return Err(MissingRenderPlugin.into());
        };
        let pass = PomPass::new(gpu, &renderer.frame, target.format());
        let sobel = crate::SobelPass::new(gpu);
        app.insert_resource(sobel);
        app.insert_resource(PomRenderer {
            pass,
            last_upload_bytes: 0,
        });
        Ok(())
    }
}

/// The Prepare stage's system: uploads the material textures, meshes and per-draw data.
pub fn prepare_pom(_: &mut hecs::World, resources: &mut Resources) -> Result<(), AppError> {
    let mut renderer = resources
        .remove::<Renderer>()
        .ok_or_else(AppError::missing::<Renderer>)?;
    let result = prepare_with(&mut renderer, resources);
    resources.insert(renderer);
    result
}

fn prepare_with(renderer: &mut Renderer, resources: &mut Resources) -> Result<(), AppError> {
    let mut pom = resources
        .remove::<PomRenderer>()
        .ok_or_else(AppError::missing::<PomRenderer>)?;
    let result = (|| {
        let gpu = resources.require::<GpuContext>()?;
        let extracted = resources.require::<ExtractedPom>()?;
        let meshes = resources.require::<Assets<Mesh>>()?;
        let images = resources.require::<Assets<Image>>()?;
        for draw in &extracted.draws {
            if renderer.assets.prepare_mesh(gpu, meshes, draw.mesh) {
                renderer.last_upload.meshes += 1;
            }
            for image in draw.textures.into_iter().flatten() {
                if renderer.assets.prepare_image(gpu, images, image) {
                    renderer.last_upload.images += 1;
                }
            }
        }
        pom.last_upload_bytes = pom
            .pass
            .prepare(gpu, &renderer.frame, extracted, &renderer.assets);
        renderer.last_upload.uniform_bytes += pom.last_upload_bytes;
        Ok(())
    })();
    resources.insert(pom);
    result
}

/// The parallax draws of the main pass (registered in [`MainPassDraws`]).
pub fn draw_pom(resources: &Resources, pass: &mut wgpu::RenderPass<'_>) {
    let (Some(pom), Some(extracted), Some(renderer)) = (
        resources.get::<PomRenderer>(),
        resources.get::<ExtractedPom>(),
        resources.get::<Renderer>(),
    ) else {
        return;
    };
    pom.pass.draw(pass, extracted, &renderer.assets);
}
