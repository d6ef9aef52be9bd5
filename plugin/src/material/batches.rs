//! One material's draws of a frame on the GPU: per-draw transforms and uniforms in two storage
//! buffers written by changed ranges, texture bind groups, pipelines, and the draws sorted and
//! merged into instanced batches (consecutive opaque draws of one pipeline, texture set and mesh
//! are one `draw_indexed` over an instance range; blended draws are batches of one, which the
//! frame's transparent phase orders among every material's). Recording them into passes is
//! [`super::draw`]'s.

use std::ops::Range;

use glam::Mat4;

mod draw_entries;
mod in_place;

use super::Material;
use super::deferred::{DeferredResolve, ResolveTargets};
use super::draw_order::{SortEntry, SortMemory};
use super::extract::ExtractedMaterials;
use super::followed_models::FollowedModels;
use super::frame_bindings::{DrawBuffers, FrameBindGroups};
use super::pipelines::{FrameVariant, MaterialPipelines, PipelineSetup};
use super::{MeshLodCache, PixelFootprint};
use crate::gpu::{BoundTextures, TextureBindGroups};
use crate::gpu::{GpuAssets, GpuContext, UploadStats};
use crate::gpu::{ObjectBuffer, ScatterQueue};
use crate::render::PhaseBindings;
use crate::render::anti_aliasing::ObjectMotions;
use crate::render::shaders::ComposedShader;
use crate::render::{FrameUniformBuffer, MeshTransform, VisibilityIds};
use crate::{AssetId, Assets, Image, Mesh};

/// One entity's draw as the Extract stage copied it, but for its material (kept apart, in
/// [`ExtractedMaterials::materials`]: an unchanged draw is told by these fields, and a frame of
/// draws that hold a shared material then reads no copy of it).
#[derive(Clone, Debug)]
pub(crate) struct ExtractedDraw<M> {
    pub(crate) model: Mat4,
    /// The entity drawn: TAA follows its motion from frame to frame.
    pub(crate) entity: hecs::Entity,
    pub(crate) mesh: AssetId<Mesh>,
    /// The shared material the entity holds a handle to, and the version of it copied; `None`
    /// for a material of the entity's own.
    pub(crate) shared: Option<(AssetId<M>, u64)>,
    /// Drawn into shadow maps (no [`crate::NotShadowCaster`]).
    pub(crate) casts_shadows: bool,
    /// Scene shadows fall on it (no [`crate::NotShadowReceiver`]).
    pub(crate) receives_shadows: bool,
    /// A shadow caster whose material reads the frame's noise
    /// ([`Material::casts_with_frame_noise`]).
    pub(crate) casts_with_frame_noise: bool,
}

/// Draws sharing pipeline, textures and mesh, adjacent in the per-draw buffers.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Batch<K> {
    pub(crate) key: K,
    pub(crate) casts_shadows: bool,
    pub(crate) textures: BoundTextures,
    pub(crate) mesh: AssetId<Mesh>,
    pub(crate) instances: Range<u32>,
    /// On deferred frames, the visibility ids of its triangles, instance after instance,
    /// starting at the first instance's first triangle (starting at 0: none; 0 is no draw's id).
    pub(crate) visibility_ids: Range<u32>,
    /// The mesh's triangles: each instance owns that many ids.
    pub(crate) triangles: u32,
    /// The view depth of its nearest instance's nearest point (bounding sphere): where it
    /// stands in the frame's nearest-first prepass.
    pub(crate) nearest_depth: f32,
    /// On TAA frames, whether an instance moved since the last frame (it then draws in the
    /// object motion pass).
    pub(crate) moving: bool,
}

/// What preparing one material's draws reads besides its own state.
pub(crate) struct PrepareInputs<'a> {
    pub(crate) gpu: &'a GpuContext,
    pub(crate) frame: &'a FrameUniformBuffer,
    pub(crate) depth: &'a PhaseBindings<'a>,
    pub(crate) meshes: &'a Assets<Mesh>,
    pub(crate) images: &'a Assets<Image>,
    pub(crate) footprint: Option<&'a PixelFootprint>,
    /// The eye and the direction it looks, for drawing nearest first.
    pub(crate) eye: (glam::Vec3, glam::Vec3),
    /// What the frame's shading pipelines compile in: shadow maps (casters then need their
    /// shadow pipelines too), the environment.
    pub(crate) variant: FrameVariant,
    /// The targets of the deferred resolve, on frames that run the deferred path.
    pub(crate) deferred: Option<ResolveTargets<'a>>,
}

/// What the frame numbers across every material's draws, handed to each as it prepares.
pub(crate) struct FrameNumbers<'a> {
    /// The deferred path's visibility ids.
    pub(crate) ids: &'a mut VisibilityIds,
    /// On TAA frames, the motions of the draws that moved.
    pub(crate) motions: Option<&'a mut ObjectMotions>,
}

/// The shader a material compiles: its deferred shader where it has one and the adapter can
/// run the visibility pass, else its forward one.
#[derive(Clone, Copy, Debug)]
pub(crate) struct MaterialShader {
    pub(crate) composed: ComposedShader,
    /// Whether `composed` is the deferred shader.
    pub(crate) deferred: bool,
}

/// How a material's shader and pipelines are compiled beyond the frame's needs.
pub(crate) struct CompileOptions {
    /// The fragment invocation counter the shader counts into (tests and measurements).
    pub(crate) counter: Option<wgpu::Buffer>,
    /// The app's count of background compiles, where pipelines compile in the background.
    pub(crate) background: Option<std::sync::Arc<std::sync::atomic::AtomicUsize>>,
}

/// Material `M`'s GPU state. A resource.
pub(crate) struct MaterialBatches<M: Material> {
    pub(crate) pipelines: MaterialPipelines<M>,
    transforms: ObjectBuffer<MeshTransform>,
    uniforms: ObjectBuffer<M::PerDraw>,
    pub(super) frame_groups: FrameBindGroups,
    pub(super) textures: TextureBindGroups,
    /// The deferred resolve's inputs, where the material compiled its deferred shader.
    pub(super) resolve: Option<DeferredResolve>,
    pub(crate) batches: Vec<Batch<M::Key>>,
    /// The blended batches of the last prepared frame: (centre's view depth, batch index).
    pub(super) blended: Vec<(f32, u32)>,
    order: Vec<SortEntry<M::Key>>,
    sort_memory: SortMemory<M::Key>,
    // The transform of each sorted slot, kept from frame to frame.
    pub(super) transform_data: Vec<MeshTransform>,
    /// The batches (increasing indices) whose visibility the polygon pass may find this frame.
    pub(super) polygon_batches: Vec<u32>,
    // On TAA frames, each followed entity's model last frame.
    followed: FollowedModels,
    // Uniforms in draw order, then in sorted order: both reused from frame to frame.
    uniform_data: Vec<M::PerDraw>,
    sorted_uniforms: Vec<M::PerDraw>,
    /// Each draw's slot in the sorted order (the inverse of `order`'s draw indices).
    slot_of_draw: Vec<u32>,
    /// What the last prepared frame saw: where it equals this frame's, only the draws that
    /// changed are prepared again (in_place.rs).
    prepared_view: Option<PreparedView>,
    /// On a frame prepared in place, the slots (increasing) whose data may have changed.
    dirty_slots: Vec<usize>,
    /// On a frame prepared in place, the slots whose uniform may have changed (a new material,
    /// or swapped with an unequal one): a draw that only moved keeps its uniform, which is then
    /// not compared.
    uniform_slots: Vec<usize>,
    /// On a frame prepared in place, the rewritten slots whose nearest depth grew (or is not
    /// a number), with the depth they had: their batch's nearest depth may have to rise.
    receded_slots: Vec<(usize, f32)>,
    /// The assets' upload serial when the uniforms were last made: an upload since may have
    /// changed the texture facts they hold.
    uniforms_serial: Option<u64>,
    /// Whether the last frame was prepared in place.
    pub(crate) prepared_in_place: bool,
    /// Whether a shadow caster's draw changed on the last frame.
    casters_data_changed: bool,
}

/// What every draw's key, order and motion depend on besides the draw itself.
#[derive(Clone, Copy, Debug, PartialEq)]
struct PreparedView {
    eye: (glam::Vec3, glam::Vec3),
    footprint: Option<PixelFootprint>,
    variant: FrameVariant,
    deferred: bool,
    /// Whether motions were numbered (a TAA frame).
    motions: bool,
}

impl<M: Material> MaterialBatches<M> {
    /// Compiles `shader` (`M`'s, or its deferred one where `deferred`)
    /// for scene targets of `color_format`, in frames with or without a depth `prepass`;
    /// pipelines follow on first use. With a `counter` the shader counts its fragment
    /// invocations into it.
    pub(crate) fn new(
        gpu: &GpuContext,
        frame: &FrameUniformBuffer,
        MaterialShader {
            composed: shader,
            deferred,
        }: MaterialShader,
        color_format: wgpu::TextureFormat,
        prepass: bool,
        depth: &PhaseBindings<'_>,
        CompileOptions {
            counter,
            background,
        }: CompileOptions,
    ) -> Self {
        let device = &gpu.device;
        let module = shader_module(device, &shader, color_format, counter.is_some());
        let transforms = ObjectBuffer::new(gpu, "mesh transforms", 16);
        let uniforms = ObjectBuffer::new(gpu, M::NAME, 16);
        let frame_groups = FrameBindGroups::new(
            gpu,
            M::NAME,
            ObjectBuffer::<M::PerDraw>::layout_entry(crate::render::frame_group::MATERIAL_UNIFORMS),
            (deferred, counter),
            &DrawBuffers {
                frame,
                transforms: transforms.buffer(),
                uniforms: uniforms.buffer(),
            },
            depth,
        );
        let textures =
            TextureBindGroups::new(gpu, M::NAME, M::TEXTURE_SLOTS, M::DERIVED_TEXTURE_SLOTS);
        let layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some(&format!("{} pipeline layout", M::NAME)),
            bind_group_layouts: &[Some(frame_groups.layout()), Some(textures.layout())],
            immediate_size: 0,
        });
        let resolve = deferred.then(|| DeferredResolve::new(gpu, M::NAME, color_format));
        let resolve_layout = resolve.as_ref().map(|resolve| {
            let groups = [frame_groups.layout(), textures.layout(), resolve.layout()];
            resolve_pipeline_layout::<M>(device, groups)
        });
        Self {
            pipelines: MaterialPipelines::new(PipelineSetup {
                shader: module,
                declares: declared_variant(&shader),
                layout,
                resolve_layout,
                color_format,
                prepass,
                background,
            }),
            resolve,
            frame_groups,
            transforms,
            uniforms,
            textures,
            batches: Vec::new(),
            blended: Vec::new(),
            order: Vec::new(),
            sort_memory: SortMemory::default(),
            transform_data: Vec::new(),
            polygon_batches: Vec::new(),
            followed: FollowedModels::default(),
            uniform_data: Vec::new(),
            sorted_uniforms: Vec::new(),
            slot_of_draw: Vec::new(),
            prepared_view: None,
            dirty_slots: Vec::new(),
            uniform_slots: Vec::new(),
            receded_slots: Vec::new(),
            uniforms_serial: None,
            prepared_in_place: false,
            casters_data_changed: false,
        }
    }

    /// Uploads the meshes and textures the draws use, computes each draw's key and uniform from
    /// the textures as bound, sorts and batches the draws, writes the per-draw data that
    /// changed, and prepares bind groups and pipelines. Counts what it uploaded in `stats`.
    /// Where the view and the draws' entities are last frame's and what changed keeps its place
    /// in the order, only the changed draws are prepared again (in_place.rs).
    pub(crate) fn prepare(
        &mut self,
        inputs: &PrepareInputs<'_>,
        extracted: &ExtractedMaterials<M>,
        assets: &mut GpuAssets,
        lod_cache: &mut MeshLodCache,
        stats: &mut UploadStats,
        FrameNumbers { ids, mut motions }: FrameNumbers<'_>,
    ) {
        let draws = &extracted.draws;
        let view = PreparedView {
            eye: inputs.eye,
            footprint: inputs.footprint.copied(),
            variant: inputs.variant,
            deferred: inputs.deferred.is_some(),
            motions: motions.is_some(),
        };
        // Past a quarter of the draws changed, preparing all of them again costs less.
        let in_place = self.prepared_view == Some(view)
            && extracted.same_entities
            && extracted.changed.len() * 4 <= draws.len()
            && self.slot_of_draw.len() == draws.len()
            && self.update_in_place(inputs, extracted, assets, lod_cache, stats, &mut motions);
        if !in_place {
            self.gather(inputs, extracted, assets, lod_cache, stats);
            SortEntry::sort(&mut self.order, &mut self.sort_memory);
            self.slot_of_draw.resize(self.order.len(), 0);
            for (slot, entry) in self.order.iter().enumerate() {
                self.slot_of_draw[entry.draw] = slot as u32;
            }
            self.update_transforms(draws);
            self.update_motions(draws, motions);
            self.sorted_uniforms.clear();
            self.sorted_uniforms
                .extend(self.order.iter().map(|entry| self.uniform_data[entry.draw]));
            self.merge_batches();
        }
        self.prepared_view = Some(view);
        self.prepared_in_place = in_place;
        self.casters_data_changed = !extracted.same_entities
            || extracted
                .changed
                .iter()
                .any(|&index| draws[index].casts_shadows);
        self.assign_visibility_ids(inputs.deferred.is_some().then_some(ids), assets, in_place);
        self.upload_draw_data(inputs, (stats, assets.scatters()), in_place);
        self.textures.prepare(
            inputs.gpu,
            assets,
            self.batches.iter().map(|batch| batch.textures),
        );
        self.ensure_pipelines(inputs);
        self.prepare_resolve(inputs, assets);
    }

    /// Writes the transform of each sorted slot, recomputing a transform (and its inverse) only
    /// where the slot's model changed.
    fn update_transforms(&mut self, draws: &[ExtractedDraw<M>]) {
        self.transform_data.truncate(self.order.len());
        for (slot, entry) in self.order.iter().enumerate() {
            let draw = &draws[entry.draw];
            let kept = self.transform_data.get(slot);
            if kept.is_some_and(|kept| kept.places(draw.model, draw.receives_shadows)) {
                continue;
            }
            let transform = MeshTransform::new(draw.model, draw.receives_shadows);
            if slot < self.transform_data.len() {
                self.transform_data[slot] = transform;
            } else {
                self.transform_data.push(transform);
            }
        }
    }

    /// On TAA frames (with `motions`), numbers each slot's motion since the last frame there
    /// (0: still, or not drawn last frame); other frames forget the models, so the next TAA
    /// frame starts still.
    fn update_motions(&mut self, draws: &[ExtractedDraw<M>], motions: Option<&mut ObjectMotions>) {
        let Some(motions) = motions else {
            // Only the frame after a TAA frame has numbers to take back.
            if self.followed.forget() {
                for transform in &mut self.transform_data {
                    transform.motion = 0;
                }
            }
            return;
        };
        let numbers = self
            .followed
            .number_motions(draws.iter().map(|draw| (draw.entity, draw.model)), motions);
        for (slot, entry) in self.order.iter().enumerate() {
            self.transform_data[slot].motion = numbers[entry.draw];
        }
    }

    /// Merges the sorted draws into batches (runs of opaque draws sharing key, shadow role,
    /// textures and mesh) and lists the blended ones.
    fn merge_batches(&mut self) {
        self.batches.clear();
        self.blended.clear();
        for (index, entry) in self.order.iter().enumerate() {
            let instance = index as u32;
            if entry.blends {
                self.blended
                    .push((entry.centre_depth, self.batches.len() as u32));
            }
            match self.batches.last_mut() {
                // A blended draw is a batch of its own: the transparent phase may draw another
                // material's between two of them.
                Some(batch)
                    if !entry.blends
                        && batch.key == entry.key
                        && batch.casts_shadows == entry.casts_shadows
                        && batch.textures == entry.textures
                        && batch.mesh == entry.mesh =>
                {
                    batch.instances.end = instance + 1;
                    batch.nearest_depth = batch.nearest_depth.min(entry.nearest_depth);
                    batch.moving |= self.transform_data[index].motion != 0;
                }
                _ => self.batches.push(Batch {
                    key: entry.key,
                    casts_shadows: entry.casts_shadows,
                    textures: entry.textures,
                    mesh: entry.mesh,
                    instances: instance..instance + 1,
                    visibility_ids: 0..0,
                    triangles: 0,
                    nearest_depth: entry.nearest_depth,
                    moving: self.transform_data[index].motion != 0,
                }),
            }
        }
    }

    /// Gives each batch its run of visibility `ids` (on deferred frames; else none) and each
    /// instance the id of its first triangle. `in_place`: the batches are last frame's, whose
    /// instances hold their ids already where a batch's run is the same.
    fn assign_visibility_ids(
        &mut self,
        ids: Option<&mut VisibilityIds>,
        assets: &GpuAssets,
        in_place: bool,
    ) {
        let Some(ids) = ids else {
            if !in_place {
                for transform in &mut self.transform_data {
                    transform.first_visibility_id = 0;
                }
            }
            return;
        };
        for batch in &mut self.batches {
            batch.triangles = assets
                .mesh(batch.mesh)
                .map_or(0, |mesh| mesh.index_count / 3);
            let count =
                u64::from(batch.instances.end - batch.instances.start) * u64::from(batch.triangles);
            // `allocate` keeps the end within u32.
            let run = ids
                .allocate(count)
                .map_or(0..0, |first| first..first + count as u32);
            if in_place && run == batch.visibility_ids {
                continue;
            }
            batch.visibility_ids = run;
            let first_id = batch.visibility_ids.start;
            for (k, slot) in batch.instances.clone().enumerate() {
                self.transform_data[slot as usize].first_visibility_id = if first_id == 0 {
                    0
                } else {
                    first_id + k as u32 * batch.triangles
                };
                if in_place {
                    self.dirty_slots.push(slot as usize);
                }
            }
        }
    }

    /// Writes the changed ranges of the per-draw transforms and uniforms (`in_place`: among the
    /// dirty slots only), and remakes the frame bind groups where a buffer grew (or the depth
    /// bindings changed).
    fn upload_draw_data(
        &mut self,
        inputs: &PrepareInputs<'_>,
        (stats, scatters): (&mut UploadStats, &mut ScatterQueue),
        in_place: bool,
    ) {
        let gpu = inputs.gpu;
        let candidates = in_place.then(|| {
            for slots in [&mut self.dirty_slots, &mut self.uniform_slots] {
                slots.sort_unstable();
                slots.dedup();
            }
            (&self.dirty_slots, &self.uniform_slots)
        });
        let in_place_bytes = candidates.and_then(|(slots, uniform_slots)| {
            Some(
                self.transforms
                    .upload_candidates(gpu, (&self.transform_data, slots), scatters)?
                    + self.uniforms.upload_candidates(
                        gpu,
                        (&self.sorted_uniforms, uniform_slots),
                        scatters,
                    )?,
            )
        });
        let (bytes, grew) = match in_place_bytes {
            Some(bytes) => (bytes, false),
            None => {
                let (transform_bytes, transforms_grew) =
                    self.transforms.upload(gpu, &self.transform_data);
                let (uniform_bytes, uniforms_grew) =
                    self.uniforms.upload(gpu, &self.sorted_uniforms);
                (
                    transform_bytes + uniform_bytes,
                    transforms_grew || uniforms_grew,
                )
            }
        };
        stats.uniform_bytes += bytes;
        self.frame_groups.refresh(
            gpu,
            &DrawBuffers {
                frame: inputs.frame,
                transforms: self.transforms.buffer(),
                uniforms: self.uniforms.buffer(),
            },
            inputs.depth,
            grew,
        );
    }

    /// Whether a shadow caster's draw changed on the last frame (where entities came or went,
    /// whether any did): the batches that draw casters are followed apart
    /// ([`MaterialBatches::shadow_casters_signature`]).
    pub(crate) fn casters_data_changed(&self) -> bool {
        self.casters_data_changed
    }

    /// Builds the pipelines the batches use this frame where missing (shadow pipelines too for
    /// opaque casters on frames with shadow maps).
    fn ensure_pipelines(&mut self, inputs: &PrepareInputs<'_>) {
        self.pipelines.take_compiled();
        self.pipelines
            .set_frame(inputs.variant, inputs.deferred.is_some());
        for batch in &self.batches {
            self.pipelines.ensure(&inputs.gpu.device, batch.key);
            if inputs.variant.scene_shadows && batch.casts_shadows && !M::blends(batch.key) {
                self.pipelines.ensure_shadow(&inputs.gpu.device, batch.key);
            }
            if batch.moving {
                self.pipelines.ensure_motion(&inputs.gpu.device, batch.key);
            }
        }
        if !self.batches.is_empty() {
            self.pipelines.frame_prepared();
        }
    }

    /// Plans the deferred resolve's dispatches on deferred frames; none on forward ones.
    fn prepare_resolve(&mut self, inputs: &PrepareInputs<'_>, assets: &GpuAssets) {
        if let Some(resolve) = &mut self.resolve {
            let pipelines = &self.pipelines;
            match &inputs.deferred {
                Some(targets) => resolve.prepare(
                    inputs.gpu,
                    targets,
                    &self.batches,
                    |batch| pipelines.resolves_in_compute(batch.key),
                    assets,
                ),
                None => resolve.skip(),
            }
        }
    }
}

/// `shader`'s module for scene targets of `color_format`, counting its fragment invocations
/// where `counts`.
fn shader_module(
    device: &wgpu::Device,
    shader: &ComposedShader,
    color_format: wgpu::TextureFormat,
    counts: bool,
) -> wgpu::ShaderModule {
    let target = crate::render::shaders::ShaderTarget::of_device(device, color_format);
    let source = if counts {
        shader.counting_source(&target)
    } else {
        shader.source_for(&target)
    };
    crate::render::shaders::create_module(device, shader.name, source)
}

/// The pipeline layout of material `M`'s deferred resolve: the frame's, the textures' and the
/// resolve's own bind groups.
fn resolve_pipeline_layout<M: Material>(
    device: &wgpu::Device,
    [frame, textures, resolve]: [&wgpu::BindGroupLayout; 3],
) -> wgpu::PipelineLayout {
    device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
        label: Some(&format!("{} deferred resolve layout", M::NAME)),
        bind_group_layouts: &[Some(frame), Some(textures), Some(resolve)],
        immediate_size: 0,
    })
}

/// What `shader` compiles in of the frame's optional bindings.
fn declared_variant(shader: &ComposedShader) -> FrameVariant {
    FrameVariant {
        scene_shadows: shader.files.contains(&crate::render::shaders::SHADOWS),
        environment: shader
            .files
            .contains(&crate::render::environment::ENVIRONMENT),
    }
}
