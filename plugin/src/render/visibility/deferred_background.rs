//! The deferred path's background pass (deferred_background.wgsl): the clear colour where the
//! visibility buffer holds no draw, from compute, on deferred frames whose opaque phase has
//! nothing to draw (it then skips that phase's render pass) and whose materials' resolves do
//! not write it themselves (their tile classification or whole-target dispatch reads every key
//! anyway).

use super::VisibilityBuffer;
use crate::gpu::GpuContext;
use crate::render::RenderTarget;
use crate::render::shaders::{self, ComposedShader, WgslFile};

/// The background pass's WGSL file.
pub const DEFERRED_BACKGROUND_ENTRY: WgslFile =
    crate::wgsl_file!(nested "render/visibility/deferred_background.wgsl");

/// The background pass's shader.
pub const DEFERRED_BACKGROUND: ComposedShader = ComposedShader {
    name: "deferred_background.wgsl",
    constants: &[shaders::deferred_header],
    files: &[shaders::VISIBILITY_READ, DEFERRED_BACKGROUND_ENTRY],
};

/// Mirrors `BackgroundParams` in deferred_background.wgsl.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub(crate) struct BackgroundParams {
    clear_color: [f32; 4],
    width: u32,
    height: u32,
    _padding: [u32; 2],
}

crate::wgsl_layout!(BackgroundParams {
    clear_color,
    width,
    height,
    _padding
});

/// The background pipeline, its clear-colour uniform, and the bind group of the current target.
#[derive(Debug)]
pub(crate) struct DeferredBackground {
    pipeline: wgpu::ComputePipeline,
    params: wgpu::Buffer,
    bind_group: Option<(u64, wgpu::BindGroup)>,
    workgroups: (u32, u32),
    /// What `params` holds (written only when the frame's differ).
    uploaded: Option<BackgroundParams>,
}

impl DeferredBackground {
    /// The pipeline for a scene target of `scene_format`.
    pub(crate) fn new(gpu: &GpuContext, scene_format: wgpu::TextureFormat) -> Self {
        let target = shaders::ShaderTarget::of_device(&gpu.device, scene_format);
        let source = DEFERRED_BACKGROUND.source_for(&target);
        let module = shaders::create_module(&gpu.device, DEFERRED_BACKGROUND.name, source);
        let pipeline = gpu
            .device
            .create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                label: Some("deferred background"),
                layout: None,
                module: &module,
                entry_point: Some("cs_background"),
                compilation_options: Default::default(),
                cache: None,
            });
        let params = gpu.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("deferred background parameters"),
            size: std::mem::size_of::<BackgroundParams>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        Self {
            pipeline,
            params,
            bind_group: None,
            uploaded: None,
            workgroups: (0, 0),
        }
    }

    /// Writes this frame's clear colour (as the opaque pass clears: see `render_frame`) and
    /// binds `target` and its visibility buffer.
    pub(crate) fn prepare(
        &mut self,
        gpu: &GpuContext,
        target: &RenderTarget,
        visibility: &VisibilityBuffer,
        clear: [f32; 4],
    ) {
        let (width, height) = target.size();
        let params = BackgroundParams {
            clear_color: clear,
            width,
            height,
            _padding: [0; 2],
        };
        gpu.write_changed(&self.params, &mut self.uploaded, params);
        self.workgroups = shaders::deferred_tiles((width, height));
        if self.bind_group.as_ref().map(|(id, _)| *id) != Some(target.id()) {
            let layout = self.pipeline.get_bind_group_layout(0);
            let bind_group = gpu.device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("deferred background"),
                layout: &layout,
                entries: &[
                    wgpu::BindGroupEntry {
                        binding: 0,
                        resource: visibility.keys.as_entire_binding(),
                    },
                    wgpu::BindGroupEntry {
                        binding: 1,
                        resource: wgpu::BindingResource::TextureView(&target.scene_view),
                    },
                    wgpu::BindGroupEntry {
                        binding: 2,
                        resource: self.params.as_entire_binding(),
                    },
                ],
            });
            self.bind_group = Some((target.id(), bind_group));
        }
    }

    /// Records the pass into the resolve's compute pass.
    pub(crate) fn record(&self, pass: &mut wgpu::ComputePass<'_>) {
        if let Some((_, bind_group)) = &self.bind_group {
            pass.set_pipeline(&self.pipeline);
            pass.set_bind_group(0, bind_group, &[]);
            pass.dispatch_workgroups(self.workgroups.0, self.workgroups.1, 1);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_background_params_match_their_wgsl() {
        let source = DEFERRED_BACKGROUND.source();
        assert_eq!(
            crate::shader::check_wgsl_layout::<BackgroundParams>(&source, "BackgroundParams"),
            Ok(())
        );
    }
}
