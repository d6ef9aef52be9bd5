//! One material's draws of a frame on the GPU: per-draw transforms and uniforms in two storage
//! buffers written by changed ranges, texture bind groups, pipelines, and the draws sorted and
//! merged into instanced batches (consecutive opaque draws of one pipeline, texture set and mesh
//! are one `draw_indexed` over an instance range; blended draws are batches of one, which the
//! frame's transparent phase orders among every material's).

use std::ops::Range;

use glam::Mat4;

use super::deferred::{DeferredResolve, ResolveTargets};
use super::frame_bindings::{DepthBindings, DrawBuffers, FrameBindGroups};
use super::pipelines::{MaterialPipelines, PipelineSetup};
use super::{MAX_MATERIAL_TEXTURES, Material, TextureFacts};
use crate::render::MAX_DERIVED_TEXTURES;
use crate::render::layout::MeshPass;
use crate::render::object_buffer::ObjectBuffer;
use crate::render::shaders::ComposedShader;
use crate::render::texture_bind_groups::{BoundTextures, TextureBindGroups};
use crate::render::{
    DrawPhase, DrawView, FrameUniformBuffer, GpuAssets, GpuContext, MeshLodCache, MeshTransform,
    PixelFootprint, UploadStats, VisibilityIds,
};
use crate::{AssetId, Assets, Image, Mesh};

/// One entity's draw as the Extract stage copied it.
#[derive(Clone, Debug)]
pub(crate) struct ExtractedDraw<M> {
    pub(crate) mesh: AssetId<Mesh>,
    pub(crate) model: Mat4,
    pub(crate) material: M,
    /// Drawn into shadow maps (no [`crate::NotShadowCaster`]).
    pub(crate) casts_shadows: bool,
    /// Scene shadows fall on it (no [`crate::NotShadowReceiver`]).
    pub(crate) receives_shadows: bool,
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
}

#[derive(Clone, Copy)]
struct SortEntry<K> {
    key: K,
    casts_shadows: bool,
    textures: BoundTextures,
    mesh: AssetId<Mesh>,
    /// Distance from the eye to the object's origin along the view, as ordered bits: the
    /// instances of one batch are drawn nearest first.
    view_depth: u32,
    /// Whether the draw blends: blended draws come after the opaque ones, farthest first, each a
    /// batch of its own (the frame's transparent phase orders them across materials).
    blends: bool,
    /// For a blended draw, `!` the ordered bits of its centre's view depth (farthest first);
    /// 0 for an opaque one.
    far_first: u32,
    /// For a blended draw, its centre's view depth (behind the eye: 0).
    centre_depth: f32,
    draw: usize,
}

/// `depth` as bits that order like the number (depths behind the eye count as 0).
fn depth_order_bits(depth: f32) -> u32 {
    if depth > 0.0 { depth.to_bits() } else { 0 }
}

/// One `draw_indexed` of a run of instances with one pipeline, texture set and mesh.
struct DrawCall<K> {
    pass: MeshPass,
    key: K,
    textures: BoundTextures,
    mesh: AssetId<Mesh>,
    instances: Range<u32>,
}

impl<K: Copy> DrawCall<K> {
    fn of(batch: &Batch<K>, pass: MeshPass) -> Self {
        Self {
            pass,
            key: batch.key,
            textures: batch.textures,
            mesh: batch.mesh,
            instances: batch.instances.clone(),
        }
    }
}

/// What preparing one material's draws reads besides its own state.
pub(crate) struct PrepareInputs<'a> {
    pub(crate) gpu: &'a GpuContext,
    pub(crate) frame: &'a FrameUniformBuffer,
    pub(crate) depth: &'a DepthBindings<'a>,
    pub(crate) meshes: &'a Assets<Mesh>,
    pub(crate) images: &'a Assets<Image>,
    pub(crate) footprint: Option<&'a PixelFootprint>,
    /// The eye and the direction it looks, for drawing nearest first.
    pub(crate) eye: (glam::Vec3, glam::Vec3),
    /// Whether the frame renders shadow maps (casters then need their shadow pipelines).
    pub(crate) shadow_maps: bool,
    /// The targets of the deferred resolve, on frames that run the deferred path.
    pub(crate) deferred: Option<ResolveTargets<'a>>,
}

/// The shader a material compiles: its deferred shader where it has one and the adapter can
/// run the visibility pass, else its forward one.
#[derive(Clone, Copy, Debug)]
pub(crate) struct MaterialShader {
    pub(crate) composed: ComposedShader,
    /// Whether `composed` is the deferred shader.
    pub(crate) deferred: bool,
}

/// Material `M`'s GPU state. A resource.
pub(crate) struct MaterialBatches<M: Material> {
    pub(crate) pipelines: MaterialPipelines<M>,
    transforms: ObjectBuffer<MeshTransform>,
    uniforms: ObjectBuffer<M::Uniform>,
    frame_groups: FrameBindGroups,
    textures: TextureBindGroups,
    /// The deferred resolve's inputs, where the material compiled its deferred shader.
    resolve: Option<DeferredResolve>,
    pub(crate) batches: Vec<Batch<M::Key>>,
    /// The blended batches of the last prepared frame: (centre's view depth, batch index).
    blended: Vec<(f32, u32)>,
    order: Vec<SortEntry<M::Key>>,
    // The model matrix (and whether it receives shadows) and transform of each sorted slot,
    // kept from frame to frame.
    models: Vec<(Mat4, bool)>,
    transform_data: Vec<MeshTransform>,
    // Uniforms in draw order, then in sorted order: both reused from frame to frame.
    uniform_data: Vec<M::Uniform>,
    sorted_uniforms: Vec<M::Uniform>,
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
        depth: &DepthBindings<'_>,
        counter: Option<wgpu::Buffer>,
    ) -> Self {
        let device = &gpu.device;
        let source = match counter {
            Some(_) => shader.counting_source(),
            None => shader.source(),
        };
        let source = crate::render::shaders::for_scene_format(source, color_format);
        let module = crate::render::shaders::create_module(device, shader.name, source.clone());
        let transforms = ObjectBuffer::new(gpu, "mesh transforms", 16);
        let uniforms = ObjectBuffer::new(gpu, M::NAME, 16);
        let frame_groups = FrameBindGroups::new(
            gpu,
            M::NAME,
            ObjectBuffer::<M::Uniform>::layout_entry(2),
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
            device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
                label: Some(&format!("{} deferred resolve layout", M::NAME)),
                bind_group_layouts: &[
                    Some(frame_groups.layout()),
                    Some(textures.layout()),
                    Some(resolve.layout()),
                ],
                immediate_size: 0,
            })
        });
        Self {
            pipelines: MaterialPipelines::new(PipelineSetup {
                shader: module,
                source,
                layout,
                resolve_layout,
                color_format,
                prepass,
            }),
            resolve,
            frame_groups,
            transforms,
            uniforms,
            textures,
            batches: Vec::new(),
            blended: Vec::new(),
            order: Vec::new(),
            models: Vec::new(),
            transform_data: Vec::new(),
            uniform_data: Vec::new(),
            sorted_uniforms: Vec::new(),
        }
    }

    /// Uploads the meshes and textures the draws use, computes each draw's key and uniform from
    /// the textures as bound, sorts and batches the draws, writes the per-draw data that
    /// changed, and prepares bind groups and pipelines. Counts what it uploaded in `stats`.
    pub(crate) fn prepare(
        &mut self,
        inputs: &PrepareInputs<'_>,
        draws: &[ExtractedDraw<M>],
        assets: &mut GpuAssets,
        lod_cache: &mut MeshLodCache,
        stats: &mut UploadStats,
        ids: &mut VisibilityIds,
    ) {
        let gpu = inputs.gpu;
        self.order.clear();
        self.uniform_data.clear();
        // Neighbouring draws mostly share mesh and textures: look each up once per run.
        let mut last_mesh = None;
        let mut bounds = None;
        let mut last_textures = None;
        let derived_slots = M::DERIVED_TEXTURE_SLOTS.min(MAX_DERIVED_TEXTURES);
        let mut facts: [Option<TextureFacts>; MAX_MATERIAL_TEXTURES] =
            [None; MAX_MATERIAL_TEXTURES];
        for (index, draw) in draws.iter().enumerate() {
            if last_mesh != Some(draw.mesh) {
                stats.meshes += u32::from(assets.prepare_mesh(gpu, inputs.meshes, draw.mesh));
                bounds = lod_cache.bounds(inputs.meshes, draw.mesh);
                last_mesh = Some(draw.mesh);
            }
            let mut derived = draw.material.derived_textures();
            // Entries past the declared slots are not bound: they must not split batches.
            derived[derived_slots..].fill(None);
            let textures = BoundTextures {
                images: draw.material.textures(),
                derived,
            };
            if last_textures != Some(textures) {
                for (slot, image) in textures.images.iter().enumerate() {
                    facts[slot] = image.and_then(|image| {
                        stats.images += u32::from(assets.prepare_image(gpu, inputs.images, image));
                        assets.image(image).map(|image| image.facts())
                    });
                }
                // Their sources are among the images: uploaded (or re-uploaded) just above.
                for derived in textures.derived.iter().flatten() {
                    stats.derived += u32::from(assets.prepare_derived(gpu, *derived));
                }
                last_textures = Some(textures);
            }
            let mut view = DrawView {
                model: draw.model,
                bounds,
                footprint: inputs.footprint,
            };
            let uniform = draw.material.uniform(&facts);
            let key = draw
                .material
                .draw_key(draw.material.key(), &uniform, &mut view);
            self.uniform_data.push(uniform);
            let (eye, forward) = inputs.eye;
            let view_depth = (draw.model.w_axis.truncate() - eye).dot(forward);
            let blends = M::blends(key);
            // Blended draws are ordered by their centre, as a mesh placed away from its origin
            // (a glTF primitive with its vertices where it stands) has it elsewhere.
            let centre_depth = if blends {
                let centre = bounds.map_or(draw.model.w_axis.truncate(), |bounds| {
                    draw.model.transform_point3(bounds.center)
                });
                f32::from_bits(depth_order_bits((centre - eye).dot(forward)))
            } else {
                0.0
            };
            self.order.push(SortEntry {
                key,
                casts_shadows: draw.casts_shadows,
                textures,
                mesh: draw.mesh,
                view_depth: depth_order_bits(view_depth),
                blends,
                far_first: if blends { !centre_depth.to_bits() } else { 0 },
                centre_depth,
                draw: index,
            });
        }
        // Opaque batches first (pipeline, textures, mesh), then nearest first within a batch:
        // the prepass then rejects hidden copies early (measured in sandbox/BENCHMARKS.md,
        // "overdraw"). Blended draws after them, farthest first. Stable: draws that share
        // everything keep the order of the world's query. Most frames come in the order the
        // last one was sorted into (a still camera), which the check finds in one pass.
        let sort_key = |entry: &SortEntry<M::Key>| {
            (
                entry.blends,
                entry.far_first,
                entry.key,
                entry.casts_shadows,
                entry.textures,
                entry.mesh,
                entry.view_depth,
            )
        };
        if !self.order.is_sorted_by_key(sort_key) {
            self.order.sort_by_key(sort_key);
        }

        // A transform (and its inverse) is recomputed only where the slot's model changed.
        self.models.truncate(self.order.len());
        self.transform_data.truncate(self.order.len());
        for (slot, entry) in self.order.iter().enumerate() {
            let draw = &draws[entry.draw];
            let model = (draw.model, draw.receives_shadows);
            if self.models.get(slot) == Some(&model) {
                continue;
            }
            let transform = MeshTransform::new(model.0, model.1);
            if slot < self.models.len() {
                self.models[slot] = model;
                self.transform_data[slot] = transform;
            } else {
                self.models.push(model);
                self.transform_data.push(transform);
            }
        }
        self.sorted_uniforms.clear();
        self.sorted_uniforms
            .extend(self.order.iter().map(|entry| self.uniform_data[entry.draw]));
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
                }
                _ => self.batches.push(Batch {
                    key: entry.key,
                    casts_shadows: entry.casts_shadows,
                    textures: entry.textures,
                    mesh: entry.mesh,
                    instances: instance..instance + 1,
                    visibility_ids: 0..0,
                    triangles: 0,
                }),
            }
        }
        self.assign_visibility_ids(inputs.deferred.is_some().then_some(ids), assets);
        let (transform_bytes, transforms_grew) = self.transforms.upload(gpu, &self.transform_data);
        let (uniform_bytes, uniforms_grew) = self.uniforms.upload(gpu, &self.sorted_uniforms);
        stats.uniform_bytes += transform_bytes + uniform_bytes;
        self.frame_groups.refresh(
            gpu,
            &DrawBuffers {
                frame: inputs.frame,
                transforms: self.transforms.buffer(),
                uniforms: self.uniforms.buffer(),
            },
            inputs.depth,
            transforms_grew || uniforms_grew,
        );

        self.textures
            .prepare(gpu, assets, self.batches.iter().map(|batch| batch.textures));
        self.pipelines
            .set_frame(inputs.shadow_maps, inputs.deferred.is_some());
        for batch in &self.batches {
            self.pipelines.ensure(&gpu.device, batch.key);
            if inputs.shadow_maps && batch.casts_shadows && !M::blends(batch.key) {
                self.pipelines.ensure_shadow(&gpu.device, batch.key);
            }
        }
        if let Some(resolve) = &mut self.resolve {
            let pipelines = &self.pipelines;
            match &inputs.deferred {
                Some(targets) => resolve.prepare(
                    gpu,
                    targets,
                    &self.batches,
                    |batch| pipelines.resolves_in_compute(batch.key),
                    assets,
                ),
                None => resolve.skip(),
            }
        }
    }

    /// Gives each batch its run of visibility `ids` (on deferred frames; else none) and each
    /// instance the id of its first triangle.
    fn assign_visibility_ids(&mut self, ids: Option<&mut VisibilityIds>, assets: &GpuAssets) {
        let Some(ids) = ids else {
            for transform in &mut self.transform_data {
                transform.first_visibility_id = 0;
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
            batch.visibility_ids = ids
                .allocate(count)
                .map_or(0..0, |first| first..first + count as u32);
            let first_id = batch.visibility_ids.start;
            for (k, slot) in batch.instances.clone().enumerate() {
                self.transform_data[slot as usize].first_visibility_id = if first_id == 0 {
                    0
                } else {
                    first_id + k as u32 * batch.triangles
                };
            }
        }
    }

    /// Whether the deferred resolve has pixels of this material to shade this frame.
    pub(crate) fn has_resolves(&self) -> bool {
        self.resolve.as_ref().is_some_and(DeferredResolve::has_work)
    }

    /// Records the deferred resolve's dispatches of this frame into `pass`.
    pub(crate) fn dispatch_resolves(&self, pass: &mut wgpu::ComputePass<'_>) {
        let Some(resolve) = &self.resolve else {
            return;
        };
        resolve.classify(pass);
        // Slot 0 of the frame uniform: the camera's view.
        pass.set_bind_group(0, self.frame_groups.shading(), &[0]);
        let mut bound_key = None;
        let mut bound_textures = None;
        resolve.dispatch(pass, &self.batches, |pass, batch| {
            let (Some(pipeline), Some(textures)) = (
                self.pipelines.resolve(&batch.key),
                self.textures.get(&batch.textures),
            ) else {
                return false;
            };
            if bound_key != Some(batch.key) {
                pass.set_pipeline(pipeline);
                bound_key = Some(batch.key);
            }
            if bound_textures != Some(batch.textures) {
                pass.set_bind_group(1, textures, &[]);
                bound_textures = Some(batch.textures);
            }
            true
        });
    }

    /// Whether any batch of the last prepared frame draws in `phase`.
    pub(crate) fn draws_in(&self, phase: DrawPhase) -> bool {
        self.batches
            .iter()
            .any(|batch| self.pipelines.pass_in(phase, batch.key).is_some())
    }

    /// The blended batches of the last prepared frame, for the frame's transparent phase:
    /// (view depth of the draw's centre, batch index).
    pub(crate) fn blended(&self) -> impl Iterator<Item = (f32, u32)> + '_ {
        self.blended.iter().copied()
    }

    /// Records the blended `batches` (indices into the last prepared frame's batches, in the
    /// order the transparent phase sorted them) into `pass`; neighbours that continue one
    /// another's instances with the same pipeline, textures and mesh are one draw.
    pub(crate) fn draw_blended(
        &self,
        pass: &mut wgpu::RenderPass<'_>,
        assets: &GpuAssets,
        batches: &[u32],
    ) {
        pass.set_bind_group(0, self.frame_groups.shading(), &[0]);
        let mut calls: Vec<DrawCall<M::Key>> = Vec::with_capacity(batches.len());
        for batch in batches
            .iter()
            .filter_map(|&index| self.batches.get(index as usize))
        {
            match calls.last_mut() {
                Some(call)
                    if call.key == batch.key
                        && call.textures == batch.textures
                        && call.mesh == batch.mesh
                        && call.instances.end == batch.instances.start =>
                {
                    call.instances.end = batch.instances.end;
                }
                _ => calls.push(DrawCall::of(batch, MeshPass::Transparent)),
            }
        }
        self.record_calls(pass, assets, calls);
    }

    /// Records the batches that draw in `phase` and whose mesh is on the GPU into `pass`,
    /// switching pipeline, textures and buffers only where they change.
    pub(crate) fn draw(
        &self,
        phase: DrawPhase,
        pass: &mut wgpu::RenderPass<'_>,
        assets: &GpuAssets,
    ) {
        let frame_bind_group = if phase == DrawPhase::Prepass {
            self.frame_groups.writing()
        } else {
            self.frame_groups.shading()
        };
        // Slot 0 of the frame uniform: the camera's view.
        pass.set_bind_group(0, frame_bind_group, &[0]);
        self.record_calls(
            pass,
            assets,
            self.batches.iter().filter_map(|batch| {
                let mesh_pass = self.pipelines.pass_in(phase, batch.key)?;
                // Blended batches draw in the frame's sorted transparent list instead.
                (mesh_pass != MeshPass::Transparent).then(|| DrawCall::of(batch, mesh_pass))
            }),
        );
    }

    /// Records the shadow casters into one shadow map's `pass`, whose view is the frame
    /// uniform's slot at `frame_offset`.
    pub(crate) fn draw_shadow_casters(
        &self,
        pass: &mut wgpu::RenderPass<'_>,
        frame_offset: u32,
        assets: &GpuAssets,
    ) {
        if !self.batches.iter().any(|batch| batch.casts_shadows) {
            return;
        }
        pass.set_bind_group(0, self.frame_groups.writing(), &[frame_offset]);
        self.record_calls(
            pass,
            assets,
            self.batches
                .iter()
                .filter(|batch| batch.casts_shadows && !M::blends(batch.key))
                .map(|batch| DrawCall::of(batch, MeshPass::Shadow)),
        );
    }

    /// Records `calls` whose mesh is on the GPU, each with its pass's pipeline, switching
    /// pipeline, textures and buffers only where they change.
    fn record_calls(
        &self,
        pass: &mut wgpu::RenderPass<'_>,
        assets: &GpuAssets,
        calls: impl IntoIterator<Item = DrawCall<M::Key>>,
    ) {
        let mut bound_key = None;
        let mut bound_textures = None;
        let mut bound_mesh = None;
        for call in calls {
            let (Some(mesh), Some(textures), Some(pipeline)) = (
                assets.mesh(call.mesh),
                self.textures.get(&call.textures),
                self.pipelines.get(call.pass, &call.key),
            ) else {
                continue;
            };
            if bound_key != Some((call.pass, call.key)) {
                pass.set_pipeline(pipeline);
                bound_key = Some((call.pass, call.key));
            }
            if bound_textures != Some(call.textures) {
                pass.set_bind_group(1, textures, &[]);
                bound_textures = Some(call.textures);
            }
            if bound_mesh != Some(call.mesh) {
                pass.set_vertex_buffer(0, mesh.vertices.slice(..));
                pass.set_index_buffer(mesh.indices.slice(..), wgpu::IndexFormat::Uint32);
                bound_mesh = Some(call.mesh);
            }
            pass.draw_indexed(0..mesh.index_count, 0, call.instances);
        }
    }
}
