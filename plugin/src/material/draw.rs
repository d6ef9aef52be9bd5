//! Recording one material's prepared batches: the draws of each render phase (prepass, opaque,
//! transparent, shadow maps) and the deferred resolve's dispatches, switching pipeline, textures
//! and buffers only where they change.

use std::ops::Range;

use super::Material;
use super::batches::{Batch, MaterialBatches};
use super::deferred::{DeferredResolve, ResolveRound};
use super::mesh_pipeline::MeshPass;
use crate::gpu::BoundTextures;
use crate::gpu::GpuAssets;
use crate::render::DrawPhase;
use crate::{AssetId, Mesh};

/// One `draw_indexed` of a run of instances with one pipeline, texture set and mesh.
struct DrawCall<K> {
    pass: MeshPass,
    key: K,
    textures: BoundTextures,
    mesh: AssetId<Mesh>,
    instances: Range<u32>,
}

impl<K: Copy> DrawCall<K> {
    /// The call drawing all of `batch`'s instances with `pass`'s pipeline.
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

impl<M: Material> MaterialBatches<M> {
    /// Whether the deferred resolve has pixels of this material to shade this frame.
    pub(crate) fn has_resolves(&self) -> bool {
        self.resolve.as_ref().is_some_and(DeferredResolve::has_work)
    }

    /// Records the deferred resolve's dispatches of this frame in `round` into `pass`: the
    /// tile classification and the batches that settle candidates first, the others after.
    pub(crate) fn dispatch_resolves(&self, pass: &mut wgpu::ComputePass<'_>, round: ResolveRound) {
        let Some(resolve) = &self.resolve else {
            return;
        };
        if round == ResolveRound::Settling {
            resolve.classify(pass);
        }
        // Slot 0 of the frame uniform: the camera's view.
        pass.set_bind_group(0, self.frame_groups.shading(), &[0]);
        let mut bound_key = None;
        let mut bound_textures = None;
        resolve.dispatch(pass, &self.batches, |pass, batch| {
            if ResolveRound::of(M::settles_depth_in_resolve(batch.key)) != round {
                return false;
            }
            let Some((pipeline, textures)) = self.resolve_inputs(batch) else {
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

    /// The resolve pipeline and texture group of `batch`, where both exist.
    fn resolve_inputs(
        &self,
        batch: &Batch<M::Key>,
    ) -> Option<(&wgpu::ComputePipeline, &wgpu::BindGroup)> {
        Some((
            self.pipelines.resolve(&batch.key)?,
            self.textures.get(&batch.textures)?,
        ))
    }

    /// Whether this frame's resolve of `M` writes the background where no draw shows.
    pub(crate) fn resolve_writes_background(&self) -> bool {
        self.resolve.as_ref().is_some_and(|resolve| {
            resolve.writes_background(&self.batches, |batch| self.resolve_inputs(batch).is_some())
        })
    }

    /// Whether any batch of the last prepared frame draws in `phase`.
    pub(crate) fn draws_in(&self, phase: DrawPhase) -> bool {
        self.batches
            .iter()
            .any(|batch| self.batch_pass(phase, batch).is_some())
    }

    /// The pass `batch` draws with in `phase`, if it draws there: in the object motion phase
    /// only batches with a moving instance do.
    fn batch_pass(&self, phase: DrawPhase, batch: &Batch<M::Key>) -> Option<MeshPass> {
        if phase == DrawPhase::Motion && !batch.moving {
            return None;
        }
        self.pipelines.pass_in(phase, batch.key)
    }

    /// The blended batches of the last prepared frame, for the frame's transparent phase:
    /// (view depth of the draw's centre, batch index).
    pub(crate) fn blended(&self) -> impl Iterator<Item = (f32, u32)> + '_ {
        self.blended.iter().copied()
    }

    /// The batches of the last prepared frame that draw in `phase` (the prepass, the
    /// candidates), for the frame's nearest-first list of it: (view depth of the batch's
    /// nearest point, batch index, whether the polygon pass may find it instead).
    pub(crate) fn nearest_first(
        &self,
        phase: DrawPhase,
    ) -> impl Iterator<Item = (f32, u32, bool)> + '_ {
        self.batches
            .iter()
            .enumerate()
            .filter_map(move |(index, batch)| {
                let index = index as u32;
                let polygon = self.polygon_batches.binary_search(&index).is_ok();
                self.pipelines
                    .pass_in(phase, batch.key)
                    .map(|_| (batch.nearest_depth, index, polygon))
            })
    }

    /// Records the `listed` batches (indices into the last prepared frame's batches, in the
    /// order the frame's sorted list of `phase` gave them) that draw in `phase` into `pass`;
    /// neighbours that continue one another's instances with the same pipeline, textures and
    /// mesh are one draw.
    pub(crate) fn draw_listed(
        &self,
        phase: DrawPhase,
        pass: &mut wgpu::RenderPass<'_>,
        assets: &GpuAssets,
        listed: &[u32],
    ) {
        pass.set_bind_group(0, self.frame_bind_group(phase), &[0]);
        let mut calls: Vec<DrawCall<M::Key>> = Vec::with_capacity(listed.len());
        for (batch, mesh_pass) in listed.iter().filter_map(|&index| {
            let batch = self.batches.get(index as usize)?;
            Some((batch, self.pipelines.pass_in(phase, batch.key)?))
        }) {
            match calls.last_mut() {
                Some(call)
                    if call.pass == mesh_pass
                        && call.key == batch.key
                        && call.textures == batch.textures
                        && call.mesh == batch.mesh
                        && call.instances.end == batch.instances.start =>
                {
                    call.instances.end = batch.instances.end;
                }
                _ => calls.push(DrawCall::of(batch, mesh_pass)),
            }
        }
        self.record_calls(pass, assets, calls);
    }

    /// The frame bind group of `phase`: the prepass and the candidates' passes write (depth,
    /// visibility and candidate keys), the others shade.
    fn frame_bind_group(&self, phase: DrawPhase) -> &wgpu::BindGroup {
        if matches!(
            phase,
            DrawPhase::Prepass | DrawPhase::Candidates | DrawPhase::SettledDepth
        ) {
            self.frame_groups.writing()
        } else {
            self.frame_groups.shading()
        }
    }

    /// Records the batches that draw in `phase` and whose mesh is on the GPU into `pass`,
    /// switching pipeline, textures and buffers only where they change.
    pub(crate) fn draw(
        &self,
        phase: DrawPhase,
        pass: &mut wgpu::RenderPass<'_>,
        assets: &GpuAssets,
    ) {
        // Slot 0 of the frame uniform: the camera's view.
        pass.set_bind_group(0, self.frame_bind_group(phase), &[0]);
        self.record_calls(
            pass,
            assets,
            self.batches.iter().filter_map(|batch| {
                let mesh_pass = self.batch_pass(phase, batch)?;
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
        if self.shadow_batches().next().is_none() {
            return;
        }
        pass.set_bind_group(0, self.frame_groups.writing(), &[frame_offset]);
        self.record_calls(
            pass,
            assets,
            self.shadow_batches()
                .map(|batch| DrawCall::of(batch, MeshPass::Shadow)),
        );
    }

    /// The batches drawn into shadow maps: the opaque casters.
    fn shadow_batches(&self) -> impl Iterator<Item = &Batch<M::Key>> {
        self.batches
            .iter()
            .filter(|batch| batch.casts_shadows && !M::blends(batch.key))
    }

    /// A hash of what the shadow maps draw of this material: each casting batch's key,
    /// textures, mesh and instances, and the pipeline that draws it (a pipeline compiled in the
    /// background or reloaded replaces another). Equal from frame to frame while the casters'
    /// batches stay; their draws are followed apart ([`MaterialBatches::casters_data_changed`]).
    pub(crate) fn shadow_casters_signature(&self) -> u64 {
        use std::hash::{Hash, Hasher};
        let mut hasher = std::collections::hash_map::DefaultHasher::new();
        for batch in self.shadow_batches() {
            (
                batch.key,
                batch.textures,
                batch.mesh,
                batch.instances.clone(),
            )
                .hash(&mut hasher);
            self.pipelines
                .get(MeshPass::Shadow, &batch.key)
                .hash(&mut hasher);
        }
        hasher.finish()
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
