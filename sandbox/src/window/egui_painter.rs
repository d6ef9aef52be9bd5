//! Paints egui's output with egui-wgpu into the window (and, for a screenshot, into an
//! offscreen texture), with the plugin's rendered scene registered as an egui texture.
//!
//! egui-wgpu samples user textures as gamma-encoded `Rgba8Unorm`, but the plugin's target is
//! `Rgba8UnormSrgb` without an `Rgba8Unorm` view format, so the scene is copied each frame into
//! a same-sized `Rgba8Unorm` texture (a byte copy: sRGB and non-sRGB formats are
//! copy-compatible) that egui shows.

use egui::TextureId;
use egui_wgpu::{Renderer, RendererOptions, ScreenDescriptor};
use pom::GpuContext;
use pom::render::RenderTarget;

use super::screenshot::ScreenshotTarget;

/// The egui renderer and the texture through which it shows the scene.
pub struct EguiPainter {
    renderer: Renderer,
    scene_copy: wgpu::Texture,
    /// The egui texture showing the scene.
    pub scene_texture: TextureId,
}

/// One frame of egui output, ready to paint.
pub struct EguiFrame<'a> {
    /// Tessellated shapes.
    pub paint_jobs: &'a [egui::ClippedPrimitive],
    /// Font and image uploads and frees; drained by [`EguiPainter::paint`].
    pub textures: &'a mut egui::TexturesDelta,
    /// Window size in pixels and the scale.
    pub screen: ScreenDescriptor,
}

fn scene_copy_texture(gpu: &GpuContext, width: u32, height: u32) -> wgpu::Texture {
    gpu.device.create_texture(&wgpu::TextureDescriptor {
        label: Some("sandbox viewport texture"),
        size: wgpu::Extent3d {
            width,
            height,
            depth_or_array_layers: 1,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format: wgpu::TextureFormat::Rgba8Unorm,
        usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
        view_formats: &[],
    })
}

impl EguiPainter {
    /// A painter for a surface of `format`, showing `target`.
    pub fn new(gpu: &GpuContext, format: wgpu::TextureFormat, target: &RenderTarget) -> Self {
        let mut renderer = Renderer::new(&gpu.device, format, RendererOptions::default());
        let (width, height) = target.size();
        let scene_copy = scene_copy_texture(gpu, width, height);
        let scene_texture = renderer.register_native_texture(
            &gpu.device,
            &scene_copy.create_view(&wgpu::TextureViewDescriptor::default()),
            wgpu::FilterMode::Linear,
        );
        Self {
            renderer,
            scene_copy,
            scene_texture,
        }
    }

    /// Makes the scene texture match `target`'s size (after the target was replaced).
    fn follow_target_size(&mut self, gpu: &GpuContext, target: &RenderTarget) {
        if target.size() == (self.scene_copy.width(), self.scene_copy.height()) {
            return;
        }
        let (width, height) = target.size();
        self.scene_copy = scene_copy_texture(gpu, width, height);
        self.renderer.update_egui_texture_from_wgpu_texture(
            &gpu.device,
            &self
                .scene_copy
                .create_view(&wgpu::TextureViewDescriptor::default()),
            wgpu::FilterMode::Linear,
            self.scene_texture,
        );
    }

    /// Copies the scene from `target`, paints `frame` into `view` and, when given, into
    /// `screenshot` too, and submits.
    pub fn paint(
        &mut self,
        gpu: &GpuContext,
        target: &RenderTarget,
        frame: EguiFrame<'_>,
        view: &wgpu::TextureView,
        screenshot: Option<&ScreenshotTarget>,
    ) {
        self.follow_target_size(gpu, target);
        for (id, deltas) in frame.textures.set.drain() {
            for delta in &deltas {
                self.renderer
                    .update_texture(&gpu.device, &gpu.queue, id, delta);
            }
        }
        let mut encoder = gpu
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("sandbox egui encoder"),
            });
        encoder.copy_texture_to_texture(
            target.color.as_image_copy(),
            self.scene_copy.as_image_copy(),
            self.scene_copy.size(),
        );
        let callbacks = self.renderer.update_buffers(
            &gpu.device,
            &gpu.queue,
            &mut encoder,
            frame.paint_jobs,
            &frame.screen,
        );
        let views = std::iter::once(view).chain(screenshot.map(|shot| &shot.view));
        for (index, view) in views.enumerate() {
            let mut pass = encoder
                .begin_render_pass(&wgpu::RenderPassDescriptor {
                    label: Some(if index == 0 {
                        "egui pass"
                    } else {
                        "egui screenshot pass"
                    }),
                    color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                        view,
                        depth_slice: None,
                        resolve_target: None,
                        ops: wgpu::Operations {
                            load: wgpu::LoadOp::Clear(wgpu::Color::BLACK),
                            store: wgpu::StoreOp::Store,
                        },
                    })],
                    depth_stencil_attachment: None,
                    timestamp_writes: None,
                    occlusion_query_set: None,
                    multiview_mask: None,
                })
                .forget_lifetime();
            self.renderer
                .render(&mut pass, frame.paint_jobs, &frame.screen);
        }
        gpu.queue
            .submit(callbacks.into_iter().chain([encoder.finish()]));
        for id in frame.textures.free.drain() {
            self.renderer.free_texture(&id);
        }
    }
}
