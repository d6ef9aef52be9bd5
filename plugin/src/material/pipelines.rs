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
    /// Whether the shader declares the core's `SCENE_SHADOWS` override (shadows.wgsl).
    declares_scene_shadows: bool,
    /// Whether this frame renders shadow maps: the shading pipelines then read them.
    scene_shadows: bool,
    pipelines: HashMap<(MeshPass, bool, M::Key), wgpu::RenderPipeline>,
}

/// The pipeline-overridable constant of shadows.wgsl that compiles the shadow-map lookups in:
/// a frame without shadow maps uses pipelines without them (code that is there costs registers
/// even where it does not run; measured in sandbox/BENCHMARKS.md, "scene shadows").
const SCENE_SHADOWS: &str = "SCENE_SHADOWS";

impl<M: Material> MaterialPipelines<M> {
    /// No pipelines yet; they will come from `shader` with `layout`, for scene targets of
    /// `color_format`, in frames with or without a depth `prepass`.
    /// `source` is the shader's WGSL (to see whether it receives scene shadows).
    pub(crate) fn new(
        shader: wgpu::ShaderModule,
        source: &str,
        layout: wgpu::PipelineLayout,
        color_format: wgpu::TextureFormat,
        prepass: bool,
    ) -> Self {
        Self {
            shader,
            layout,
            color_format,
            prepass,
            declares_scene_shadows: source.contains(&format!("override {SCENE_SHADOWS}")),
            scene_shadows: false,
            pipelines: HashMap::new(),
        }
    }

    /// Sets whether this frame renders shadow maps (which shading pipelines are used).
    pub(crate) fn set_scene_shadows(&mut self, scene_shadows: bool) {
        self.scene_shadows = scene_shadows && self.declares_scene_shadows;
    }

    /// Whether `pass` of this frame reads the shadow maps.
    fn reads_shadow_maps(&self, pass: MeshPass) -> bool {
        self.scene_shadows && !matches!(pass, MeshPass::Prepass | MeshPass::Shadow)
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
        let shadowed = self.reads_shadow_maps(pass);
        if self.pipelines.contains_key(&(pass, shadowed, key)) {
            return;
        }
        let mut fragment = match pass {
            MeshPass::Prepass => M::prepass_fragment(key),
            MeshPass::Shadow => M::shadow_fragment(key),
            MeshPass::OpaqueAfterPrepass => Some(M::fragment_after_prepass(key)),
            MeshPass::Opaque | MeshPass::Transparent => Some(M::fragment(key)),
        };
        if shadowed && let Some(fragment) = &mut fragment {
            fragment.constants.push((SCENE_SHADOWS, 1.0));
        }
        let pipeline = mesh_pipeline(
            device,
            &MeshPipelineDescriptor {
                label: &format!("{} {pass:?} pipeline {key:?} shadowed {shadowed}", M::NAME),
                layout: &self.layout,
                shader: &self.shader,
                pass,
                fragment: fragment.as_ref(),
                color_format: self.color_format,
                cull_mode: M::cull_mode(key),
            },
        );
        self.pipelines.insert((pass, shadowed, key), pipeline);
    }

    /// The pipeline of `key` in `pass`, once [`MaterialPipelines::ensure`]d.
    pub(crate) fn get(&self, pass: MeshPass, key: &M::Key) -> Option<&wgpu::RenderPipeline> {
        self.pipelines
            .get(&(pass, self.reads_shadow_maps(pass), *key))
    }

    /// Every pipeline in use rebuilt from `shader` (a recompiled shader), for hot reload:
    /// create it inside an error scope, then swap it in. At least the default material's
    /// pipelines are built, so a broken shader is caught before anything uses it.
    #[cfg(feature = "dev-tools")]
    pub(crate) fn rebuilt(&self, device: &wgpu::Device, shader: wgpu::ShaderModule) -> Self {
        let mut rebuilt = Self {
            shader,
            layout: self.layout.clone(),
            color_format: self.color_format,
            prepass: self.prepass,
            declares_scene_shadows: self.declares_scene_shadows,
            scene_shadows: self.scene_shadows,
            pipelines: HashMap::new(),
        };
        let keys: std::collections::BTreeSet<M::Key> =
            self.pipelines.keys().map(|(_, _, key)| *key).collect();
        for key in keys.into_iter().chain([M::default().key()]) {
            rebuilt.ensure(device, key);
        }
        rebuilt
    }
}
