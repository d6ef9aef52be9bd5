//! Scene shadows' pass: [`ShadowsPlugin`] joins the shadows phase with one depth pass per
//! shadow map (a cascade, a spot light's map, a cube face), into which every material draws
//! its casters from the light's view, timed as "shadows". Which lights cast and how is the
//! [`crate::LightShadows`] component: in the Extract stage the plugin plans each casting
//! light's maps (plan.rs; where each looks from: views.rs) and points the light's GPU record at
//! them. The maps themselves, and what receivers read of them, belong to the frame's bindings
//! (`render/shadow_maps.rs`, `render/shadows.wgsl`), so that every material can sample them
//! whether or not this feature is in the app.

mod cascades;
mod kept;
mod plan;
mod views;

use kept::KeptShadowViews;
pub use kept::ShadowMapStats;

use crate::gpu::PassTimestamps;
use crate::render::{
    ExtractedFrame, FrameNode, FrameNodes, FrameView, NodePlace, RenderError, RenderPhase,
    RenderPhases, Renderer,
};
use crate::{App, Plugin, Stage};

/// The node name the shadow maps are timed under.
pub const SHADOW_MAPS_NODE: &str = RenderPhase::Shadows.name();

/// Plans and draws the shadow maps the lights ask for (the render plugin adds it with its
/// standard features). Without it the frame has no shadow map: lights cast no scene shadow.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct ShadowsPlugin;

impl Plugin for ShadowsPlugin {
    fn build(&self, app: &mut App) {
        app.resources.get_or_default::<FrameNodes>().add(
            NodePlace::new(SHADOW_MAPS_NODE, RenderPhase::Shadows),
            ShadowMapsNode::default,
        );
        app.resources.get_or_default::<ShadowMapStats>();
        app.add_system(Stage::Extract, plan::plan_shadow_maps);
    }
}

/// One pass per shadow map, each drawing every shadow caster from its light, for the maps
/// whose view or casters changed since they were drawn (kept.rs).
#[derive(Default)]
struct ShadowMapsNode {
    kept: KeptShadowViews,
}

impl FrameNode for ShadowMapsNode {
    fn runs(&self, frame: FrameView<'_>) -> bool {
        let resources = frame.resources;
        resources
            .get::<ExtractedFrame>()
            .is_some_and(|extracted| !extracted.shadow_views.is_empty())
            && resources
                .get::<RenderPhases>()
                .is_some_and(|phases| phases.shadow_draws().next().is_some())
    }

    fn record(
        &mut self,
        frame: FrameView<'_>,
        encoder: &mut wgpu::CommandEncoder,
        time: Option<&PassTimestamps>,
    ) -> Result<(), RenderError> {
        let resources = frame.resources;
        let phases = resources.require::<RenderPhases>()?;
        let extracted = resources.require::<ExtractedFrame>()?;
        let renderer = resources.require::<Renderer>()?;
        let shadow_maps = &renderer.shadow_maps;
        let stats = resources.get::<ShadowMapStats>();
        let layer_size = shadow_maps.layer_size();
        let count = extracted.shadow_views.len();
        let target_size = extracted.frame.target_size;
        // The noise changes a map only where a caster reads it.
        let noise = if shadow_maps.casters.read_frame_noise() {
            [target_size[2], target_size[3]]
        } else {
            [0; 2]
        };
        self.kept
            .begin_frame(shadow_maps.casters, shadow_maps.generation());
        for (index, plan) in extracted.shadow_views.iter().enumerate() {
            let Some(layer) = shadow_maps.layer_view(plan.gpu.layer) else {
                continue;
            };
            let (first, last) = (index == 0, index + 1 == count);
            let draw = self.kept.needs_drawing(plan, noise, layer_size);
            if let Some(stats) = stats {
                stats.count(draw);
            }
            // Kept: not drawn again, except an empty pass where the node's timestamps start or
            // end, so the span stays measured.
            if !draw && !(time.is_some() && (first || last)) {
                continue;
            }
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("shadow map"),
                color_attachments: &[],
                depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                    view: layer,
                    depth_ops: Some(wgpu::Operations {
                        load: if draw {
                            wgpu::LoadOp::Clear(1.0)
                        } else {
                            wgpu::LoadOp::Load
                        },
                        store: wgpu::StoreOp::Store,
                    }),
                    stencil_ops: None,
                }),
                // The node's span: the first map's pass begins it, the last one ends it.
                timestamp_writes: time
                    .filter(|_| first || last)
                    .map(|time| time.render_part(first, last)),
                occlusion_query_set: None,
                multiview_mask: None,
            });
            // A smaller map draws into a corner of its layer.
            let size = plan.map_size.min(layer_size) as f32;
            pass.set_viewport(0.0, 0.0, size, size, 0.0, 1.0);
            if draw {
                for draw_casters in phases.shadow_draws() {
                    draw_casters(resources, &mut pass, 1 + index as u32);
                }
            }
        }
        Ok(())
    }
}
