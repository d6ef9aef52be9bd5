//! The passes of a frame, one function per phase, recorded into the frame's encoder by
//! [`super::render_frame`] as its [`FramePlan`] says; post-processing in its own submission.

use super::frame::FramePlan;
use super::{
    DrawPhase, ExtractedFrame, FxaaPass, GpuContext, PassTimestamps, PostRouting, RenderPhase,
    RenderPhases, RenderTarget, Renderer, TaaInputs, TaaPass, TaaUniform, clearing_attachment,
};
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
    /// pass clears first, inside the phase's timestamps.
    pub fn prepass(&self, encoder: &mut wgpu::CommandEncoder, time: Option<&PassTimestamps>) {
        let clear = self
            .renderer
            .visibility
            .as_ref()
            .filter(|_| self.plan.deferred);
        if let Some(visibility) = clear {
            visibility.record_clear(encoder, time);
        }
        let deferred = self.plan.deferred;
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some(if deferred { "visibility" } else { "prepass" }),
            color_attachments: &[],
            depth_stencil_attachment: self.depth_attachment(Some(wgpu::Operations {
                load: wgpu::LoadOp::Clear(1.0),
                store: wgpu::StoreOp::Store,
            })),
            timestamp_writes: time.map(|time| time.render_part(clear.is_none(), true)),
            occlusion_query_set: None,
            multiview_mask: None,
        });
        if let (true, Some(phases)) = (self.plan.has_camera, self.phases) {
            self.renderer
                .prepass_order
                .record(phases, self.resources, &mut pass);
        }
        self.draw_phase(DrawPhase::Prepass, &mut pass);
    }

    /// One pass per shadow map, each drawing every shadow caster from its light.
    pub fn shadow_maps(&self, encoder: &mut wgpu::CommandEncoder, time: Option<&PassTimestamps>) {
        let Some(phases) = self.phases else {
            return;
        };
        let shadow_maps = &self.renderer.shadow_maps;
        let layer_size = shadow_maps.layer_size();
        let count = self.extracted.shadow_views.len();
        for (index, plan) in self.extracted.shadow_views.iter().enumerate() {
            let Some(layer) = shadow_maps.layer_view(plan.gpu.layer) else {
                continue;
            };
            let (first, last) = (index == 0, index + 1 == count);
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("shadow map"),
                color_attachments: &[],
                depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                    view: layer,
                    depth_ops: Some(wgpu::Operations {
                        load: wgpu::LoadOp::Clear(1.0),
                        store: wgpu::StoreOp::Store,
                    }),
                    stencil_ops: None,
                }),
                // The phase's span: the first map's pass begins it, the last one ends it.
                timestamp_writes: time
                    .filter(|_| first || last)
                    .map(|time| time.render_part(first, last)),
                occlusion_query_set: None,
                multiview_mask: None,
            });
            // A smaller map draws into a corner of its layer.
            let size = plan.map_size.min(layer_size) as f32;
            pass.set_viewport(0.0, 0.0, size, size, 0.0, 1.0);
            for draw in phases.shadow_draws() {
                draw(self.resources, &mut pass, 1 + index as u32);
            }
        }
    }

    /// The materials' own work of the shadows phase.
    pub fn shadow_work(&self, encoder: &mut wgpu::CommandEncoder) {
        self.work(RenderPhase::Shadows, encoder);
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
            // TAA reprojects through the depth.
            store: if self.plan.transparent || self.plan.taa {
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

    /// The deferred path's compute resolve (and the background, where no opaque pass ran).
    pub fn resolve(&self, encoder: &mut wgpu::CommandEncoder, time: Option<&PassTimestamps>) {
        let Some(phases) = self.phases else {
            return;
        };
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("deferred resolve"),
            timestamp_writes: time.map(PassTimestamps::compute),
        });
        if self.plan.background_in_compute
            && let Some(background) = &self.renderer.background
        {
            background.record(&mut pass);
        }
        for dispatch in phases.resolves() {
            dispatch(self.resources, &mut pass);
        }
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
                .record(phases, self.resources, &mut pass);
        }
        self.draw_phase(DrawPhase::Transparent, &mut pass);
    }

    /// TAA's object motion pass: every moving draw writes its motion's number where it shows
    /// (tested against the finished depth, never writing it); elsewhere the numbers are 0.
    pub fn object_motion(&self, encoder: &mut wgpu::CommandEncoder, time: Option<&PassTimestamps>) {
        let Some(ids) = self.renderer.object_motions.ids_view() else {
            return;
        };
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("object motion"),
            color_attachments: &[Some(clearing_attachment(ids, wgpu::Color::TRANSPARENT))],
            depth_stencil_attachment: self.depth_attachment(None),
            timestamp_writes: time.map(PassTimestamps::render),
            occlusion_query_set: None,
            multiview_mask: None,
        });
        self.draw_phase(DrawPhase::Motion, &mut pass);
    }
}

/// The timestamps of the post phase's passes.
pub(super) struct PostTimes<'a> {
    pub taa: Option<&'a PassTimestamps>,
    pub post: Option<&'a PassTimestamps>,
    pub post_filter: Option<&'a PassTimestamps>,
}

/// Post-processing and the materials' work of that phase, in a submission after the frame's:
/// TAA on the HDR scene, tonemapping, the post filter, as `plan` says.
pub(super) fn post_process(
    resources: &mut Resources,
    plan: &FramePlan,
    times: PostTimes<'_>,
) -> Result<(), AppError> {
    resources.require_scope(|resources, renderer: &mut Renderer| {
        renderer.assets.derived_builds_submitted();
        let gpu = resources.require::<GpuContext>()?;
        let target = resources.require::<RenderTarget>()?;
        let extracted = resources.require::<ExtractedFrame>()?;
        let mut encoder = gpu
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("post-process encoder"),
            });
        let colour = match extracted.temporal.filter(|_| plan.taa) {
            Some(frame) => {
                let jittered = glam::Mat4::from_cols_array_2d(&extracted.frame.view_projection);
                renderer
                    .taa
                    .get_or_insert_with(|| TaaPass::new(gpu))
                    .record(
                        gpu,
                        target,
                        TaaInputs {
                            uniform: TaaUniform::new(
                                &frame,
                                jittered,
                                extracted.tonemapping,
                                plan.object_motion,
                            ),
                            motions: &renderer.object_motions,
                        },
                        &mut encoder,
                        times.taa,
                    )
            }
            None => None,
        };
        let format = target.target_format();
        let filter = if plan.post_filter {
            if !renderer
                .fxaa
                .as_ref()
                .is_some_and(|fxaa| fxaa.is_for(format))
            {
                renderer.fxaa = Some(FxaaPass::new(gpu, format, renderer.post.stage()));
            }
            renderer.fxaa.as_mut()
        } else {
            None
        };
        let (output, filter) = match filter {
            Some(fxaa) => {
                let (id, view) = fxaa.tonemapped_view(gpu, target);
                (Some((id, view.clone())), Some(&*fxaa))
            }
            None => (None, None),
        };
        let routing = PostRouting {
            colour,
            output: output.as_ref().map(|(id, view)| (*id, view)),
        };
        renderer
            .post
            .record(gpu, target, routing, &mut encoder, times.post);
        if let Some(fxaa) = filter {
            fxaa.record(target, &mut encoder, times.post_filter);
        }
        if let Some(phases) = resources.get::<RenderPhases>() {
            for work in phases.work(RenderPhase::PostProcess) {
                work(resources, &mut encoder);
            }
        }
        gpu.queue.submit([encoder.finish()]);
        Ok(())
    })
}

/// What the scene is cleared to: the clear colour as set, its negative alpha marking it
/// display-referred (post_process.wgsl), so neither exposure nor tonemapping changes the
/// background.
pub(super) fn clear_value(clear: crate::Color) -> [f32; 4] {
    [clear.r, clear.g, clear.b, -1.0 - clear.a.clamp(0.0, 1.0)]
}
