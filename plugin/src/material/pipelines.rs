//! A material's render pipelines, one per [`Material::Key`] and pass, compiled on first use.

use std::collections::HashMap;

use super::Material;
use crate::render::DrawPhase;
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

    /// The passes a draw of `key` takes part in: the transparent one for a blending key,
    /// else the prepass (when frames have one) and the opaque one.
    pub(crate) fn passes(&self, key: M::Key) -> &'static [MeshPass] {
        if M::blends(key) {
            &[MeshPass::Transparent]
        } else if self.prepass {
            &[MeshPass::Prepass, MeshPass::OpaqueAfterPrepass]
        } else {
            &[MeshPass::Opaque]
        }
    }

    /// The pass a draw of `key` takes in `phase`, if it draws there at all.
    pub(crate) fn pass_in(&self, phase: DrawPhase, key: M::Key) -> Option<MeshPass> {
        let wanted = match phase {
            DrawPhase::Prepass => MeshPass::Prepass,
            DrawPhase::Transparent => MeshPass::Transparent,
            _ if self.prepass => MeshPass::OpaqueAfterPrepass,
            _ => MeshPass::Opaque,
        };
        self.passes(key).contains(&wanted).then_some(wanted)
    }

    /// Compiles the pipelines of `key` unless they exist (a first use costs a pipeline
    /// compile per pass, a few milliseconds, once).
    pub(crate) fn ensure(&mut self, device: &wgpu::Device, key: M::Key) {
        for &pass in self.passes(key) {
            self.ensure_pass(device, pass, key);
        }
    }

    /// Compiles `key`'s shadow-map pipeline unless it exists (only frames with shadow maps
    /// need it).
    pub(crate) fn ensure_shadow(&mut self, device: &wgpu::Device, key: M::Key) {
        self.ensure_pass(device, MeshPass::Shadow, key);
    }

    fn ensure_pass(&mut self, device: &wgpu::Device, pass: MeshPass, key: M::Key) {
        if self.pipelines.contains_key(&(pass, key)) {
            return;
        }
        let fragment = match pass {
            MeshPass::Prepass => M::prepass_fragment(key),
            MeshPass::Shadow => M::shadow_fragment(key),
            MeshPass::OpaqueAfterPrepass => Some(M::fragment_after_prepass(key)),
            MeshPass::Opaque | MeshPass::Transparent => Some(M::fragment(key)),
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
