//! Anti-aliasing: temporal anti-aliasing (TAA) with its object motion, and FXAA. Which a
//! camera uses, and the parameters of TAA (temporal.rs) and FXAA (fxaa.rs), are camera
//! components; this folder's [`AntiAliasingPlugin`] joins the frame with three nodes:
//!
//! ```text
//! transparent  object_motion  moving draws write their motion's number (frames where one moved)
//! post (HDR)   taa            jittered scene + history → new history (tonemapped colour)
//! post (disp.) post_filter    FXAA on the display image
//! ```
//! Without the plugin a camera's [`AntiAliasing`] has no pass to run: the frame shows the
//! scene as rendered.

mod extract;
mod fxaa;
mod object_motion;
mod taa;
mod temporal;

pub use extract::AntiAliasingFrame;
pub use fxaa::{FXAA_SHADERS, FastApproximateAntiAliasing, set_camera_fxaa};
pub use object_motion::ObjectMotion;
pub(crate) use object_motion::ObjectMotions;
pub use taa::{HISTORY_FORMAT, TAA_SHADER, TaaUniform};
pub use temporal::{
    AntiAliasing, POST_FILTER_MIP_BIAS, TemporalAntiAliasing, TemporalFrame, TemporalHistory,
    TemporalView, jitter_offset, set_camera_anti_aliasing,
};

use fxaa::FxaaPass;
use taa::{TaaInputs, TaaPass};

use crate::gpu::{GpuContext, PassTimestamps, clearing_attachment};
use crate::parameters::ClampWarnings;
use crate::render::tonemapping::CameraTonemapping;
use crate::render::{
    DrawPhase, ExtractedFrame, FrameNode, FrameNodes, FrameView, HdrInput, NodePlace, PostEffect,
    PostImage, PostIo, PostStage, RenderError, RenderPhase, RenderPhases, RenderTarget, Renderer,
};
use crate::{App, AppError, Plugin, Resources, Stage};

/// The name the TAA pass is timed under in [`crate::GpuTimings`] (in the post phase, before
/// tonemapping).
pub const TAA_PASS: &str = "taa";
/// The name TAA's object motion pass is timed under in [`crate::GpuTimings`] (frames in which
/// a draw moved).
pub const OBJECT_MOTION_PASS: &str = "object_motion";
/// The name the post filter (FXAA) is timed under in [`crate::GpuTimings`] (after
/// tonemapping).
pub const POST_FILTER_PASS: &str = "post_filter";

/// Adds TAA, its object motion and FXAA to the frame (the render plugin adds it with its
/// standard features).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct AntiAliasingPlugin;

impl Plugin for AntiAliasingPlugin {
    fn build(&self, app: &mut App) {
        let nodes = app.resources.get_or_default::<FrameNodes>();
        nodes.add(
            NodePlace::new(OBJECT_MOTION_PASS, RenderPhase::Transparent),
            || MotionNode,
        );
        nodes.add_post_effect(TAA_PASS, Taa::default);
        nodes.add_post_effect(POST_FILTER_PASS, Fxaa::default);
        // After the renderer's extraction, before the materials': they read the jitter.
        app.add_system(Stage::Extract, extract::extract_anti_aliasing);
        // Before the materials prepare: they add this frame's moving draws.
        app.add_system(Stage::Prepare, forget_last_motions);
    }
}

/// Empties the list of moving draws before the materials fill it for this frame (making it on
/// the first frame, when every plugin has finished, and again on a new GPU device).
fn forget_last_motions(_: &mut hecs::World, resources: &mut Resources) -> Result<(), AppError> {
    let gpu = resources.require::<GpuContext>()?;
    match resources.get::<ObjectMotions>() {
        Some(motions) if motions.made_on(gpu) => {}
        _ => {
            let motions = ObjectMotions::new(gpu);
            resources.insert(motions);
        }
    }
    resources.require_mut::<ObjectMotions>()?.reset();
    Ok(())
}

/// Whether this frame runs TAA: a camera sees it and asks for it.
fn taa_runs(frame: FrameView<'_>) -> bool {
    frame.has_camera
        && frame
            .resources
            .get::<AntiAliasingFrame>()
            .is_some_and(|aa| aa.temporal.is_some())
}

/// Whether this frame runs the object motion pass: TAA runs and a drawn object moved.
fn motion_runs(frame: FrameView<'_>) -> bool {
    let resources = frame.resources;
    taa_runs(frame)
        && resources
            .get::<ObjectMotions>()
            .is_some_and(ObjectMotions::any)
        && resources
            .get::<RenderPhases>()
            .is_some_and(|phases| phases.has_draws(DrawPhase::Motion, resources))
}

/// The object motion pass: every moving draw writes its motion's number where it shows
/// (tested against the finished depth, never writing it); elsewhere the numbers are 0.
struct MotionNode;

impl FrameNode for MotionNode {
    fn prepare(&mut self, resources: &mut Resources) -> Result<u64, RenderError> {
        // The materials have numbered their moving draws.
        resources.require_scope(|resources, motions: &mut ObjectMotions| {
            let gpu = resources.require::<GpuContext>()?;
            motions.prepare(gpu, resources.require::<RenderTarget>()?);
            Ok(())
        })?;
        Ok(0)
    }

    fn runs(&self, frame: FrameView<'_>) -> bool {
        motion_runs(frame)
    }

    fn reads_scene_depth(&self) -> bool {
        true
    }

    fn record(
        &mut self,
        frame: FrameView<'_>,
        encoder: &mut wgpu::CommandEncoder,
        time: Option<&PassTimestamps>,
    ) -> Result<(), RenderError> {
        let motions = frame.resources.require::<ObjectMotions>()?;
        let Some(ids) = motions.ids_view() else {
            return Ok(());
        };
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("object motion"),
            color_attachments: &[Some(clearing_attachment(ids, wgpu::Color::TRANSPARENT))],
            depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                view: &frame.target.depth_view,
                depth_ops: None,
                stencil_ops: None,
            }),
            timestamp_writes: time.map(PassTimestamps::render),
            occlusion_query_set: None,
            multiview_mask: None,
        });
        if let Some(phases) = frame.resources.get::<RenderPhases>() {
            for draw in phases.draws(DrawPhase::Motion) {
                draw(frame.resources, &mut pass);
            }
        }
        Ok(())
    }
}

/// TAA, an HDR effect writing its history; its pass is made on the first TAA frame.
#[derive(Default)]
struct Taa {
    pass: Option<TaaPass>,
}

impl PostEffect for Taa {
    fn stage(&self) -> PostStage {
        PostStage::Hdr
    }

    fn runs(&self, frame: FrameView<'_>) -> bool {
        taa_runs(frame)
    }

    fn writes_own_image(&self) -> bool {
        true
    }

    fn output_is_tonemapped(&self) -> bool {
        true
    }

    fn reads_the_scene(&self) -> bool {
        // Its history is of the jittered scene.
        true
    }

    fn samples_scene_depth(&self) -> bool {
        // It reprojects through the depth.
        true
    }

    fn record(
        &mut self,
        frame: FrameView<'_>,
        _: PostIo<'_>,
        encoder: &mut wgpu::CommandEncoder,
        time: Option<&PassTimestamps>,
    ) -> Result<Option<PostImage>, RenderError> {
        let extracted = frame.resources.require::<ExtractedFrame>()?;
        let aa = frame.resources.require::<AntiAliasingFrame>()?;
        let Some(temporal) = aa.temporal else {
            return Ok(None);
        };
        let motions = frame.resources.require::<ObjectMotions>()?;
        let jittered = glam::Mat4::from_cols_array_2d(&extracted.frame.view_projection);
        let uniform = taa::TaaUniform::new(
            &temporal,
            jittered,
            frame
                .resources
                .get::<CameraTonemapping>()
                .map_or_else(Default::default, |operator| operator.0),
            motion_runs(frame),
        );
        Ok(self
            .pass
            .get_or_insert_with(|| TaaPass::new(frame.gpu))
            .record(
                frame.gpu,
                frame.target,
                TaaInputs {
                    uniform,
                    motions,
                    scene_depth: frame.scene_depth,
                },
                encoder,
                time,
            ))
    }
}

/// FXAA, a display effect; its pass is made on the first frame that asks for it.
#[derive(Default)]
struct Fxaa {
    pass: Option<FxaaPass>,
    warnings: ClampWarnings<FastApproximateAntiAliasing>,
}

impl PostEffect for Fxaa {
    fn stage(&self) -> PostStage {
        PostStage::Display
    }

    fn runs(&self, frame: FrameView<'_>) -> bool {
        frame
            .resources
            .get::<AntiAliasingFrame>()
            .is_some_and(|aa| aa.kind == AntiAliasing::Fxaa)
    }

    fn prepare(&mut self, resources: &mut Resources, _: HdrInput) -> Result<u64, RenderError> {
        let format = resources.require::<RenderTarget>()?.target_format();
        if !self.pass.as_ref().is_some_and(|pass| pass.is_for(format)) {
            let stage = resources.require::<Renderer>()?.full_screen_stage();
            self.pass = Some(FxaaPass::new(
                resources.require::<GpuContext>()?,
                format,
                stage,
            ));
        }
        let fxaa = resources.require::<AntiAliasingFrame>()?.fxaa;
        let settings = self.warnings.sanitized("FXAA", &fxaa);
        Ok(match &mut self.pass {
            Some(pass) => pass.upload(resources.require::<GpuContext>()?, settings.into()),
            None => 0,
        })
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
