//! A material's render pipelines, one per [`Material::Key`] and pass, compiled on first use.

use std::collections::HashMap;

use super::Material;
use crate::render::layout::{MeshPass, MeshPipelineDescriptor, mesh_pipeline};

/// The compiled shader of material `M` and every pipeline made from it so far.
pub(crate) struct MaterialPipelines<M: Material> {
    shader: wgpu::ShaderModule,
    layout: wgpu::PipelineLayout,
    color_format: wgpu::TextureFormat,
    /// Whether the frame has a depth prepass (the opaque pipelines' depth state follows).
    prepass: bool,
    pipelines: HashMap<(MeshPass, M::Key), wgpu::RenderPipeline>,
}

impl<M: Material> MaterialPipelines<M> {
    /// No pipelines yet; they will come from `shader` with `layout`, for scene targets of
    /// `color_format`, in frames with or without a depth `prepass`.
    pub(crate) fn new(
        shader: wgpu::ShaderModule,
        layout: wgpu::PipelineLayout,
        color_format: wgpu::TextureFormat,
        prepass: bool,
    ) -> Self {
        Self {
            shader,
            layout,
            color_format,
            prepass,
            pipelines: HashMap::new(),
        }
    }

    /// The passes a draw of this material takes part in.
    pub(crate) fn passes(&self) -> &'static [MeshPass] {
        if self.prepass {
            &[MeshPass::Prepass, MeshPass::OpaqueAfterPrepass]
        } else {
            &[MeshPass::Opaque]
        }
    }

    /// Compiles the pipelines of `key` unless they exist (a first use costs a pipeline
    /// compile per pass, a few milliseconds, once).
    pub(crate) fn ensure(&mut self, device: &wgpu::Device, key: M::Key) {
        for &pass in self.passes() {
            if self.pipelines.contains_key(&(pass, key)) {
                continue;
            }
            let fragment = match pass {
                MeshPass::Prepass => M::prepass_fragment(key),
                MeshPass::OpaqueAfterPrepass => Some(M::fragment_after_prepass(key)),
                MeshPass::Opaque => Some(M::fragment(key)),
            };
            let pipeline = mesh_pipeline(
                device,
                &MeshPipelineDescriptor {
                    label: &format!("{} {pass:?} pipeline {key:?}", M::NAME),
                    layout: &self.layout,
                    shader: &self.shader,
                    pass,
                    fragment: fragment.as_ref(),
                    color_format: self.color_format,
                    cull_mode: M::cull_mode(key),
                },
            );
            self.pipelines.insert((pass, key), pipeline);
        }
    }

    /// The pipeline of `key` in `pass`, once [`MaterialPipelines::ensure`]d.
    pub(crate) fn get(&self, pass: MeshPass, key: &M::Key) -> Option<&wgpu::RenderPipeline> {
        self.pipelines.get(&(pass, *key))
    }

    /// Every pipeline in use rebuilt from `shader` (a recompiled shader), for hot reload:
    /// create it inside an error scope, then swap it in. At least the default material's
    /// pipelines are built, so a broken shader is caught before anything uses it.
    #[cfg(feature = "dev-tools")]
    pub(crate) fn rebuilt(&self, device: &wgpu::Device, shader: wgpu::ShaderModule) -> Self {
        let mut rebuilt = Self::new(shader, self.layout.clone(), self.color_format, self.prepass);
        let keys: std::collections::BTreeSet<M::Key> =
            self.pipelines.keys().map(|(_, key)| *key).collect();
        for key in keys.into_iter().chain([M::default().key()]) {
            rebuilt.ensure(device, key);
        }
        rebuilt
    }
}
