//! Uploading scattered entries of a per-draw buffer in one write: the changed entries and their
//! slots are packed into a staging buffer, and a compute dispatch, recorded at the start of the
//! frame's encoder ([`ScatterQueue`]), writes each into its slot. A write call per run of entries
//! costs far more on the CPU than the bytes (a tenth of the draws moving, spread over the
//! buffer, made hundreds of calls a frame: sandbox/BENCHMARKS.md, "CPU side"); the dispatch
//! costs one write however the changes lie.

use crate::gpu::GpuContext;
use crate::shader::{ComposedShader, WgslFile};

/// The scatter pass's WGSL file.
const SCATTER_ENTRY: WgslFile = crate::wgsl_file!("gpu/scatter.wgsl");

/// The scatter pass's shader.
pub const SCATTER_SHADER: ComposedShader = ComposedShader {
    name: "scatter.wgsl",
    constants: &[],
    files: &[SCATTER_ENTRY],
};

/// Threads per workgroup (`GROUP_SIZE` in scatter.wgsl).
const GROUP_SIZE: u32 = 64;

/// The pipeline, the staging buffer and the bind group of one destination buffer.
#[derive(Debug)]
pub(crate) struct ScatterUpload {
    pipeline: wgpu::ComputePipeline,
    staging: Option<wgpu::Buffer>,
    /// The bind group, and the destination buffer it writes.
    bind_group: Option<(wgpu::BindGroup, wgpu::Buffer)>,
    packed: Vec<u32>,
}

impl ScatterUpload {
    /// The pipeline, compiled on `gpu`; the staging buffer follows on first use.
    pub(crate) fn new(gpu: &GpuContext) -> Self {
        let module = gpu
            .device
            .create_shader_module(wgpu::ShaderModuleDescriptor {
                label: Some(SCATTER_SHADER.name),
                source: wgpu::ShaderSource::Wgsl(SCATTER_SHADER.source().into()),
            });
        let pipeline = gpu
            .device
            .create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                label: Some("scatter upload"),
                layout: None,
                module: &module,
                entry_point: Some("cs_scatter"),
                compilation_options: Default::default(),
                cache: None,
            });
        Self {
            pipeline,
            staging: None,
            bind_group: None,
            packed: Vec::new(),
        }
    }

    /// Uploads `entries` (the bytes of each, `words_per_entry` words) for their `slots` of
    /// `destination` and queues the dispatch that writes them there on `queue`. Returns the
    /// bytes uploaded. At most once a frame: the staging buffer must not be written again before
    /// the dispatch ran (the Prepare stage submits what no frame recorded before any upload).
    pub(crate) fn write<'a>(
        &mut self,
        gpu: &GpuContext,
        (destination, queue): (&wgpu::Buffer, &mut ScatterQueue),
        (slots, words_per_entry): (&[u32], u32),
        entries: impl Iterator<Item = &'a [u8]>,
    ) -> u64 {
        self.packed.clear();
        self.packed.push(slots.len() as u32);
        self.packed.push(words_per_entry);
        self.packed.extend_from_slice(slots);
        for entry in entries {
            match bytemuck::try_cast_slice::<u8, u32>(entry) {
                Ok(words) => self.packed.extend_from_slice(words),
                // Bytes not aligned to words: one word at a time.
                Err(_) => self.packed.extend(
                    entry
                        .chunks_exact(4)
                        .map(|word| u32::from_ne_bytes([word[0], word[1], word[2], word[3]])),
                ),
            }
        }
        let size = std::mem::size_of_val(self.packed.as_slice()) as u64;
        self.prepare_staging(gpu, size, destination);
        let (Some(staging), Some((bind_group, _))) = (&self.staging, &self.bind_group) else {
            return 0;
        };
        gpu.write_buffer(staging, 0, bytemuck::cast_slice(&self.packed));
        let groups = (slots.len() as u32 * words_per_entry).div_ceil(GROUP_SIZE);
        let row = groups
            .min(gpu.device.limits().max_compute_workgroups_per_dimension)
            .max(1);
        queue.0.push(ScatterDispatch {
            pipeline: self.pipeline.clone(),
            bind_group: bind_group.clone(),
            groups: (row, groups.div_ceil(row)),
        });
        size
    }

    /// Grows the staging buffer to hold `bytes`, and binds it with `destination`.
    fn prepare_staging(&mut self, gpu: &GpuContext, bytes: u64, destination: &wgpu::Buffer) {
        let staging = match self.staging.take() {
            Some(staging) if staging.size() >= bytes => staging,
            _ => {
                // A new staging buffer needs a new bind group.
                self.bind_group = None;
                gpu.device.create_buffer(&wgpu::BufferDescriptor {
                    label: Some("scatter upload staging"),
                    size: bytes.next_power_of_two(),
                    usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
                    mapped_at_creation: false,
                })
            }
        };
        if self
            .bind_group
            .as_ref()
            .is_none_or(|(_, bound)| bound != destination)
        {
            let group = gpu.device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("scatter upload"),
                layout: &self.pipeline.get_bind_group_layout(0),
                entries: &[
                    wgpu::BindGroupEntry {
                        binding: 0,
                        resource: staging.as_entire_binding(),
                    },
                    wgpu::BindGroupEntry {
                        binding: 1,
                        resource: destination.as_entire_binding(),
                    },
                ],
            });
            self.bind_group = Some((group, destination.clone()));
        }
        self.staging = Some(staging);
    }
}

/// One queued scatter: its pipeline, bindings and workgroups.
#[derive(Debug)]
struct ScatterDispatch {
    pipeline: wgpu::ComputePipeline,
    bind_group: wgpu::BindGroup,
    groups: (u32, u32),
}

/// The scatters uploaded in the Prepare stage, for the frame to record before its passes read
/// the buffers. Part of the GPU assets.
#[derive(Debug, Default)]
pub(crate) struct ScatterQueue(Vec<ScatterDispatch>);

impl ScatterQueue {
    /// Records the queued scatters into `encoder` (one compute pass) and forgets them: the frame
    /// submits them before anything of its own.
    pub(crate) fn record(&mut self, encoder: &mut wgpu::CommandEncoder) {
        if self.0.is_empty() {
            return;
        }
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("scatter uploads"),
            timestamp_writes: None,
        });
        for dispatch in self.0.drain(..) {
            pass.set_pipeline(&dispatch.pipeline);
            pass.set_bind_group(0, &dispatch.bind_group, &[]);
            pass.dispatch_workgroups(dispatch.groups.0, dispatch.groups.1, 1);
        }
    }

    /// Submits the scatters no frame recorded (Prepare ran again without a Render stage between).
    pub(crate) fn submit_unrecorded(&mut self, gpu: &GpuContext) {
        if self.0.is_empty() {
            return;
        }
        let mut encoder = gpu
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("scatter uploads"),
            });
        self.record(&mut encoder);
        gpu.queue.submit([encoder.finish()]);
    }
}
