//! One material's deferred resolve: the bind group layout of its inputs (group 2 of
//! `deferred_resolve.wgsl`), a uniform slot per resolved batch, a bind group per mesh, and the
//! dispatches. The pipelines are [`super::pipelines::MaterialPipelines`]'.

use std::collections::{HashMap, HashSet};
use std::sync::{Mutex, PoisonError};

use bytemuck::{Pod, Zeroable};
use glam::Mat4;

use super::batches::Batch;
use super::resolve_tiles::ResolveTiles;
use crate::gpu::layout::compute_storage_buffer;
use crate::gpu::{GpuAssets, GpuContext};
use crate::render::shaders::{self, ComposedShader, GeneratedWgsl, WgslFile};
use crate::{AssetId, Mesh};

/// The deferred resolve's inputs and `resolve_pixel()`, which rebuilds a pixel's vertex output
/// and footprint from its visibility id: a material's compute resolve composes it.
pub const DEFERRED_RESOLVE: WgslFile = crate::wgsl_file!("material/deferred_resolve.wgsl");

/// The candidate pass's and the settled depth's fragment entries, for a deferred shader whose
/// material settles its depth in the resolve (after [`crate::render::shaders::VISIBILITY`]).
pub const CANDIDATES: WgslFile = crate::wgsl_file!("material/candidates.wgsl");

/// `shader`'s twin for the deferred path, for a material whose surface lies on its polygon
/// ([`crate::Material::SURFACE_ON_POLYGON`]): [`crate::render::shaders::deferred_header`] first among its constants and
/// [`crate::render::shaders::VISIBILITY`] after its files, so its prepass draws write each pixel's visibility key with
/// the core's `fs_visibility` and it shades in the opaque phase as on the forward path. Made
/// once per shader for the whole process (the lists are `'static`, like a shader's own).
pub fn deferred_twin(shader: &ComposedShader) -> ComposedShader {
    static TWINS: Mutex<Vec<(ComposedShader, ComposedShader)>> = Mutex::new(Vec::new());
    let mut twins = TWINS.lock().unwrap_or_else(PoisonError::into_inner);
    if let Some((_, twin)) = twins.iter().find(|(forward, _)| forward == shader) {
        return *twin;
    }
    let constants: Vec<GeneratedWgsl> = std::iter::once(shaders::deferred_header as GeneratedWgsl)
        .chain(shader.constants.iter().copied())
        .collect();
    let files: Vec<WgslFile> = shader
        .files
        .iter()
        .copied()
        .chain([shaders::VISIBILITY])
        .collect();
    let twin = ComposedShader {
        name: Box::leak(format!("{} (deferred)", shader.name).into_boxed_str()),
        constants: Box::leak(constants.into_boxed_slice()),
        files: Box::leak(files.into_boxed_slice()),
    };
    twins.push((*shader, twin));
    twin
}

/// The two rounds of a frame's deferred resolve: the batches that settle candidates
/// ([`crate::Material::settles_depth_in_resolve`]) of every material, then the others.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum ResolveRound {
    /// Classification and the settling batches.
    Settling,
    /// Every other batch.
    Shading,
}

impl ResolveRound {
    /// The round of a batch that settles candidates or not.
    pub(crate) fn of(settles: bool) -> Self {
        if settles {
            Self::Settling
        } else {
            Self::Shading
        }
    }
}

/// What one dispatch resolves. Mirrors `ResolveBatch` in deferred_resolve.wgsl.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub(crate) struct ResolveBatch {
    inverse_view_projection: [[f32; 4]; 4],
    target_width: f32,
    target_height: f32,
    first_id: u32,
    end_id: u32,
    first_object: u32,
    triangles: u32,
    batch: u32,
    tiles_across: u32,
    tile_count: u32,
    writes_background: u32,
    _padding: [u32; 2],
    background: [f32; 4],
}

impl ResolveBatch {
    /// The fields every batch of a frame shares: the camera's `inverse` view-projection, the
    /// target's size and background and the tile grid; the batch's own are zero.
    fn for_frame(inverse: Mat4, targets: &ResolveTargets<'_>, tiles: &ResolveTiles) -> Self {
        let (width, height) = targets.size;
        Self {
            inverse_view_projection: inverse.to_cols_array_2d(),
            target_width: width as f32,
            target_height: height as f32,
            tiles_across: tiles.tiles_across(),
            tile_count: tiles.tile_count(),
            background: targets.background,
            ..Self::zeroed()
        }
    }
}

crate::wgsl_layout!(ResolveBatch {
    inverse_view_projection,
    target_width,
    target_height,
    first_id,
    end_id,
    first_object,
    triangles,
    batch,
    tiles_across,
    tile_count,
    writes_background,
    _padding,
    background,
});

/// The frame's targets and camera as the resolve sees them.
pub(crate) struct ResolveTargets<'a> {
    /// The visibility keys the prepass merged.
    pub(crate) visibility: &'a wgpu::Buffer,
    /// The HDR scene the resolve writes.
    pub(crate) scene: &'a wgpu::TextureView,
    /// The [`crate::render::RenderTarget::id`] of both.
    pub(crate) target: u64,
    pub(crate) size: (u32, u32),
    pub(crate) view_projection: Mat4,
    /// The clear colour as the opaque pass would have cleared to, where no draw shows.
    pub(crate) background: [f32; 4],
}

/// A mesh's resolve bind group and the buffers it was made with (a mesh uploaded anew gets
/// new buffers).
struct MeshBindGroup {
    vertices: wgpu::Buffer,
    indices: wgpu::Buffer,
    bind_group: wgpu::BindGroup,
}

/// `ResolveBatch::batch` of a dispatch over the whole target (`UNCLASSIFIED` in WGSL).
const UNCLASSIFIED: u32 = u32::MAX;

/// One dispatch of the frame: a batch, its place in the tile lists, and its uniform slot.
struct Dispatch {
    batch: usize,
    place: u32,
    offset: u32,
}

/// Material `M`'s resolve inputs.
pub(crate) struct DeferredResolve {
    label: &'static str,
    layout: wgpu::BindGroupLayout,
    slot_size: u64,
    slots: wgpu::Buffer,
    slot_data: Vec<u8>,
    /// What `slots` holds (written only when the frame's slots differ).
    uploaded_slots: Vec<u8>,
    meshes: HashMap<AssetId<Mesh>, MeshBindGroup>,
    /// The target and tile buffers ([`ResolveTiles::generation`]) the mesh bind groups hold.
    bound: (u64, u64),
    tiles: ResolveTiles,
    dispatches: Vec<Dispatch>,
}

impl DeferredResolve {
    /// The layout of group 2 for a scene target of `scene_format`; no slots yet.
    pub(crate) fn new(
        gpu: &GpuContext,
        label: &'static str,
        scene_format: wgpu::TextureFormat,
    ) -> Self {
        let stages = wgpu::ShaderStages::COMPUTE;
        let storage = |binding| compute_storage_buffer(binding, true);
        let layout = gpu
            .device
            .create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
                label: Some(&format!("{label} deferred resolve layout")),
                entries: &[
                    wgpu::BindGroupLayoutEntry {
                        binding: 0,
                        visibility: stages,
                        ty: wgpu::BindingType::Buffer {
                            ty: wgpu::BufferBindingType::Uniform,
                            has_dynamic_offset: true,
                            min_binding_size: wgpu::BufferSize::new(
                                std::mem::size_of::<ResolveBatch>() as u64,
                            ),
                        },
                        count: None,
                    },
                    // Read-write: settling resolves write the candidate keys.
                    compute_storage_buffer(1, false),
                    storage(2),
                    storage(3),
                    wgpu::BindGroupLayoutEntry {
                        binding: 4,
                        visibility: stages,
                        ty: wgpu::BindingType::StorageTexture {
                            access: wgpu::StorageTextureAccess::WriteOnly,
                            format: scene_format,
                            view_dimension: wgpu::TextureViewDimension::D2,
                        },
                        count: None,
                    },
                    storage(5),
                    storage(6),
                ],
            });
        let alignment = u64::from(gpu.device.limits().min_uniform_buffer_offset_alignment);
        let slot_size =
            (std::mem::size_of::<ResolveBatch>() as u64).div_ceil(alignment) * alignment;
        Self {
            label,
            layout,
            slot_size,
            slots: Self::slot_buffer(gpu, label, slot_size, 4),
            slot_data: Vec::new(),
            uploaded_slots: Vec::new(),
            meshes: HashMap::new(),
            bound: (0, 0),
            tiles: ResolveTiles::new(gpu, scene_format),
            dispatches: Vec::new(),
        }
    }

    fn slot_buffer(gpu: &GpuContext, label: &str, slot_size: u64, slots: u64) -> wgpu::Buffer {
        gpu.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some(&format!("{label} resolve batches")),
            size: slot_size * slots.max(1),
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        })
    }

    /// Group 2's layout, for the resolve's pipeline layout.
    pub(crate) fn layout(&self) -> &wgpu::BindGroupLayout {
        &self.layout
    }

    /// Plans this frame's dispatches: one per batch `resolves` picks, over the tiles the
    /// classification finds it in (with two batches or more; one batch covers the target),
    /// with its slot written and its mesh's bind group made where missing.
    pub(crate) fn prepare<K>(
        &mut self,
        gpu: &GpuContext,
        targets: &ResolveTargets<'_>,
        batches: &[Batch<K>],
        resolves: impl Fn(&Batch<K>) -> bool,
        assets: &GpuAssets,
    ) {
        self.dispatches.clear();
        self.slot_data.clear();
        let inverse = targets.view_projection.inverse();
        // A camera that maps everything onto a plane has no rays: nothing to resolve.
        if !inverse.is_finite() {
            return;
        }
        let resolved: Vec<_> = batches
            .iter()
            .enumerate()
            .filter(|(_, batch)| resolves(batch) && batch.visibility_ids.start != 0)
            .filter_map(|(index, batch)| Some((index, batch, assets.mesh(batch.mesh)?)))
            .collect();
        let classified =
            self.prepare_tiles(gpu, targets, resolved.iter().map(|(_, batch, _)| *batch));
        let frame_slot = ResolveBatch::for_frame(inverse, targets, &self.tiles);
        let mut used = HashSet::new();
        for (place, (index, batch, mesh)) in resolved.into_iter().enumerate() {
            let slot = ResolveBatch {
                first_id: batch.visibility_ids.start,
                end_id: batch.visibility_ids.end,
                first_object: batch.instances.start,
                triangles: batch.triangles,
                batch: if classified {
                    place as u32
                } else {
                    UNCLASSIFIED
                },
                writes_background: u32::from(!classified),
                ..frame_slot
            };
            self.push_dispatch(index, place as u32, &slot);
            used.insert(batch.mesh);
            self.bind_mesh(gpu, targets, batch.mesh, &mesh.vertices, &mesh.indices);
        }
        self.meshes.retain(|mesh, _| used.contains(mesh));
        if self.slot_data.is_empty() {
            return;
        }
        if self.slots.size() < self.slot_data.len() as u64 {
            self.grow_slots(gpu);
            return self.prepare(gpu, targets, batches, resolves, assets);
        }
        if self.slot_data != self.uploaded_slots {
            gpu.write_buffer(&self.slots, 0, &self.slot_data);
            self.uploaded_slots.clone_from(&self.slot_data);
        }
    }

    /// Prepares the tile classification for the `resolved` batches where it pays, and returns
    /// whether it does; drops the mesh bind groups where the target or the tile buffers they
    /// hold changed.
    fn prepare_tiles<'b, K: 'b>(
        &mut self,
        gpu: &GpuContext,
        targets: &ResolveTargets<'_>,
        resolved: impl ExactSizeIterator<Item = &'b Batch<K>>,
    ) -> bool {
        // Classifying costs one read of the whole visibility buffer, as does each batch's
        // whole-target dispatch (its pixels of other batches return after one load): it pays
        // from two batches on, while the tile lists fit the device's buffers.
        let classified =
            resolved.len() >= 2 && ResolveTiles::fits(gpu, resolved.len(), targets.size);
        let ranges: Vec<[u32; 2]> = if classified {
            resolved
                .map(|batch| [batch.visibility_ids.start, batch.visibility_ids.end])
                .collect()
        } else {
            Vec::new()
        };
        self.tiles.prepare(gpu, targets, &ranges);
        let bound = (targets.target, self.tiles.generation());
        if self.bound != bound {
            self.meshes.clear();
            self.bound = bound;
        }
        classified
    }

    /// Adds a dispatch of `batches[index]`, the `place`th resolved, with its uniform `slot`.
    fn push_dispatch(&mut self, index: usize, place: u32, slot: &ResolveBatch) {
        let offset = self.slot_data.len() as u64;
        self.slot_data.extend_from_slice(bytemuck::bytes_of(slot));
        self.slot_data.resize((offset + self.slot_size) as usize, 0);
        self.dispatches.push(Dispatch {
            batch: index,
            place,
            offset: offset as u32,
        });
    }

    /// Makes `mesh`'s bind group where it has none for these `vertices` and `indices` (a mesh
    /// uploaded anew gets new buffers).
    fn bind_mesh(
        &mut self,
        gpu: &GpuContext,
        targets: &ResolveTargets<'_>,
        mesh: AssetId<Mesh>,
        vertices: &wgpu::Buffer,
        indices: &wgpu::Buffer,
    ) {
        let current = self
            .meshes
            .get(&mesh)
            .is_some_and(|bound| bound.vertices == *vertices && bound.indices == *indices);
        if !current {
            let bind_group = self.mesh_bind_group(gpu, targets, vertices, indices);
            self.meshes.insert(
                mesh,
                MeshBindGroup {
                    vertices: vertices.clone(),
                    indices: indices.clone(),
                    bind_group,
                },
            );
        }
    }

    /// Replaces the slot buffer with one that holds this frame's slots (a power of two of them).
    fn grow_slots(&mut self, gpu: &GpuContext) {
        let slots = (self.slot_data.len() as u64 / self.slot_size).next_power_of_two();
        self.slots = Self::slot_buffer(gpu, self.label, self.slot_size, slots);
        self.uploaded_slots.clear();
        // Every bind group holds the old buffer.
        self.meshes.clear();
    }

    fn mesh_bind_group(
        &self,
        gpu: &GpuContext,
        targets: &ResolveTargets<'_>,
        vertices: &wgpu::Buffer,
        indices: &wgpu::Buffer,
    ) -> wgpu::BindGroup {
        let entry = |binding, resource| wgpu::BindGroupEntry { binding, resource };
        gpu.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some(&format!("{} deferred resolve", self.label)),
            layout: &self.layout,
            entries: &[
                entry(
                    0,
                    wgpu::BindingResource::Buffer(wgpu::BufferBinding {
                        buffer: &self.slots,
                        offset: 0,
                        size: wgpu::BufferSize::new(std::mem::size_of::<ResolveBatch>() as u64),
                    }),
                ),
                entry(1, targets.visibility.as_entire_binding()),
                entry(2, vertices.as_entire_binding()),
                entry(3, indices.as_entire_binding()),
                entry(4, wgpu::BindingResource::TextureView(targets.scene)),
                entry(5, self.tiles.batch_tiles().as_entire_binding()),
                entry(6, self.tiles.tile_counts().as_entire_binding()),
            ],
        })
    }

    /// Plans no dispatch this frame (it runs forward).
    pub(crate) fn skip(&mut self) {
        self.dispatches.clear();
    }

    /// Whether this frame has pixels to resolve.
    pub(crate) fn has_work(&self) -> bool {
        !self.dispatches.is_empty()
    }

    /// Whether this frame's recorded resolve writes the background where no draw shows: the
    /// classification does, else each whole-target dispatch of a batch that is `ready` (its
    /// pipeline and groups exist) does.
    pub(crate) fn writes_background<K>(
        &self,
        batches: &[Batch<K>],
        ready: impl Fn(&Batch<K>) -> bool,
    ) -> bool {
        self.has_work()
            && (self.tiles.has_batches()
                || self.dispatches.iter().any(|dispatch| {
                    let batch = &batches[dispatch.batch];
                    self.meshes.contains_key(&batch.mesh) && ready(batch)
                }))
    }

    /// Records the tile classification into `pass` (first: it binds a group 0 of its own).
    pub(crate) fn classify(&self, pass: &mut wgpu::ComputePass<'_>) {
        if self.has_work() {
            self.tiles.record(pass);
        }
    }

    /// Records this frame's dispatches into `pass`, one workgroup per tile each batch shows in
    /// (indirect, after [`DeferredResolve::classify`]); `bind` sets the batch's pipeline and
    /// groups 0 and 1 (it returns `false` where they are missing, and the batch is skipped).
    pub(crate) fn dispatch<K>(
        &self,
        pass: &mut wgpu::ComputePass<'_>,
        batches: &[Batch<K>],
        mut bind: impl FnMut(&mut wgpu::ComputePass<'_>, &Batch<K>) -> bool,
    ) {
        for dispatch in &self.dispatches {
            let batch = &batches[dispatch.batch];
            let Some(mesh) = self.meshes.get(&batch.mesh) else {
                continue;
            };
            if !bind(pass, batch) {
                continue;
            }
            pass.set_bind_group(2, &mesh.bind_group, &[dispatch.offset]);
            if self.tiles.has_batches() {
                let (args, offset) = self.tiles.dispatch_args(dispatch.place);
                pass.dispatch_workgroups_indirect(args, offset);
            } else {
                pass.dispatch_workgroups(self.tiles.tiles_across(), self.tiles.tiles_down(), 1);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::gpu::Vertex;
    use crate::material::check_wgsl_layout;

    #[test]
    fn the_resolve_inputs_match_their_wgsl() {
        let source = crate::parallax::PARALLAX_DEFERRED_SHADER.source();
        assert_eq!(
            check_wgsl_layout::<ResolveBatch>(&source, "ResolveBatch"),
            Ok(())
        );
        assert_eq!(check_wgsl_layout::<Vertex>(&source, "StoredVertex"), Ok(()));
    }

    #[test]
    fn each_deferred_shader_is_its_forward_shader_and_more() {
        use crate::render::shaders::{VISIBILITY, deferred_header};
        for (forward, deferred) in [
            (crate::lit::LIT_SHADER, crate::lit::LIT_DEFERRED_SHADER),
            (
                crate::parallax::PARALLAX_SHADER,
                crate::parallax::PARALLAX_DEFERRED_SHADER,
            ),
        ] {
            let header = crate::shader::GENERATED_HEADER;
            assert_eq!(
                deferred.generated(),
                forward
                    .generated()
                    .replacen(header, &format!("{header}{}", deferred_header()), 1),
                "{}",
                deferred.name
            );
            assert_eq!(
                &deferred.files[..forward.files.len()],
                forward.files,
                "{}",
                deferred.name
            );
            assert!(deferred.files.contains(&VISIBILITY), "{}", deferred.name);
        }
    }
}
