//! Presenting a frame: a small pass that draws the display target into a window's swapchain
//! image, whatever the swapchain's format (a texture copy cannot: the target is `Rgba8Unorm`
//! holding sRGB-encoded bytes, swapchains are often `Bgra8UnormSrgb`).

use std::collections::HashMap;

use super::layout::{fullscreen_pipeline, unfilterable_texture_2d};
use super::shaders::{ComposedShader, FULLSCREEN_TRIANGLE, WgslFile};
use super::{GpuContext, RenderTarget, TargetFormat};

/// present.wgsl: the two fragment entries of the present pass.
const PRESENT: WgslFile = crate::wgsl_file!("render/present.wgsl");

/// The present pass's shader.
pub const PRESENT_SHADER: ComposedShader = ComposedShader {
    name: "present",
    constants: &[],
    files: &[FULLSCREEN_TRIANGLE, PRESENT],
};

/// Why a frame could not be presented.
#[derive(Debug, thiserror::Error, PartialEq, Eq)]
pub enum PresentError {
    /// Only 8-bit display targets hold what a screen shows.
    #[error("only an Srgb8 render target can be presented (this one is {0:?})")]
    TargetFormat(TargetFormat),
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

    /// Records into `encoder` the pass that draws `target`'s display colour into `view`, a
    /// swapchain image of `format`.
    ///
    /// # Errors
    /// [`PresentError::TargetFormat`] for a target that is not [`TargetFormat::Srgb8`].
    pub fn record(
        &mut self,
        gpu: &GpuContext,
        target: &RenderTarget,
        encoder: &mut wgpu::CommandEncoder,
        view: &wgpu::TextureView,
        format: wgpu::TextureFormat,
    ) -> Result<(), PresentError> {
        if target.target_format() != TargetFormat::Srgb8 {
            return Err(PresentError::TargetFormat(target.target_format()));
        }
        let device = &gpu.device;
        let pipeline = self.pipelines.entry(format).or_insert_with(|| {
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
        let Some((_, bind_group)) = &self.bind_group else {
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
}
