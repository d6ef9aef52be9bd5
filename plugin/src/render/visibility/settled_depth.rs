//! The settled depth as an image (settled_depth.wgsl): where a deferred frame's resolve settled
//! depth-offset candidates and only compute passes read the scene's depth after it, they read
//! this image, written by one compute pass, rather than the depth attachment redrawn by the
//! candidates' polygons with `frag_depth`.

use crate::gpu::GpuContext;
use crate::render::RenderTarget;
use crate::render::shaders::{ComposedShader, WgslFile};

/// The pass's shader: the keys read as in every deferred compute pass, then its entry.
pub const SETTLED_DEPTH_SHADER: ComposedShader = ComposedShader {
    name: "settled_depth.wgsl",
    constants: &[],
    files: &[crate::render::shaders::VISIBILITY_READ, SETTLED_DEPTH_ENTRY],
};

/// The pass's WGSL file.
const SETTLED_DEPTH_ENTRY: WgslFile =
    crate::wgsl_file!(nested "render/visibility/settled_depth.wgsl");

/// The image's format: the depth attachment's value, exactly.
const SETTLED_DEPTH_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::R32Float;

/// Pixels along each side of the pass's workgroup (`@workgroup_size` in WGSL).
const GROUP_SIDE: u32 = 8;

/// How the passes after a deferred resolve read a frame's depth where depth-offset candidates
/// were settled ([`crate::Material::settles_depth_in_resolve`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum SettledDepth {
    /// The frame settled no candidate, or no pass after the resolve reads its depth.
    #[default]
    Unsettled,
    /// The candidates' polygons drew the settled depth into the depth attachment, for passes
    /// that test against it (blended draws, the object motion pass).
    DepthPass,
    /// Only compute passes read the depth: one compute pass wrote it into an image.
    Image,
}

/// The image, its pipeline, and its bind group over the keys.
#[derive(Debug)]
pub(crate) struct SettledDepthImage {
    pipeline: wgpu::ComputePipeline,
    view: wgpu::TextureView,
    size: (u32, u32),
    /// Over the keys and the image (every target of this size shares both: the split view).
    group: wgpu::BindGroup,
}

/// The pass's pipeline (compiled once per device: a resize makes a new image and keeps it).
pub(crate) fn settled_depth_pipeline(gpu: &GpuContext) -> wgpu::ComputePipeline {
    let module = SETTLED_DEPTH_SHADER.create_module(&gpu.device);
    gpu.device
        .create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some("settled depth"),
            layout: None,
            module: &module,
            entry_point: Some("cs_settle_depth"),
            compilation_options: Default::default(),
            cache: None,
        })
}

impl SettledDepthImage {
    /// An image of `target`'s size, written by `pipeline` from `keys`.
    pub(crate) fn new(
        gpu: &GpuContext,
        target: &RenderTarget,
        pipeline: wgpu::ComputePipeline,
        keys: &wgpu::Buffer,
    ) -> Self {
        let view = crate::render::plain_texture(
            gpu,
            "settled depth",
            target.size(),
            SETTLED_DEPTH_FORMAT,
            wgpu::TextureUsages::STORAGE_BINDING | wgpu::TextureUsages::TEXTURE_BINDING,
        )
        .create_view(&wgpu::TextureViewDescriptor::default());
        let group = gpu.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("settled depth"),
            layout: &pipeline.get_bind_group_layout(0),
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: keys.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: wgpu::BindingResource::TextureView(&view),
                },
            ],
        });
        Self {
            pipeline,
            view,
            size: target.size(),
            group,
        }
    }

    /// Whether it serves `target` (same size).
    pub(crate) fn fits(&self, target: &RenderTarget) -> bool {
        self.size == target.size()
    }

    /// The image, for the passes that read the scene's depth.
    pub(crate) fn view(&self) -> &wgpu::TextureView {
        &self.view
    }

    /// Records the pass into `pass` (after every resolve dispatch: the keys are settled).
    pub(crate) fn record(&self, pass: &mut wgpu::ComputePass<'_>) {
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, &self.group, &[]);
        let (width, height) = self.size;
        pass.dispatch_workgroups(width.div_ceil(GROUP_SIDE), height.div_ceil(GROUP_SIDE), 1);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_dispatch_covers_the_shaders_workgroup() {
        let declaration = format!("@workgroup_size({GROUP_SIDE}, {GROUP_SIDE})");
        assert!(SETTLED_DEPTH_SHADER.source().contains(&declaration));
    }
}
