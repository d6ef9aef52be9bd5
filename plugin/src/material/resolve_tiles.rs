//! The deferred resolve's tile classification (deferred_classify.wgsl) for one material: which
//! 8 × 8 tiles of the visibility buffer each of its resolve batches shows in, as a tile list and
//! an indirect dispatch per batch, so a batch's resolve runs only where the batch is seen. It
//! also writes the background where no draw shows.

use bytemuck::{Pod, Zeroable};

use super::deferred::ResolveTargets;
use crate::gpu::GpuContext;
use crate::gpu::layout::{compute_storage_buffer, compute_storage_texture, compute_uniform_buffer};
use crate::render::shaders::{self, ComposedShader, WgslFile};

/// The classification's shader.
pub const DEFERRED_CLASSIFY_SHADER: ComposedShader = ComposedShader {
    name: "deferred_classify.wgsl",
    constants: &[shaders::deferred_header],
    files: &[shaders::VISIBILITY_READ, DEFERRED_CLASSIFY],
};

/// The classification's own WGSL.
const DEFERRED_CLASSIFY: WgslFile = crate::wgsl_file!("material/deferred_classify.wgsl");

/// Mirrors `ClassifyParams` in deferred_classify.wgsl.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub(crate) struct ClassifyParams {
    width: u32,
    height: u32,
    tiles_across: u32,
    tile_count: u32,
    batch_count: u32,
    tiles_down: u32,
    _padding: [u32; 2],
    background: [f32; 4],
}

crate::wgsl_layout!(ClassifyParams {
    width,
    height,
    tiles_across,
    tile_count,
    batch_count,
    tiles_down,
    _padding,
    background
});

/// The buffers of one frame's classification, sized for `batches` batches of `tiles` tiles in
/// `rows` rows.
struct TileBuffers {
    batches: u64,
    tiles: u64,
    rows: u64,
    batch_ids: wgpu::Buffer,
    tile_counts: wgpu::Buffer,
    batch_tiles: wgpu::Buffer,
    dispatch_args: wgpu::Buffer,
    row_counts: wgpu::Buffer,
    row_tiles: wgpu::Buffer,
}

impl TileBuffers {
    fn new(gpu: &GpuContext, batches: u64, (tiles, rows): (u64, u64)) -> Self {
        let buffer = |label: &str, size: u64, usage| {
            gpu.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: size.max(4),
                usage: wgpu::BufferUsages::STORAGE | usage,
                mapped_at_creation: false,
            })
        };
        Self {
            batches,
            tiles,
            rows,
            batch_ids: buffer(
                "resolve batch ids",
                batches * 8,
                wgpu::BufferUsages::COPY_DST,
            ),
            tile_counts: buffer(
                "resolve tile counts",
                batches * 4,
                wgpu::BufferUsages::COPY_DST,
            ),
            batch_tiles: buffer(
                "resolve batch tiles",
                batches * tiles * 4,
                wgpu::BufferUsages::empty(),
            ),
            dispatch_args: buffer(
                "resolve dispatch args",
                batches * 12,
                wgpu::BufferUsages::INDIRECT,
            ),
            row_counts: buffer(
                "resolve row counts",
                batches * rows * 4,
                wgpu::BufferUsages::empty(),
            ),
            row_tiles: buffer(
                "resolve row tiles",
                batches * tiles * 4,
                wgpu::BufferUsages::empty(),
            ),
        }
    }
}

/// One material's classification: pipelines, buffers, and the bind group of the current
/// target and buffers.
pub(crate) struct ResolveTiles {
    layout: wgpu::BindGroupLayout,
    pipeline_layout: wgpu::PipelineLayout,
    /// `cs_clear_counts`, `cs_classify`, `cs_join_rows` and `cs_copy_rows`, compiled on the
    /// first frame that classifies (most materials never do: one resolve batch, or none).
    pipelines: Option<[wgpu::ComputePipeline; 4]>,
    scene_format: wgpu::TextureFormat,
    params: wgpu::Buffer,
    /// What `params` and the batches' ids hold (written only when they change).
    uploaded: Option<(ClassifyParams, Vec<[u32; 2]>)>,
    buffers: TileBuffers,
    /// Bumped whenever the buffers are made anew (the resolve's bind groups hold them).
    generation: u64,
    bind_group: Option<((u64, u64), wgpu::BindGroup)>,
    tiles: (u32, u32),
    batch_count: u32,
}

impl ResolveTiles {
    /// The layouts for a scene target of `scene_format`; no pipelines or tiles yet.
    pub(crate) fn new(gpu: &GpuContext, scene_format: wgpu::TextureFormat) -> Self {
        let device = &gpu.device;
        let storage = compute_storage_buffer;
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("resolve classification layout"),
            entries: &[
                compute_uniform_buffer(0, false),
                storage(1, true),
                storage(2, true),
                storage(3, false),
                storage(4, false),
                storage(5, false),
                storage(6, false),
                storage(7, false),
                compute_storage_texture(8, scene_format),
            ],
        });
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("resolve classification"),
            bind_group_layouts: &[Some(&layout)],
            immediate_size: 0,
        });
        Self {
            layout,
            pipeline_layout,
            pipelines: None,
            scene_format,
            uploaded: None,
            params: device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("resolve classification params"),
                size: std::mem::size_of::<ClassifyParams>() as u64,
                usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            }),
            buffers: TileBuffers::new(gpu, 1, (1, 1)),
            generation: 0,
            bind_group: None,
            tiles: (0, 0),
            batch_count: 0,
        }
    }

    /// Plans this frame: the batches' id ranges (`first..end`, increasing) over `targets`,
    /// uploading what changed.
    pub(crate) fn prepare(
        &mut self,
        gpu: &GpuContext,
        targets: &ResolveTargets<'_>,
        ranges: &[[u32; 2]],
    ) {
        let size = targets.size;
        self.tiles = shaders::deferred_tiles(size);
        let tile_count = u64::from(self.tiles.0) * u64::from(self.tiles.1);
        self.batch_count = ranges.len() as u32;
        if ranges.is_empty() {
            return;
        }
        if self.pipelines.is_none() {
            self.pipelines = Some(self.compile(gpu));
        }
        let batches = ranges.len() as u64;
        let rows = u64::from(self.tiles.1);
        if batches > self.buffers.batches
            || tile_count != self.buffers.tiles
            || rows != self.buffers.rows
        {
            self.buffers = TileBuffers::new(gpu, batches.next_power_of_two(), (tile_count, rows));
            self.generation += 1;
            self.uploaded = None;
        }
        let params = ClassifyParams {
            width: size.0,
            height: size.1,
            tiles_across: self.tiles.0,
            tile_count: tile_count as u32,
            batch_count: self.batch_count,
            tiles_down: self.tiles.1,
            _padding: [0; 2],
            background: targets.background,
        };
        if self
            .uploaded
            .as_ref()
            .is_none_or(|(uploaded, ids)| *uploaded != params || ids != ranges)
        {
            gpu.write_buffer(&self.params, 0, bytemuck::bytes_of(&params));
            gpu.write_buffer(&self.buffers.batch_ids, 0, bytemuck::cast_slice(ranges));
            self.uploaded = Some((params, ranges.to_vec()));
        }
        let bound = (targets.target, self.generation);
        if self.bind_group.as_ref().map(|(key, _)| *key) != Some(bound) {
            let entry = |binding, resource| wgpu::BindGroupEntry { binding, resource };
            let bind_group = gpu.device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("resolve classification"),
                layout: &self.layout,
                entries: &[
                    entry(0, self.params.as_entire_binding()),
                    entry(1, targets.visibility.as_entire_binding()),
                    entry(2, self.buffers.batch_ids.as_entire_binding()),
                    entry(3, self.buffers.tile_counts.as_entire_binding()),
                    entry(4, self.buffers.batch_tiles.as_entire_binding()),
                    entry(5, self.buffers.dispatch_args.as_entire_binding()),
                    entry(6, self.buffers.row_counts.as_entire_binding()),
                    entry(7, self.buffers.row_tiles.as_entire_binding()),
                    entry(8, wgpu::BindingResource::TextureView(targets.scene)),
                ],
            });
            self.bind_group = Some((bound, bind_group));
        }
    }

    /// The classification's pipelines, for a scene target of the format it was made for.
    fn compile(&self, gpu: &GpuContext) -> [wgpu::ComputePipeline; 4] {
        let target = shaders::ShaderTarget::of_device(&gpu.device, self.scene_format);
        let module = shaders::create_module(
            &gpu.device,
            DEFERRED_CLASSIFY_SHADER.name,
            DEFERRED_CLASSIFY_SHADER.source_for(&target),
        );
        let pipeline = |entry: &str| {
            gpu.device
                .create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                    label: Some(entry),
                    layout: Some(&self.pipeline_layout),
                    module: &module,
                    entry_point: Some(entry),
                    compilation_options: Default::default(),
                    cache: None,
                })
        };
        [
            pipeline("cs_clear_counts"),
            pipeline("cs_classify"),
            pipeline("cs_join_rows"),
            pipeline("cs_copy_rows"),
        ]
    }

    /// Records the classification, the joined lists and the indirect arguments into `pass`
    /// (before the batches' dispatches; each dispatch of a compute pass sees the writes of the
    /// ones before).
    pub(crate) fn record(&self, pass: &mut wgpu::ComputePass<'_>) {
        let (Some((_, bind_group)), Some([clear_counts, classify, join_rows, copy_rows])) =
            (&self.bind_group, &self.pipelines)
        else {
            return;
        };
        if self.batch_count == 0 {
            return;
        }
        let (across, down) = self.tiles;
        pass.set_bind_group(0, bind_group, &[]);
        pass.set_pipeline(clear_counts);
        pass.dispatch_workgroups((self.batch_count * down).div_ceil(64), 1, 1);
        pass.set_pipeline(classify);
        pass.dispatch_workgroups(across, down, 1);
        pass.set_pipeline(join_rows);
        pass.dispatch_workgroups(self.batch_count, 1, 1);
        pass.set_pipeline(copy_rows);
        pass.dispatch_workgroups(down, self.batch_count, 1);
    }

    /// Whether the tile lists of `batches` batches over a target of `size` fit the device's
    /// buffer limits (two lists of every tile per batch, by row and joined: 518 KB each at 4K)
    /// and its dispatch limits.
    pub(crate) fn fits(gpu: &GpuContext, batches: usize, size: (u32, u32)) -> bool {
        let (across, down) = shaders::deferred_tiles(size);
        let tiles = u64::from(across) * u64::from(down);
        let most = u64::from(gpu.device.limits().max_compute_workgroups_per_dimension);
        gpu.storage_buffer_fits((batches as u64).next_power_of_two() * tiles * 4)
            && (batches as u64) * u64::from(down) <= most * 64
            && batches as u64 <= most
    }

    /// Tiles along the target's width.
    pub(crate) fn tiles_across(&self) -> u32 {
        self.tiles.0
    }

    /// Tiles along the target's height.
    pub(crate) fn tiles_down(&self) -> u32 {
        self.tiles.1
    }

    /// Whether this frame classifies (it has batches).
    pub(crate) fn has_batches(&self) -> bool {
        self.batch_count > 0
    }

    /// Tiles of the whole target: the slots of each batch's list.
    pub(crate) fn tile_count(&self) -> u32 {
        self.tiles.0 * self.tiles.1
    }

    /// Changes whenever the buffers below are made anew.
    pub(crate) fn generation(&self) -> u64 {
        self.generation
    }

    /// Each batch's tile list.
    pub(crate) fn batch_tiles(&self) -> &wgpu::Buffer {
        &self.buffers.batch_tiles
    }

    /// Each batch's tile count.
    pub(crate) fn tile_counts(&self) -> &wgpu::Buffer {
        &self.buffers.tile_counts
    }

    /// Batch `batch`'s indirect dispatch arguments: the buffer and the byte offset.
    pub(crate) fn dispatch_args(&self, batch: u32) -> (&wgpu::Buffer, u64) {
        (&self.buffers.dispatch_args, u64::from(batch) * 12)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::material::check_wgsl_layout;

    #[test]
    fn the_classification_params_match_their_wgsl() {
        let source = DEFERRED_CLASSIFY_SHADER.source();
        assert_eq!(
            check_wgsl_layout::<ClassifyParams>(&source, "ClassifyParams"),
            Ok(())
        );
    }
}
