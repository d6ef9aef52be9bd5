//! Tonemapping: the post chain's display conversion, from the pre-exposed HDR scene (the lights
//! carry the camera's [`crate::Exposure`]) to the display image with the camera's
//! [`crate::Tonemapping`] operator, sRGB-encoded for 8-bit targets. It sits between the HDR
//! effects (TAA) and the display effects (FXAA) of the post phase, and is timed as "post".
//! Pixels whose alpha marks them display-referred (the clear colour, debug views) pass
//! through unchanged (post_process.wgsl).

mod operators;
mod post_process;

pub use operators::{Tonemapping, set_camera_display_mapping};
pub(crate) use post_process::POST_SHADERS;
pub use post_process::{
    POST_COMPUTE_ENTRY, POST_COMPUTE_RGBA8, POST_COMPUTE_RGBA32F, POST_FRAGMENT,
    POST_FRAGMENT_ENTRY, POST_PROCESS, PostSettings, TONEMAPPING,
};
pub(crate) use post_process::{rgba8_output, rgba32f_output};

use post_process::PostProcess;

use crate::gpu::GpuContext;
use crate::gpu::PassTimestamps;
use crate::render::{
    FrameNodes, FrameView, HdrInput, PostEffect, PostImage, PostIo, PostStage, RenderError,
    RenderPhase, RenderTarget, Renderer,
};
use crate::{App, Plugin, Resources, Stage};

/// The node name tonemapping is timed under.
pub const TONEMAPPING_NODE: &str = RenderPhase::PostProcess.name();

/// Adds tonemapping to the post chain (the render plugin adds it with its standard features).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct TonemappingPlugin;

impl Plugin for TonemappingPlugin {
    fn build(&self, app: &mut App) {
        app.resources
            .get_or_default::<FrameNodes>()
            .add_post_effect(TONEMAPPING_NODE, Tonemap::default);
        app.add_system(Stage::Extract, extract_tonemapping);
    }
}

/// The active camera's operator this frame (its component, else the default). A resource of
/// the tonemapping plugin; TAA tonemaps its history with it too.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct CameraTonemapping(pub Tonemapping);

/// The Extract stage's system: the active camera's operator.
fn extract_tonemapping(world: &mut hecs::World, resources: &mut Resources) {
    let operator = world
        .query::<(&crate::Camera, Option<&Tonemapping>)>()
        .iter()
        .find(|(camera, _)| camera.active)
        .and_then(|(_, operator)| operator.copied())
        .unwrap_or_default();
    resources.insert(CameraTonemapping(operator));
}

/// The display conversion of the post chain; its pass is made on the first frame.
#[derive(Debug, Default)]
struct Tonemap {
    pass: Option<PostProcess>,
}

impl PostEffect for Tonemap {
    fn stage(&self) -> PostStage {
        PostStage::ToDisplay
    }

    fn runs(&self, _: FrameView<'_>) -> bool {
        true
    }

    fn prepare(&mut self, resources: &mut Resources, input: HdrInput) -> Result<u64, RenderError> {
        let gpu = resources.require::<GpuContext>()?;
        let format = resources.require::<RenderTarget>()?.target_format();
        let stage = resources.require::<Renderer>()?.full_screen_stage();
        let operator = match input {
            HdrInput::Tonemapped => Tonemapping::None,
            HdrInput::SceneColour => resources.require::<CameraTonemapping>()?.0,
        };
        if !self.pass.as_ref().is_some_and(|pass| pass.is_for(format)) {
            self.pass = Some(PostProcess::new(gpu, format, stage));
        }
        Ok(self.pass.as_mut().map_or(0, |pass| {
            pass.upload(gpu, PostSettings::new(operator, format))
        }))
    }

    fn record(
        &mut self,
        frame: FrameView<'_>,
        io: PostIo<'_>,
        encoder: &mut wgpu::CommandEncoder,
        time: Option<&PassTimestamps>,
    ) -> Result<Option<PostImage>, RenderError> {
        if let (Some(pass), Some(output)) = (&mut self.pass, io.output) {
            pass.record(frame.gpu, frame.target, (io.input, output), encoder, time);
        }
        Ok(None)
    }
}
