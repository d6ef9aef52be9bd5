//! Paints egui's output with egui-wgpu over the scene the window runner presented (into the
//! swapchain image, or a screenshot's texture), with the plugin's rendered scene and the split
//! view's second image registered as egui textures (the wipe shows the second).
//!
//! egui-wgpu samples user textures as gamma-encoded `Rgba8Unorm`; the plugin's targets offer
//! such a view of their sRGB bytes (`RenderTarget::display_view`), so egui samples them directly.

use egui::TextureId;
use egui_wgpu::{Renderer, RendererOptions, ScreenDescriptor};
use pom::GpuContext;
use pom::render::RenderTarget;

/// The egui renderer and the textures through which it shows the scene.
pub struct EguiPainter {
    renderer: Renderer,
    /// The egui texture showing the main scene image.
    pub scene_texture: TextureId,
    /// The egui texture showing the split view's second image.
    pub split_texture: TextureId,
}

/// One frame of egui output, ready to paint.
pub struct EguiFrame<'a> {
    /// Tessellated shapes.
    pub paint_jobs: &'a [egui::ClippedPrimitive],
    /// Font and image uploads and frees; drained by the first [`EguiPainter::paint`].
    pub textures: &'a mut egui::TexturesDelta,
    /// Window size in pixels and the scale.
    pub screen: ScreenDescriptor,
}

impl EguiPainter {
    /// A painter for a surface of `format`, showing `target` (also as the split image until
    /// one is given).
    pub fn new(gpu: &GpuContext, format: wgpu::TextureFormat, target: &RenderTarget) -> Self {
        let mut renderer = Renderer::new(&gpu.device, format, RendererOptions::default());
        let mut register = || {
            renderer.register_native_texture(
                &gpu.device,
                &target.display_view,
                wgpu::FilterMode::Linear,
            )
        };
        let (scene_texture, split_texture) = (register(), register());
        Self {
            renderer,
            scene_texture,
            split_texture,
        }
    }

    /// Points the scene and split textures at this frame's targets (either may have been
    /// replaced since the last frame; a new bind group per frame costs next to nothing).
    fn show_targets(&mut self, gpu: &GpuContext, scene: &RenderTarget, split: &RenderTarget) {
        for (texture, target) in [(self.scene_texture, scene), (self.split_texture, split)] {
            self.renderer.update_egui_texture_from_wgpu_texture(
                &gpu.device,
                &target.display_view,
                wgpu::FilterMode::Linear,
                texture,
            );
        }
    }

    /// Records into `encoder` the pass that paints `frame` over `view` (which holds the scene
    /// already), showing `scene` and `split` (the main target again when there is no split
    /// view). The pass writes `overlay_time`'s timestamps.
    pub fn paint(
        &mut self,
        gpu: &GpuContext,
        (scene, split): (&RenderTarget, &RenderTarget),
        frame: EguiFrame<'_>,
        (encoder, view): (&mut wgpu::CommandEncoder, &wgpu::TextureView),
        overlay_time: Option<&pom::gpu::PassTimestamps>,
    ) {
        self.show_targets(gpu, scene, split);
        for (id, deltas) in frame.textures.set.drain() {
            for delta in &deltas {
                self.renderer
                    .update_texture(&gpu.device, &gpu.queue, id, delta);
            }
        }
        let callbacks = self.renderer.update_buffers(
            &gpu.device,
            &gpu.queue,
            encoder,
            frame.paint_jobs,
            &frame.screen,
        );
        // Paint callbacks' own command buffers (the sandbox has none) go first.
        if !callbacks.is_empty() {
            gpu.queue.submit(callbacks);
        }
        let mut pass = encoder
            .begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("egui pass"),
                color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                    view,
                    depth_slice: None,
                    resolve_target: None,
                    ops: wgpu::Operations {
                        load: wgpu::LoadOp::Load,
                        store: wgpu::StoreOp::Store,
                    },
                })],
                depth_stencil_attachment: None,
                timestamp_writes: overlay_time.map(pom::gpu::PassTimestamps::render),
                occlusion_query_set: None,
                multiview_mask: None,
            })
            .forget_lifetime();
        self.renderer
            .render(&mut pass, frame.paint_jobs, &frame.screen);
        drop(pass);
        for id in frame.textures.free.drain() {
            self.renderer.free_texture(&id);
        }
    }
}
