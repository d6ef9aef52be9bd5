//! Presenting a frame: a small pass that draws the display target into a window's swapchain
//! image, whatever the swapchain's format (a texture copy cannot: the target is `Rgba8Unorm`
//! holding sRGB-encoded bytes, swapchains are often `Bgra8UnormSrgb`).

use std::collections::HashMap;

use crate::gpu::GpuContext;
use crate::gpu::layout::{fullscreen_pipeline, unfilterable_texture_2d};
use crate::render::shaders::{self, ComposedShader, FULLSCREEN_TRIANGLE, WgslFile};
use crate::render::{RenderTarget, TargetFormat};

/// present.wgsl: the two fragment entries of the present pass.
const PRESENT: WgslFile = crate::wgsl_file!("window/present.wgsl");

/// The present pass's shader.
pub const PRESENT_SHADER: ComposedShader = ComposedShader {
    name: "present",
    constants: &[],
    files: &[shaders::SRGB, FULLSCREEN_TRIANGLE, PRESENT],
};

/// Why a frame could not be presented.
#[derive(Debug, thiserror::Error, PartialEq, Eq)]
pub enum PresentError {
    /// Only 8-bit display targets hold what a screen shows.
    #[error("only an Srgb8 render target can be presented (this one is {0:?})")]
    TargetFormat(TargetFormat),
}

/// A rectangle of a window (or any image) in pixels, from its top-left corner.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ScreenRect {
    /// Left edge.
    pub x: u32,
    /// Top edge.
    pub y: u32,
    /// Width (at least 1 to show anything).
    pub width: u32,
    /// Height (at least 1 to show anything).
    pub height: u32,
}

impl ScreenRect {
    /// This rectangle cut to a `width` × `height` window; `None` where nothing is left.
    pub fn within(self, width: u32, height: u32) -> Option<Self> {
        let x = self.x.min(width);
        let y = self.y.min(height);
        let rect = Self {
            x,
            y,
            width: self.width.min(width - x),
            height: self.height.min(height - y),
        };
        (rect.width > 0 && rect.height > 0).then_some(rect)
    }
}

/// Whether a swapchain of `format` must be given linear colour: it encodes itself (sRGB
/// formats) or holds floats.
fn takes_linear(format: wgpu::TextureFormat) -> bool {
    format.is_srgb()
        || matches!(
            format,
            wgpu::TextureFormat::Rgba16Float | wgpu::TextureFormat::Rgba32Float
        )
}

/// The present pass: one pipeline per swapchain format, and the bind group of the target it
/// last presented. Owned by whatever presents (the window runner).
#[derive(Debug)]
pub struct Presenter {
    module: wgpu::ShaderModule,
    bind_group_layout: wgpu::BindGroupLayout,
    pipeline_layout: wgpu::PipelineLayout,
    pipelines: HashMap<wgpu::TextureFormat, wgpu::RenderPipeline>,
    /// The id of the target `bind_group` reads, and the group.
    bind_group: Option<(u64, wgpu::BindGroup)>,
}

impl Presenter {
    /// Compiles the present shader on `gpu`'s device.
    pub fn new(gpu: &GpuContext) -> Self {
        let device = &gpu.device;
        let module = PRESENT_SHADER.create_module(device);
        let bind_group_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("present bind group layout"),
            entries: &[unfilterable_texture_2d(0)],
        });
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("present pipeline layout"),
            bind_group_layouts: &[Some(&bind_group_layout)],
            immediate_size: 0,
        });
        Self {
            module,
            bind_group_layout,
            pipeline_layout,
            pipelines: HashMap::new(),
            bind_group: None,
        }
    }

    /// Makes the pipeline for `format` on first use, and the bind group of `target` when it is
    /// not the one presented last.
    fn follow(&mut self, gpu: &GpuContext, target: &RenderTarget, format: wgpu::TextureFormat) {
        let device = &gpu.device;
        self.pipelines.entry(format).or_insert_with(|| {
            let entry = if takes_linear(format) {
                "present_decoded"
            } else {
                "present_encoded"
            };
            fullscreen_pipeline(
                device,
                &format!("present pipeline ({format:?})"),
                Some(&self.pipeline_layout),
                &self.module,
                entry,
                format,
            )
        });
        if self.bind_group.as_ref().map(|(id, _)| *id) != Some(target.id()) {
            let group = device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("present bind group"),
                layout: &self.bind_group_layout,
                entries: &[wgpu::BindGroupEntry {
                    binding: 0,
                    resource: wgpu::BindingResource::TextureView(&target.color_view),
                }],
            });
            self.bind_group = Some((target.id(), group));
        }
    }

    /// Records into `encoder` the pass that draws `target`'s display colour into `view`, a
    /// swapchain image of `format` and `size` pixels, over `rect` of it (`None`: all of it;
    /// the rest is cleared to black).
    ///
    /// # Errors
    /// [`PresentError::TargetFormat`] for a target that is not [`TargetFormat::Srgb8`].
    pub fn record(
        &mut self,
        gpu: &GpuContext,
        target: &RenderTarget,
        encoder: &mut wgpu::CommandEncoder,
        view: &wgpu::TextureView,
        (format, size): (wgpu::TextureFormat, (u32, u32)),
        rect: Option<ScreenRect>,
    ) -> Result<(), PresentError> {
        if target.target_format() != TargetFormat::Srgb8 {
            return Err(PresentError::TargetFormat(target.target_format()));
        }
        self.follow(gpu, target, format);
        let (Some(pipeline), Some((_, bind_group))) =
            (self.pipelines.get(&format), &self.bind_group)
        else {
            return Ok(());
        };
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("present"),
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
        });
        let Some(rect) = rect
            .unwrap_or(ScreenRect {
                x: 0,
                y: 0,
                width: size.0,
                height: size.1,
            })
            .within(size.0, size.1)
        else {
            return Ok(());
        };
        pass.set_viewport(
            rect.x as f32,
            rect.y as f32,
            rect.width as f32,
            rect.height as f32,
            0.0,
            1.0,
        );
        pass.set_pipeline(pipeline);
        pass.set_bind_group(0, bind_group, &[]);
        pass.draw(0..3, 0..1);
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn swapchains_that_encode_or_hold_floats_take_linear_colour() {
        assert!(takes_linear(wgpu::TextureFormat::Bgra8UnormSrgb));
        assert!(takes_linear(wgpu::TextureFormat::Rgba8UnormSrgb));
        assert!(takes_linear(wgpu::TextureFormat::Rgba16Float));
        assert!(!takes_linear(wgpu::TextureFormat::Bgra8Unorm));
        assert!(!takes_linear(wgpu::TextureFormat::Rgb10a2Unorm));
    }

    #[test]
    fn a_rectangle_is_cut_to_the_window() {
        let rect = ScreenRect {
            x: 300,
            y: 0,
            width: 1000,
            height: 720,
        };
        assert_eq!(
            rect.within(1280, 720),
            Some(ScreenRect {
                x: 300,
                y: 0,
                width: 980,
                height: 720
            })
        );
        assert_eq!(rect.within(200, 720), None);
    }
}
