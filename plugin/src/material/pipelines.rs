//! A material's render pipelines, one per [`Material::Key`] and pass, compiled on first use:
//! in that frame, or on a worker thread while the variant's draws use a fallback
//! ([`crate::gpu::PipelineCompilation`]).

use std::collections::{HashMap, HashSet};
use std::sync::Arc;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::mpsc::{Receiver, Sender, channel};

use super::Material;
use super::mesh_pipeline::{MeshPass, MeshPipelineDescriptor, mesh_pipeline};
use crate::gpu::ShaderEntry;
use crate::render::DrawPhase;

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
    /// Which of the core's overrides the shader declares.
    declares: FrameVariant,
    /// What this frame's shading pipelines compile in.
    variant: FrameVariant,
    /// Whether this frame runs the deferred path.
    deferred: bool,
    pipelines: HashMap<(MeshPass, FrameVariant, M::Key), wgpu::RenderPipeline>,
    resolve_pipelines: HashMap<(FrameVariant, M::Key), wgpu::ComputePipeline>,
    /// Compiles on worker threads, where the app asked for them.
    background: Option<Background<M>>,
}

/// A pipeline compiled on a worker thread.
enum Compiled<M: Material> {
    Mesh((MeshPass, FrameVariant, M::Key), wgpu::RenderPipeline),
    Resolve((FrameVariant, M::Key), wgpu::ComputePipeline),
}

/// What a worker thread is compiling.
#[derive(Clone, Copy, PartialEq, Eq, Hash)]
enum Pending<K> {
    Mesh(MeshPass, FrameVariant, K),
    Resolve(FrameVariant, K),
}

/// One compile handed to a worker thread: where its pipeline goes, and the count it is in.
struct Job<M: Material> {
    sender: Sender<Compiled<M>>,
    in_flight: Arc<AtomicUsize>,
}

impl<M: Material> Job<M> {
    /// Runs `compile` on a worker thread and sends its pipeline back.
    fn run(
        self,
        device: wgpu::Device,
        compile: impl FnOnce(&wgpu::Device) -> Compiled<M> + Send + 'static,
    ) {
        let Self { sender, in_flight } = self;
        let counter = Arc::clone(&in_flight);
        let spawned = std::thread::Builder::new()
            .name(format!("{} pipeline", M::NAME))
            .spawn(move || {
                let _ = sender.send(compile(&device));
                counter.fetch_sub(1, Ordering::AcqRel);
            });
        if let Err(error) = spawned {
            // The thread never ran: nothing will arrive, so the count goes back.
            log::warn!("cannot start a pipeline compile thread: {error}");
            in_flight.fetch_sub(1, Ordering::AcqRel);
        }
    }
}

/// The worker threads' side of a material's pipelines.
struct Background<M: Material> {
    sender: Sender<Compiled<M>>,
    receiver: Receiver<Compiled<M>>,
    pending: HashSet<Pending<M::Key>>,
    /// The app's count of compiles in flight ([`crate::gpu::wait_for_pipelines`]).
    in_flight: Arc<AtomicUsize>,
    /// The variant that stands in for any variant not ready (compiled at start).
    stand_in: M::Key,
    /// Whether a frame was prepared: the variants of the first frame compile in it (an app's
    /// loading frame, and again after a lost device), later ones in the background.
    loaded: bool,
}

/// The pipeline-overridable constant of shadows.wgsl that compiles the shadow-map lookups in.
const SCENE_SHADOWS: &str = "SCENE_SHADOWS";
/// The pipeline-overridable constant of environment.wgsl that compiles the environment in.
const ENVIRONMENT: &str = "ENVIRONMENT";

/// The core's pipeline-overridable constants a shading pipeline compiles in: a frame without
/// shadow maps, or without an environment, uses pipelines without their code (code that is
/// there costs registers even where it does not run; sandbox/BENCHMARKS.md, "Street corner:
/// scene shadows").
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub(crate) struct FrameVariant {
    /// `SCENE_SHADOWS`: the frame renders shadow maps.
    pub(crate) scene_shadows: bool,
    /// `ENVIRONMENT`: an environment lights the frame.
    pub(crate) environment: bool,
}

impl FrameVariant {
    /// Every variant, for compiling the stand-in ahead.
    const ALL: [FrameVariant; 4] = [
        FrameVariant {
            scene_shadows: false,
            environment: false,
        },
        FrameVariant {
            scene_shadows: true,
            environment: false,
        },
        FrameVariant {
            scene_shadows: false,
            environment: true,
        },
        FrameVariant {
            scene_shadows: true,
            environment: true,
        },
    ];

    /// The overrides this variant sets.
    fn constants(self) -> impl Iterator<Item = (&'static str, f64)> {
        [
            (SCENE_SHADOWS, self.scene_shadows),
            (ENVIRONMENT, self.environment),
        ]
        .into_iter()
        .filter(|(_, on)| *on)
        .map(|(name, _)| (name, 1.0))
    }

    /// What of `self` a shader declaring `declared` can compile in.
    fn within(self, declared: FrameVariant) -> Self {
        Self {
            scene_shadows: self.scene_shadows && declared.scene_shadows,
            environment: self.environment && declared.environment,
        }
    }
}

/// How a material's pipelines are made: its module and layouts, the scene format and whether
/// frames have a depth prepass.
pub(crate) struct PipelineSetup {
    pub(crate) shader: wgpu::ShaderModule,
    /// Which of the core's overrides the shader declares (composed with shadows.wgsl, with
    /// environment.wgsl).
    pub(crate) declares: FrameVariant,
    pub(crate) layout: wgpu::PipelineLayout,
    /// Present where the module is `M`'s deferred shader.
    pub(crate) resolve_layout: Option<wgpu::PipelineLayout>,
    pub(crate) color_format: wgpu::TextureFormat,
    pub(crate) prepass: bool,
    /// The app's count of background compiles, where pipelines compile in the background.
    pub(crate) background: Option<Arc<AtomicUsize>>,
}

impl<M: Material> MaterialPipelines<M> {
    /// No pipelines yet; they will come from `setup`.
    pub(crate) fn new(setup: PipelineSetup) -> Self {
        Self {
            declares: setup.declares,
            shader: setup.shader,
            layout: setup.layout,
            resolve_layout: setup.resolve_layout,
            color_format: setup.color_format,
            prepass: setup.prepass,
            variant: FrameVariant::default(),
            deferred: false,
            pipelines: HashMap::new(),
            resolve_pipelines: HashMap::new(),
            background: setup.background.map(|in_flight| {
                let (sender, receiver) = channel();
                let stand_in = M::default().key();
                Background {
                    sender,
                    receiver,
                    pending: HashSet::new(),
                    in_flight,
                    stand_in: M::fallback_key(stand_in).unwrap_or(stand_in),
                    loaded: false,
                }
            }),
        }
    }

    /// Compiles, blocking, the stand-in variant's pipelines for every pass and shadow-map
    /// state a frame may ask of it, where pipelines compile in the background.
    pub(crate) fn compile_stand_in(&mut self, device: &wgpu::Device) {
        let Some(stand_in) = self.background.as_ref().map(|b| b.stand_in) else {
            return;
        };
        let (variant, deferred) = (self.variant, self.deferred);
        for frame_variant in FrameVariant::ALL {
            for deferred_frame in [false, true] {
                self.set_frame(frame_variant, deferred_frame);
                for &pass in self.passes(stand_in) {
                    self.compile_pass(device, pass, stand_in, false);
                }
                self.compile_pass(device, MeshPass::Shadow, stand_in, false);
                if self.resolves_in_compute(stand_in) {
                    self.compile_resolve(device, stand_in, false);
                }
            }
        }
        self.variant = variant;
        self.deferred = deferred;
    }

    /// Takes in the pipelines the worker threads have finished (at the start of a frame's
    /// preparation: a frame draws with what was ready when it began).
    pub(crate) fn take_compiled(&mut self) {
        let Some(background) = &mut self.background else {
            return;
        };
        while let Ok(compiled) = background.receiver.try_recv() {
            match compiled {
                Compiled::Mesh(id, pipeline) => {
                    background.pending.remove(&Pending::Mesh(id.0, id.1, id.2));
                    self.pipelines.insert(id, pipeline);
                }
                Compiled::Resolve(id, pipeline) => {
                    background.pending.remove(&Pending::Resolve(id.0, id.1));
                    self.resolve_pipelines.insert(id, pipeline);
                }
            }
        }
    }

    /// Marks a frame prepared: variants first used from now on compile in the background.
    pub(crate) fn frame_prepared(&mut self) {
        if let Some(background) = &mut self.background {
            background.loaded = true;
        }
    }

    /// Whether every pipeline `key` needs this frame is compiled (not standing in).
    pub(crate) fn ready(&self, key: M::Key) -> bool {
        self.passes(key).iter().all(|&pass| {
            self.pipelines
                .contains_key(&(pass, self.variant_of(pass), key))
        }) && (!self.resolves_in_compute(key)
            || self.resolve_pipelines.contains_key(&(self.variant, key)))
    }

    /// The pipeline `lookup` finds for `key`, else (while `key` compiles in the background)
    /// for its fallback, else for the stand-in: one lookup when `key`'s is there, as it is in
    /// every settled frame.
    fn drawn_as<'a, P>(
        &self,
        key: M::Key,
        lookup: impl Fn(M::Key) -> Option<&'a P>,
    ) -> Option<&'a P> {
        lookup(key).or_else(|| {
            let background = self.background.as_ref()?;
            M::fallback_key(key)
                .and_then(&lookup)
                .or_else(|| lookup(background.stand_in))
        })
    }

    /// Sets what this frame's shading pipelines compile in (shadow maps, environment) and
    /// whether it runs the deferred path (which the renderer only chooses where every material
    /// has its deferred shader).
    pub(crate) fn set_frame(&mut self, variant: FrameVariant, deferred: bool) {
        self.variant = variant.within(self.declares);
        self.deferred = deferred && self.resolve_layout.is_some();
    }

    /// Whether `key`'s pixels are shaded by the deferred resolve this frame.
    pub(crate) fn resolves_in_compute(&self, key: M::Key) -> bool {
        self.deferred && !M::blends(key) && M::deferred_resolve(key).is_some()
    }

    /// What `pass` of this frame compiles in: nothing for the passes that do not shade.
    fn variant_of(&self, pass: MeshPass) -> FrameVariant {
        match pass {
            MeshPass::Prepass | MeshPass::Visibility | MeshPass::Shadow | MeshPass::Motion => {
                FrameVariant::default()
            }
            _ => self.variant,
        }
    }

    /// The passes a draw of `key` takes part in: the transparent one for a blending key,
    /// else the prepass (the visibility pass on deferred frames; when frames have one) and the
    /// opaque one (unless the deferred resolve shades it).
    pub(crate) fn passes(&self, key: M::Key) -> &'static [MeshPass] {
        if M::blends(key) {
            &[MeshPass::Transparent]
        } else if self.resolves_in_compute(key) && M::settles_depth_in_resolve(key) {
            &[MeshPass::Candidate, MeshPass::SettledDepth]
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

    /// Compiles the object motion pipeline of `key` unless it exists (TAA frames in which a
    /// draw of `key` moved; blended keys take no part).
    pub(crate) fn ensure_motion(&mut self, device: &wgpu::Device, key: M::Key) {
        if !M::blends(key) {
            let background = self.background.as_ref().is_some_and(|b| b.loaded);
            self.compile_pass(device, MeshPass::Motion, key, background);
        }
    }

    /// The pass a draw of `key` takes in `phase`, if it draws there at all.
    pub(crate) fn pass_in(&self, phase: DrawPhase, key: M::Key) -> Option<MeshPass> {
        let wanted = match phase {
            DrawPhase::Motion => return (!M::blends(key)).then_some(MeshPass::Motion),
            DrawPhase::Prepass if self.deferred => MeshPass::Visibility,
            DrawPhase::Prepass => MeshPass::Prepass,
            DrawPhase::Candidates => MeshPass::Candidate,
            DrawPhase::SettledDepth => MeshPass::SettledDepth,
            DrawPhase::Transparent => MeshPass::Transparent,
            _ if self.prepass => MeshPass::OpaqueAfterPrepass,
            _ => MeshPass::Opaque,
        };
        self.passes(key).contains(&wanted).then_some(wanted)
    }

    /// Compiles the pipelines of `key` unless they exist (a first use costs a pipeline
    /// compile per pass, a few milliseconds, once).
    pub(crate) fn ensure(&mut self, device: &wgpu::Device, key: M::Key) {
        let background = self.background.as_ref().is_some_and(|b| b.loaded);
        for &pass in self.passes(key) {
            self.compile_pass(device, pass, key, background);
        }
        if self.resolves_in_compute(key) {
            self.compile_resolve(device, key, background);
        }
    }

    /// Compiles `key`'s deferred resolve unless it exists or is compiling, on a worker thread
    /// where `background`.
    fn compile_resolve(&mut self, device: &wgpu::Device, key: M::Key, background: bool) {
        let variant = self.variant;
        let (Some(layout), Some(mut entry)) = (&self.resolve_layout, M::deferred_resolve(key))
        else {
            return;
        };
        if self.resolve_pipelines.contains_key(&(variant, key))
            || self.is_pending(Pending::Resolve(variant, key))
        {
            return;
        }
        entry.constants.extend(variant.constants());
        let label = format!("{} deferred resolve {key:?} {variant:?}", M::NAME);
        let (layout, shader) = (layout.clone(), self.shader.clone());
        let compile = move |device: &wgpu::Device| {
            device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                label: Some(&label),
                layout: Some(&layout),
                module: &shader,
                entry_point: Some(entry.entry_point),
                compilation_options: wgpu::PipelineCompilationOptions {
                    constants: &entry.constants,
                    ..Default::default()
                },
                cache: None,
            })
        };
        match self.background_job(background, Pending::Resolve(variant, key)) {
            Some(job) => job.run(device.clone(), move |device| {
                Compiled::Resolve((variant, key), compile(device))
            }),
            None => {
                let pipeline = compile(device);
                self.resolve_pipelines.insert((variant, key), pipeline);
            }
        }
    }

    /// Whether a worker thread is compiling `pending`.
    fn is_pending(&self, pending: Pending<M::Key>) -> bool {
        self.background
            .as_ref()
            .is_some_and(|background| background.pending.contains(&pending))
    }

    /// Where `background`, marks `pending` as compiling and returns the job that compiles it
    /// on a worker thread; `None`: compile here.
    fn background_job(&mut self, background: bool, pending: Pending<M::Key>) -> Option<Job<M>> {
        let worker = self.background.as_mut().filter(|_| background)?;
        worker.pending.insert(pending);
        worker.in_flight.fetch_add(1, Ordering::AcqRel);
        Some(Job {
            sender: worker.sender.clone(),
            in_flight: Arc::clone(&worker.in_flight),
        })
    }

    /// The deferred resolve's pipeline of `key` (or of what stands in for it), once
    /// [`MaterialPipelines::ensure`]d.
    pub(crate) fn resolve(&self, key: &M::Key) -> Option<&wgpu::ComputePipeline> {
        let variant = self.variant;
        self.drawn_as(*key, |key| self.resolve_pipelines.get(&(variant, key)))
    }

    /// Compiles `key`'s shadow-map pipeline unless it exists (only frames with shadow maps
    /// need it).
    pub(crate) fn ensure_shadow(&mut self, device: &wgpu::Device, key: M::Key) {
        let background = self.background.as_ref().is_some_and(|b| b.loaded);
        self.compile_pass(device, MeshPass::Shadow, key, background);
    }

    /// Compiles `key`'s pipeline of `pass` unless it exists or is compiling, on a worker
    /// thread where `background`.
    fn compile_pass(
        &mut self,
        device: &wgpu::Device,
        pass: MeshPass,
        key: M::Key,
        background: bool,
    ) {
        let variant = self.variant_of(pass);
        if self.pipelines.contains_key(&(pass, variant, key))
            || self.is_pending(Pending::Mesh(pass, variant, key))
        {
            return;
        }
        let mut fragment = match pass {
            MeshPass::Prepass => M::prepass_fragment(key),
            MeshPass::Visibility => Some(M::visibility_fragment(key)),
            MeshPass::Candidate => Some(ShaderEntry::entry(super::mesh_pipeline::CANDIDATE_ENTRY)),
            MeshPass::SettledDepth => Some(ShaderEntry::entry(
                super::mesh_pipeline::SETTLED_DEPTH_ENTRY,
            )),
            MeshPass::Shadow => M::shadow_fragment(key),
            MeshPass::OpaqueAfterPrepass => Some(M::fragment_after_prepass(key)),
            MeshPass::Opaque | MeshPass::Transparent => Some(M::fragment(key)),
            MeshPass::Motion => Some(ShaderEntry::entry("fs_motion")),
        };
        if let Some(fragment) = &mut fragment {
            fragment.constants.extend(variant.constants());
        }
        let label = format!("{} {pass:?} pipeline {key:?} {variant:?}", M::NAME);
        let (layout, shader, color_format) =
            (self.layout.clone(), self.shader.clone(), self.color_format);
        let compile = move |device: &wgpu::Device| {
            mesh_pipeline(
                device,
                &MeshPipelineDescriptor {
                    label: &label,
                    layout: &layout,
                    shader: &shader,
                    pass,
                    fragment: fragment.as_ref(),
                    color_format,
                    cull_mode: M::cull_mode(key),
                },
            )
        };
        match self.background_job(background, Pending::Mesh(pass, variant, key)) {
            Some(job) => job.run(device.clone(), move |device| {
                Compiled::Mesh((pass, variant, key), compile(device))
            }),
            None => {
                let pipeline = compile(device);
                self.pipelines.insert((pass, variant, key), pipeline);
            }
        }
    }

    /// The pipeline of `key` in `pass` (or of what stands in for it while it compiles), once
    /// [`MaterialPipelines::ensure`]d.
    pub(crate) fn get(&self, pass: MeshPass, key: &M::Key) -> Option<&wgpu::RenderPipeline> {
        let variant = self.variant_of(pass);
        self.drawn_as(*key, |key| self.pipelines.get(&(pass, variant, key)))
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
            declares: self.declares,
            variant: self.variant,
            deferred: self.deferred,
            pipelines: HashMap::new(),
            resolve_pipelines: HashMap::new(),
            // A rebuild compiles here, inside the caller's error scope.
            background: None,
        };
        let keys: std::collections::BTreeSet<M::Key> =
            self.pipelines.keys().map(|(_, _, key)| *key).collect();
        for key in keys.into_iter().chain([M::default().key()]) {
            rebuilt.ensure(device, key);
        }
        rebuilt
    }
}
