//! The core's passes of a frame, one function per phase, recorded into the frame's encoder by
//! [`super::render_frame`] as its [`FramePlan`] says.

use super::frame::FramePlan;
use super::frame_nodes::FrameView;
use super::{
    DrawPhase, ExtractedFrame, RenderPhase, RenderPhases, RenderTarget, Renderer, SettledDepth,
};
use crate::gpu::{GpuContext, PassTimestamps, clearing_attachment};
use crate::{AppError, Resources};

/// What the phases of one frame read: the app's resources and the frame's plan.
pub(super) struct FramePasses<'a> {
    resources: &'a Resources,
    plan: &'a FramePlan,
    gpu: &'a GpuContext,
    target: &'a RenderTarget,
    extracted: &'a ExtractedFrame,
    renderer: &'a Renderer,
    phases: Option<&'a RenderPhases>,
}

impl<'a> FramePasses<'a> {
    pub fn new(resources: &'a Resources, plan: &'a FramePlan) -> Result<Self, AppError> {
        Ok(Self {
            resources,
            plan,
            gpu: resources.require::<GpuContext>()?,
            target: resources.require::<RenderTarget>()?,
            extracted: resources.require::<ExtractedFrame>()?,
            renderer: resources.require::<Renderer>()?,
            phases: resources.get::<RenderPhases>(),
        })
    }

    /// What the frame's nodes read of it.
    pub fn view(&self) -> FrameView<'a> {
        FrameView {
            resources: self.resources,
            gpu: self.gpu,
            target: self.target,
            has_camera: self.plan.has_camera,
            scene_depth: self.renderer.scene_depth(self.target),
        }
    }

    /// A command encoder on the frame's device.
    pub fn encoder(&self, label: &str) -> wgpu::CommandEncoder {
        self.gpu
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some(label) })
    }

    /// Submits the frame's passes.
    pub fn submit(&self, encoder: wgpu::CommandEncoder) {
        self.gpu.queue.submit([encoder.finish()]);
    }

    /// Draws every material's draws of `phase` into `pass` (none without a camera).
    fn draw_phase(&self, phase: DrawPhase, pass: &mut wgpu::RenderPass<'_>) {
        if let (true, Some(phases)) = (self.plan.has_camera, self.phases) {
            for draw in phases.draws(phase) {
                draw(self.resources, pass);
            }
        }
    }

    /// The target's depth as the attachment, with `ops` (`None`: read-only).
    fn depth_attachment(
        &self,
        ops: Option<wgpu::Operations<f32>>,
    ) -> Option<wgpu::RenderPassDepthStencilAttachment<'a>> {
        Some(wgpu::RenderPassDepthStencilAttachment {
            view: &self.target.depth_view,
            depth_ops: ops,
            stencil_ops: None,
        })
    }

    /// Builds the textures derived in the Prepare stage.
    pub fn derived_textures(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        time: Option<&PassTimestamps>,
    ) {
        self.renderer
            .assets
            .pending_derived_builds()
            .record(encoder, time);
    }

    /// The depth prepass. On the deferred path it is the visibility pass: its fragments also
    /// merge each pixel's draw and triangle into the visibility keys (0: none), which a compute
    /// pass clears first (and the polygon pass fills), inside the phase's timestamps; where
    /// the polygon pass found every draw no render pass runs.
    pub fn prepass(&self, encoder: &mut wgpu::CommandEncoder, time: Option<&PassTimestamps>) {
        let clear = self
            .renderer
            .visibility
            .as_ref()
            .filter(|_| self.plan.deferred);
        let raster = clear.is_none() || self.plan.visibility_raster;
        if let Some(visibility) = clear {
            let polygons = self.plan.polygons.then_some(&self.renderer.polygons);
            visibility.record_clear(encoder, time, self.plan.candidates, polygons, !raster);
        }
        // An empty depth pass still clears the whole attachment, which nothing reads here.
        if raster {
            let time = time.map(|time| time.render_part(clear.is_none(), true));
            self.depth_pass(encoder, DrawPhase::Prepass, wgpu::LoadOp::Clear(1.0), time);
        }
    }

    /// The encoder work plugins added to `phase`, after its pass (with a camera).
    pub fn work(&self, phase: RenderPhase, encoder: &mut wgpu::CommandEncoder) {
        if let (true, Some(phases)) = (self.plan.has_camera, self.phases) {
            for work in phases.work(phase) {
                work(self.resources, encoder);
            }
        }
    }

    /// The opaque phase: clears the scene and draws every opaque surface. After a prepass the
    /// depth is read-only: materials test against it, and may sample it.
    pub fn opaque(&self, encoder: &mut wgpu::CommandEncoder, time: Option<&PassTimestamps>) {
        let [r, g, b, a] = clear_value(self.extracted.clear_color).map(f64::from);
        let depth_ops = (!self.plan.prepass).then_some(wgpu::Operations {
            load: wgpu::LoadOp::Clear(1.0),
            store: if self.plan.keep_depth {
                wgpu::StoreOp::Store
            } else {
                wgpu::StoreOp::Discard
            },
        });
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("opaque"),
            color_attachments: &[Some(clearing_attachment(
                &self.target.scene_view,
                wgpu::Color { r, g, b, a },
            ))],
            depth_stencil_attachment: self.depth_attachment(depth_ops),
            timestamp_writes: time.map(PassTimestamps::render),
            occlusion_query_set: None,
            multiview_mask: None,
        });
        self.draw_phase(DrawPhase::Opaque, &mut pass);
    }

    /// The deferred path's compute resolve (and the background, where no opaque pass ran);
    /// with candidates, after the candidate pass and before the settled depth where a later
    /// pass reads it (`FramePlan::settled_depth`), timed as one span.
    pub fn resolve(&self, encoder: &mut wgpu::CommandEncoder, time: Option<&PassTimestamps>) {
        let Some(phases) = self.phases else {
            return;
        };
        // Where the polygon pass finds every candidate, no candidate is rasterized.
        let candidates = self.plan.candidates
            && !(self.plan.polygons && self.renderer.candidate_order.all_polygons());
        let settled_depth = self.plan.settled_depth == SettledDepth::DepthPass;
        if candidates {
            let time = time.map(|time| time.render_part(true, false));
            // Where the visibility pass did not rasterize, the depth was not cleared.
            let load = if self.plan.visibility_raster {
                wgpu::LoadOp::Load
            } else {
                wgpu::LoadOp::Clear(1.0)
            };
            self.depth_pass(encoder, DrawPhase::Candidates, load, time);
        }
        let (first, last) = (!candidates, !settled_depth);
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("deferred resolve"),
            timestamp_writes: time
                .filter(|_| first || last)
                .map(|time| time.compute_part(first, last)),
        });
        if self.plan.polygons {
            self.renderer.candidate_polygons.record(&mut pass);
        }
        if self.plan.background_pass
            && let Some(background) = &self.renderer.background
        {
            background.record(&mut pass);
        }
        for dispatch in phases.resolves() {
            dispatch(self.resources, &mut pass);
        }
        if let (SettledDepth::Image, Some(visibility)) =
            (self.plan.settled_depth, &self.renderer.visibility)
        {
            visibility.record_settled_depth(&mut pass);
        }
        drop(pass);
        if settled_depth {
            let time = time.map(|time| time.render_part(false, true));
            self.depth_pass(encoder, DrawPhase::SettledDepth, wgpu::LoadOp::Load, time);
        }
    }

    /// A render pass of `phase`'s draws (its sorted list first) into the depth alone, kept.
    fn depth_pass(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        phase: DrawPhase,
        load: wgpu::LoadOp<f32>,
        timestamp_writes: Option<wgpu::RenderPassTimestampWrites<'_>>,
    ) {
        let (label, sorted) = match phase {
            DrawPhase::Prepass if self.plan.deferred => {
                ("visibility", Some(&self.renderer.prepass_order))
            }
            DrawPhase::Prepass => ("prepass", Some(&self.renderer.prepass_order)),
            DrawPhase::Candidates => ("candidates", Some(&self.renderer.candidate_order)),
            _ => ("settled depth", None),
        };
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some(label),
            color_attachments: &[],
            depth_stencil_attachment: self.depth_attachment(Some(wgpu::Operations {
                load,
                store: wgpu::StoreOp::Store,
            })),
            timestamp_writes,
            occlusion_query_set: None,
            multiview_mask: None,
        });
        if let (true, Some(phases), Some(sorted)) = (self.plan.has_camera, self.phases, sorted) {
            let without_polygons = self.plan.polygons;
            sorted.record(phases, self.resources, &mut pass, without_polygons);
        }
        self.draw_phase(phase, &mut pass);
    }

    /// The transparent phase: every material's blended draws farthest first, then the draws
    /// materials record themselves.
    pub fn transparent(&self, encoder: &mut wgpu::CommandEncoder, time: Option<&PassTimestamps>) {
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("transparent"),
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view: &self.target.scene_view,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations {
                    load: wgpu::LoadOp::Load,
                    store: wgpu::StoreOp::Store,
                },
            })],
            depth_stencil_attachment: self.depth_attachment(None),
            timestamp_writes: time.map(PassTimestamps::render),
            occlusion_query_set: None,
            multiview_mask: None,
        });
        if let Some(phases) = self.phases {
            self.renderer
                .transparent
                .record(phases, self.resources, &mut pass, false);
        }
        self.draw_phase(DrawPhase::Transparent, &mut pass);
    }
}

/// What the scene is cleared to: the clear colour as set, marked display-referred
/// (display_referred.rs), so neither exposure nor tonemapping changes the background.
pub(crate) fn clear_value(clear: crate::Color) -> [f32; 4] {
    [
        clear.r,
        clear.g,
        clear.b,
        super::display_referred_alpha(clear.a),
    ]
}
