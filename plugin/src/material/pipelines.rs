//! A material's render pipelines, one per [`Material::Key`] and pass, compiled on first use.

use std::collections::HashMap;

use super::Material;
use crate::render::DrawPhase;
use crate::render::layout::{MeshPass, MeshPipelineDescriptor, mesh_pipeline};

/// The compiled shader of material `M` and every pipeline made from it so far.
pub(crate) struct MaterialPipelines<M: Material> {
    shader: wgpu::ShaderModule,
    layout: wgpu::PipelineLayout,
    /// The deferred resolve's layout (groups 0 and 1 as `layout`, then the resolve's group
    /// 2), where the module holds `M`'s deferred shader.
    resolve_layout: Option<wgpu::PipelineLayout>,
    color_format: wgpu::TextureFormat,
    /// Whether the frame has a depth prepass (the opaque pipelines' depth state follows).
    prepass: bool,
    /// Whether the shader declares the core's `SCENE_SHADOWS` override (shadows.wgsl).
    declares_scene_shadows: bool,
    /// Whether this frame renders shadow maps: the shading pipelines then read them.
    scene_shadows: bool,
    /// Whether this frame runs the deferred path.
    deferred: bool,
    pipelines: HashMap<(MeshPass, bool, M::Key), wgpu::RenderPipeline>,
    resolve_pipelines: HashMap<(bool, M::Key), wgpu::ComputePipeline>,
}

/// The pipeline-overridable constant of shadows.wgsl that compiles the shadow-map lookups in:
/// a frame without shadow maps uses pipelines without them (code that is there costs registers
/// even where it does not run; measured in sandbox/BENCHMARKS.md, "scene shadows").
const SCENE_SHADOWS: &str = "SCENE_SHADOWS";

/// How a material's pipelines are made: its module and layouts, the scene format and whether
/// frames have a depth prepass.
pub(crate) struct PipelineSetup {
    pub(crate) shader: wgpu::ShaderModule,
    /// Whether the shader is composed with the core's scene shadows (shaders::SHADOWS, which
    /// declares the `SCENE_SHADOWS` override).
    pub(crate) receives_scene_shadows: bool,
    pub(crate) layout: wgpu::PipelineLayout,
    /// Present where the module is `M`'s deferred shader.
    pub(crate) resolve_layout: Option<wgpu::PipelineLayout>,
    pub(crate) color_format: wgpu::TextureFormat,
    pub(crate) prepass: bool,
}

impl<M: Material> MaterialPipelines<M> {
    /// No pipelines yet; they will come from `setup`.
    pub(crate) fn new(setup: PipelineSetup) -> Self {
        Self {
            declares_scene_shadows: setup.receives_scene_shadows,
            shader: setup.shader,
            layout: setup.layout,
            resolve_layout: setup.resolve_layout,
            color_format: setup.color_format,
            prepass: setup.prepass,
            scene_shadows: false,
            deferred: false,
            pipelines: HashMap::new(),
            resolve_pipelines: HashMap::new(),
        }
    }

    /// Sets whether this frame renders shadow maps (which shading pipelines are used) and
    /// whether it runs the deferred path (which the renderer only chooses where every material
    /// has its deferred shader).
    pub(crate) fn set_frame(&mut self, scene_shadows: bool, deferred: bool) {
        self.scene_shadows = scene_shadows && self.declares_scene_shadows;
        self.deferred = deferred && self.resolve_layout.is_some();
    }

    /// Whether `key`'s pixels are shaded by the deferred resolve this frame.
    pub(crate) fn resolves_in_compute(&self, key: M::Key) -> bool {
        self.deferred && !M::blends(key) && M::deferred_resolve(key).is_some()
    }

    /// Whether `pass` of this frame reads the shadow maps.
    fn reads_shadow_maps(&self, pass: MeshPass) -> bool {
        self.scene_shadows
            && !matches!(
                pass,
                MeshPass::Prepass | MeshPass::Visibility | MeshPass::Shadow
            )
    }

    /// The passes a draw of `key` takes part in: the transparent one for a blending key,
    /// else the prepass (the visibility pass on deferred frames; when frames have one) and the
    /// opaque one (unless the deferred resolve shades it).
    pub(crate) fn passes(&self, key: M::Key) -> &'static [MeshPass] {
        if M::blends(key) {
            &[MeshPass::Transparent]
        } else if self.resolves_in_compute(key) {
            &[MeshPass::Visibility]
        } else if self.deferred {
            &[MeshPass::Visibility, MeshPass::OpaqueAfterPrepass]
        } else if self.prepass {
            &[MeshPass::Prepass, MeshPass::OpaqueAfterPrepass]
        } else {
            &[MeshPass::Opaque]
        }
    }

    /// The pass a draw of `key` takes in `phase`, if it draws there at all.
    pub(crate) fn pass_in(&self, phase: DrawPhase, key: M::Key) -> Option<MeshPass> {
        let wanted = match phase {
            DrawPhase::Prepass if self.deferred => MeshPass::Visibility,
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
        if self.resolves_in_compute(key) {
            self.ensure_resolve(device, key);
        }
    }

    fn ensure_resolve(&mut self, device: &wgpu::Device, key: M::Key) {
        let shadowed = self.scene_shadows;
        let (Some(layout), Some(mut entry)) = (&self.resolve_layout, M::deferred_resolve(key))
        else {
            return;
        };
        if self.resolve_pipelines.contains_key(&(shadowed, key)) {
            return;
        }
        if shadowed {
            entry.constants.push((SCENE_SHADOWS, 1.0));
        }
        let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some(&format!(
                "{} deferred resolve {key:?} shadowed {shadowed}",
                M::NAME
            )),
            layout: Some(layout),
            module: &self.shader,
            entry_point: Some(entry.entry_point),
            compilation_options: wgpu::PipelineCompilationOptions {
                constants: &entry.constants,
                ..Default::default()
            },
            cache: None,
        });
        self.resolve_pipelines.insert((shadowed, key), pipeline);
    }

    /// The deferred resolve's pipeline of `key`, once [`MaterialPipelines::ensure`]d.
    pub(crate) fn resolve(&self, key: &M::Key) -> Option<&wgpu::ComputePipeline> {
        self.resolve_pipelines.get(&(self.scene_shadows, *key))
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
            MeshPass::Visibility => Some(M::visibility_fragment(key)),
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
            resolve_layout: self.resolve_layout.clone(),
            color_format: self.color_format,
            prepass: self.prepass,
            declares_scene_shadows: self.declares_scene_shadows,
            scene_shadows: self.scene_shadows,
            deferred: self.deferred,
            pipelines: HashMap::new(),
            resolve_pipelines: HashMap::new(),
        };
        let keys: std::collections::BTreeSet<M::Key> =
            self.pipelines.keys().map(|(_, _, key)| *key).collect();
        for key in keys.into_iter().chain([M::default().key()]) {
            rebuilt.ensure(device, key);
        }
        rebuilt
    }
}
