//! The point lights and their clusters in every material's group 0 (bindings 14 and 15, read
//! by frame.wgsl's `light_at` and lights/lights.wgsl's `lights_near`), which the lights
//! feature fills each frame; each is rewritten only where it changed.

use super::extract::NO_LIGHT_CLUSTERS;
use super::gpu_types::PointLightGpu;
use crate::gpu::{GpuContext, ObjectBuffer};

/// The point lights and light clusters group 0 binds. Part of the renderer.
#[derive(Debug)]
pub struct LightBuffers {
    point_lights: ObjectBuffer<PointLightGpu>,
    clusters: ObjectBuffer<u32>,
    /// Changes whenever a buffer is replaced.
    generation: u64,
}

impl LightBuffers {
    /// No point light, one empty cluster.
    pub fn new(gpu: &GpuContext) -> Self {
        let mut clusters = ObjectBuffer::new(gpu, "light clusters", NO_LIGHT_CLUSTERS.len() as u64);
        clusters.upload(gpu, &NO_LIGHT_CLUSTERS);
        Self {
            point_lights: ObjectBuffer::new(gpu, "point lights", 1),
            clusters,
            generation: 0,
        }
    }

    /// Uploads the frame's point lights and clusters; returns the bytes written.
    pub fn prepare(
        &mut self,
        gpu: &GpuContext,
        point_lights: &[PointLightGpu],
        clusters: &[u32],
    ) -> u64 {
        let (light_bytes, lights_grew) = self.point_lights.upload(gpu, point_lights);
        let (cluster_bytes, clusters_grew) = self.clusters.upload(gpu, clusters);
        if lights_grew || clusters_grew {
            self.generation += 1;
        }
        light_bytes + cluster_bytes
    }

    /// The point lights' buffer (binding 14), for a pass that binds it alone.
    pub fn point_lights(&self) -> &wgpu::Buffer {
        self.point_lights.buffer()
    }

    /// Changes whenever a buffer is replaced.
    pub fn generation(&self) -> u64 {
        self.generation
    }

    /// The layout entries of bindings 14 and 15 of group 0.
    pub fn layout_entries() -> [wgpu::BindGroupLayoutEntry; 2] {
        let [lights, clusters] = BINDINGS;
        [
            ObjectBuffer::<PointLightGpu>::layout_entry(lights),
            ObjectBuffer::<u32>::layout_entry(clusters),
        ]
    }

    /// The bind group entries of bindings 14 and 15.
    pub fn entries(&self) -> [wgpu::BindGroupEntry<'_>; 2] {
        let [lights, clusters] = BINDINGS;
        [
            wgpu::BindGroupEntry {
                binding: lights,
                resource: self.point_lights.buffer().as_entire_binding(),
            },
            wgpu::BindGroupEntry {
                binding: clusters,
                resource: self.clusters.buffer().as_entire_binding(),
            },
        ]
    }
}

/// The bindings of the point lights and the light clusters.
const BINDINGS: [u32; 2] = [
    super::frame_group::POINT_LIGHTS,
    super::frame_group::LIGHT_CLUSTERS,
];
