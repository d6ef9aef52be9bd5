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

/// Bind groups kept, by target: the split view writes two targets of one size in turn.
const KEPT_GROUPS: usize = 2;

/// The image, its pipeline, and the bind groups of the targets it was last written for.
#[derive(Debug)]
pub(crate) struct SettledDepthImage {
    pipeline: wgpu::ComputePipeline,
    view: wgpu::TextureView,
    size: (u32, u32),
    /// Bind groups over the keys and a target's depth, with that target's id, newest last.
    groups: Vec<(u64, wgpu::BindGroup)>,
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
    /// An image of `target`'s size, written by `pipeline`.
    pub(crate) fn new(
        gpu: &GpuContext,
        target: &RenderTarget,
        pipeline: wgpu::ComputePipeline,
    ) -> Self {
        let view = crate::render::plain_texture(
            gpu,
            "settled depth",
            target.size(),
            SETTLED_DEPTH_FORMAT,
            wgpu::TextureUsages::STORAGE_BINDING | wgpu::TextureUsages::TEXTURE_BINDING,
        )
        .create_view(&wgpu::TextureViewDescriptor::default());
        Self {
            pipeline,
            view,
            size: target.size(),
            groups: Vec::new(),
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

    /// Makes the bind group over `keys` and `target`'s depth the one recorded, made unless
    /// kept.
    pub(crate) fn bind(&mut self, gpu: &GpuContext, keys: &wgpu::Buffer, target: &RenderTarget) {
        if let Some(kept) = self.groups.iter().position(|(id, _)| *id == target.id()) {
            let group = self.groups.remove(kept);
            self.groups.push(group);
            return;
        }
        let group = gpu.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("settled depth"),
            layout: &self.pipeline.get_bind_group_layout(0),
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: keys.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: wgpu::BindingResource::TextureView(&target.depth_view),
                },
                wgpu::BindGroupEntry {
                    binding: 2,
                    resource: wgpu::BindingResource::TextureView(&self.view),
                },
            ],
        });
        if self.groups.len() == KEPT_GROUPS {
            self.groups.remove(0);
        }
        self.groups.push((target.id(), group));
    }

    /// Records the pass into `pass` (after every resolve dispatch: the keys are settled).
    pub(crate) fn record(&self, pass: &mut wgpu::ComputePass<'_>) {
        let Some((_, group)) = self.groups.last() else {
            return;
        };
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, group, &[]);
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
