//! The environment drawn behind the scene (background.wgsl): a compute pass after the resolve
//! phase that writes the source's radiance wherever the scene's depth is still the cleared far
//! plane, on both paths. It reads the source itself (the sky analytically, an image at full
//! resolution) rather than the prefiltered cube, so the background is as sharp as its source.

use glam::{Mat4, Vec3};

use super::prefilter::{ENVIRONMENT_SOURCE, EnvironmentGpu, SKY};
use crate::gpu::{GpuContext, PassTimestamps};
use crate::render::RenderTarget;
use crate::render::shaders::{self, ComposedShader, WgslFile};

/// The background pass's entry point.
pub const BACKGROUND_ENTRY: WgslFile =
    crate::wgsl_file!(nested "render/environment/background.wgsl");

/// The background pass's shader.
pub const BACKGROUND: ComposedShader = ComposedShader {
    name: "background.wgsl",
    constants: &[],
    files: &[SKY, ENVIRONMENT_SOURCE, BACKGROUND_ENTRY],
};

/// Mirrors `BackgroundParams` in background.wgsl.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub(crate) struct BackgroundParams {
    environment_from_clip: [[f32; 4]; 4],
    scale: [f32; 4],
    size: [u32; 4],
}

crate::wgsl_layout!(BackgroundParams {
    environment_from_clip,
    scale,
    size
});

/// What the background needs of the frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct BackgroundView {
    /// The camera's view-projection (jittered under TAA, as the scene's).
    pub view_projection: Mat4,
    /// The environment's turn about +Y, radians.
    pub rotation: f32,
    /// What the source's radiance is multiplied with.
    pub scale: f32,
}

/// The background pipeline, its parameters and its bind groups for the current target.
pub(crate) struct Background {
    pipeline: wgpu::ComputePipeline,
    params: wgpu::Buffer,
    /// The target and the scene depth they bind, and the two groups.
    groups: Option<(u64, wgpu::TextureView, wgpu::BindGroup, wgpu::BindGroup)>,
    workgroups: (u32, u32),
    /// What `params` holds (written only when the frame's differ).
    uploaded: Option<BackgroundParams>,
}

impl Background {
    /// The pipeline for a scene target of `scene_format`.
    pub(crate) fn new(gpu: &GpuContext, scene_format: wgpu::TextureFormat) -> Self {
        let target = shaders::ShaderTarget::of_device(&gpu.device, scene_format);
        let module =
            shaders::create_module(&gpu.device, BACKGROUND.name, BACKGROUND.source_for(&target));
        let pipeline = gpu
            .device
            .create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                label: Some("environment background"),
                layout: None,
                module: &module,
                entry_point: Some("cs_background"),
                compilation_options: Default::default(),
                cache: None,
            });
        let params = gpu.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("environment background parameters"),
            size: std::mem::size_of::<BackgroundParams>() as u64,
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        Self {
            pipeline,
            params,
            groups: None,
            workgroups: (0, 0),
            uploaded: None,
        }
    }

    /// Writes this frame's parameters and binds `target`, its depth as `scene_depth` and the
    /// source (`new_source`: the source's image changed since the groups were made); returns
    /// the bytes written.
    pub(crate) fn prepare(
        &mut self,
        gpu: &GpuContext,
        (target, scene_depth): (&RenderTarget, &wgpu::TextureView),
        environment: &EnvironmentGpu,
        (view, new_source): (BackgroundView, bool),
    ) -> u64 {
        let (width, height) = target.size();
        let turn = Mat4::from_axis_angle(Vec3::Y, -view.rotation);
        let params = BackgroundParams {
            environment_from_clip: (turn * view.view_projection.inverse()).to_cols_array_2d(),
            scale: [view.scale, 0.0, 0.0, 0.0],
            size: [width, height, 0, 0],
        };
        let written = gpu.write_changed(&self.params, &mut self.uploaded, params);
        self.workgroups = (width.div_ceil(8), height.div_ceil(8));
        let bound = self
            .groups
            .as_ref()
            .is_some_and(|(id, depth, ..)| *id == target.id() && depth == scene_depth);
        if new_source || !bound {
            let layout = self.pipeline.get_bind_group_layout(0);
            let frame = gpu.device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("environment background"),
                layout: &layout,
                entries: &[
                    wgpu::BindGroupEntry {
                        binding: 0,
                        resource: self.params.as_entire_binding(),
                    },
                    wgpu::BindGroupEntry {
                        binding: 1,
                        resource: wgpu::BindingResource::TextureView(scene_depth),
                    },
                    wgpu::BindGroupEntry {
                        binding: 2,
                        resource: wgpu::BindingResource::TextureView(&target.scene_view),
                    },
                ],
            });
            let source = environment.source_group(&self.pipeline.get_bind_group_layout(1));
            self.groups = Some((target.id(), scene_depth.clone(), frame, source));
        }
        written
    }

    /// Records the pass, timed by `time`.
    pub(crate) fn record(&self, encoder: &mut wgpu::CommandEncoder, time: Option<&PassTimestamps>) {
        let Some((_, _, frame, source)) = &self.groups else {
            return;
        };
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("environment background"),
            timestamp_writes: time.map(PassTimestamps::compute),
        });
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, frame, &[]);
        pass.set_bind_group(1, source, &[]);
        pass.dispatch_workgroups(self.workgroups.0, self.workgroups.1, 1);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_background_params_match_their_wgsl() {
        assert_eq!(
            crate::shader::check_wgsl_layout::<BackgroundParams>(
                &BACKGROUND.source(),
                "BackgroundParams"
            ),
            Ok(())
        );
    }
}
