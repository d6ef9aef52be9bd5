//! A material's render pipelines, one per [`Material::Key`], compiled on first use.

use std::collections::HashMap;

use super::Material;
use crate::render::layout::mesh_pipeline;

/// The compiled shader of material `M` and every pipeline made from it so far.
pub(crate) struct MaterialPipelines<M: Material> {
    shader: wgpu::ShaderModule,
    layout: wgpu::PipelineLayout,
    color_format: wgpu::TextureFormat,
    pipelines: HashMap<M::Key, wgpu::RenderPipeline>,
}

impl<M: Material> MaterialPipelines<M> {
    /// No pipelines yet; they will come from `shader` with `layout`, for targets of
    /// `color_format`.
    pub(crate) fn new(
        shader: wgpu::ShaderModule,
        layout: wgpu::PipelineLayout,
        color_format: wgpu::TextureFormat,
    ) -> Self {
        Self {
            shader,
            layout,
            color_format,
            pipelines: HashMap::new(),
        }
    }

    /// Compiles the pipeline for `key` unless it exists (a first use costs one pipeline
    /// compile, a few milliseconds, once).
    pub(crate) fn ensure(&mut self, device: &wgpu::Device, key: M::Key) {
        if !self.pipelines.contains_key(&key) {
            let pipeline = mesh_pipeline(
                device,
                &format!("{} pipeline {key:?}", M::NAME),
                &self.layout,
                &self.shader,
                &M::fragment(key),
                self.color_format,
            );
            self.pipelines.insert(key, pipeline);
        }
    }

    /// The pipeline for `key`, once [`MaterialPipelines::ensure`]d.
    pub(crate) fn get(&self, key: &M::Key) -> Option<&wgpu::RenderPipeline> {
        self.pipelines.get(key)
    }

    /// Every pipeline in use rebuilt from `shader` (a recompiled shader), for hot reload:
    /// create it inside an error scope, then swap it in. At least the default material's
    /// pipeline is built, so a broken shader is caught before anything uses it.
    #[cfg(feature = "dev-tools")]
    pub(crate) fn rebuilt(&self, device: &wgpu::Device, shader: wgpu::ShaderModule) -> Self {
        let mut rebuilt = Self::new(shader, self.layout.clone(), self.color_format);
        for key in self.pipelines.keys().copied().chain([M::default().key()]) {
            rebuilt.ensure(device, key);
        }
        rebuilt
    }
}
