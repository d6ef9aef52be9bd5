//! What every full-screen pass of the post chain shares: its pipeline, compute or a full-screen
//! triangle, recorded the same way ([`FullScreenPipeline`]), and its bind groups kept by the
//! ids of the images they bind ([`BindGroupCache`]).

use super::{PassTimestamps, clearing_attachment};

/// The side of a full-screen compute pass's square workgroups, in pixels.
pub(crate) const FULL_SCREEN_GROUP: u32 = 8;

/// A full-screen pass's pipeline: a compute pass, one invocation per pixel writing its output
/// as a storage texture bound by the caller, or a full-screen triangle drawing into it.
#[derive(Debug)]
pub(crate) enum FullScreenPipeline {
    /// Compute, in [`FULL_SCREEN_GROUP`]-sided workgroups.
    Compute(wgpu::ComputePipeline),
    /// A full-screen triangle.
    Fragment(wgpu::RenderPipeline),
}

impl FullScreenPipeline {
    /// Whether it runs in compute.
    pub(crate) fn is_compute(&self) -> bool {
        matches!(self, FullScreenPipeline::Compute(_))
    }

    /// A bind group of `layout` with `entries` and, in compute, `output` as binding 2 (the
    /// storage texture the pass writes).
    pub(crate) fn bind_group<'a>(
        &self,
        device: &wgpu::Device,
        (label, layout): (&str, &wgpu::BindGroupLayout),
        mut entries: Vec<wgpu::BindGroupEntry<'a>>,
        output: &'a wgpu::TextureView,
    ) -> wgpu::BindGroup {
        if self.is_compute() {
            entries.push(wgpu::BindGroupEntry {
                binding: 2,
                resource: wgpu::BindingResource::TextureView(output),
            });
        }
        device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some(label),
            layout,
            entries: &entries,
        })
    }

    /// Records one pass over `size` pixels with `bind_group`, writing `output` (attached and
    /// cleared first for the triangle; bound in the group for compute).
    pub(crate) fn record(
        &self,
        label: &str,
        encoder: &mut wgpu::CommandEncoder,
        (bind_group, output): (&wgpu::BindGroup, &wgpu::TextureView),
        (width, height): (u32, u32),
        time: Option<&PassTimestamps>,
    ) {
        match self {
            FullScreenPipeline::Compute(pipeline) => {
                let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                    label: Some(label),
                    timestamp_writes: time.map(PassTimestamps::compute),
                });
                pass.set_pipeline(pipeline);
                pass.set_bind_group(0, bind_group, &[]);
                pass.dispatch_workgroups(
                    width.div_ceil(FULL_SCREEN_GROUP),
                    height.div_ceil(FULL_SCREEN_GROUP),
                    1,
                );
            }
            FullScreenPipeline::Fragment(pipeline) => {
                let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                    label: Some(label),
                    color_attachments: &[Some(clearing_attachment(
                        output,
                        wgpu::Color::TRANSPARENT,
                    ))],
                    depth_stencil_attachment: None,
                    timestamp_writes: time.map(PassTimestamps::render),
                    occlusion_query_set: None,
                    multiview_mask: None,
                });
                pass.set_pipeline(pipeline);
                pass.set_bind_group(0, bind_group, &[]);
                pass.draw(0..3, 0..1);
            }
        }
    }
}

/// Bind groups by what they bind (`K`: the ids of the images), the latest few: a target's
/// chain binds few images, and groups of an earlier target's are stale.
#[derive(Debug)]
pub(crate) struct BindGroupCache<K> {
    groups: Vec<(K, wgpu::BindGroup)>,
}

impl<K> Default for BindGroupCache<K> {
    fn default() -> Self {
        Self { groups: Vec::new() }
    }
}

/// How many bind groups a cache keeps.
const CACHED_GROUPS: usize = 4;

impl<K: Copy + PartialEq> BindGroupCache<K> {
    /// The group for `key`, made with `make` unless the cache has it.
    pub(crate) fn get_or_make(
        &mut self,
        key: K,
        make: impl FnOnce() -> wgpu::BindGroup,
    ) -> wgpu::BindGroup {
        if let Some((_, group)) = self.groups.iter().find(|(k, _)| *k == key) {
            return group.clone();
        }
        let group = make();
        if self.groups.len() >= CACHED_GROUPS {
            self.groups.remove(0);
        }
        self.groups.push((key, group.clone()));
        group
    }

    /// Drops the groups whose key `keep` refuses.
    pub(crate) fn retain(&mut self, keep: impl Fn(&K) -> bool) {
        self.groups.retain(|(key, _)| keep(key));
    }
}
