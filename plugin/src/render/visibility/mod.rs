//! The deferred path's visibility buffer (visibility.wgsl writes it): its size, the ids a frame
//! hands out, and the buffer of one target; and the core's compute passes over it: its clear,
//! the polygon pass, the settled depth and the background.

mod deferred_background;
mod listed_triangle;
mod polygons;
mod settled_depth;

pub use deferred_background::DEFERRED_BACKGROUND;
pub(crate) use deferred_background::DeferredBackground;
pub(crate) use listed_triangle::VisiblePolygon;
pub use polygons::POLYGON_PASS_SHADER;
pub(crate) use polygons::{
    MAX_LISTED_TRIANGLES, MAX_POLYGON_TRIANGLES, MIN_POLYGON_PIXELS, VisiblePolygons,
};
pub use settled_depth::{SETTLED_DEPTH_SHADER, SettledDepth};

use super::RenderTarget;
use super::shaders::{ComposedShader, WgslFile};
use crate::gpu::{GpuContext, PassTimestamps};

/// The compute pass that clears the visibility keys (visibility_clear.wgsl).
pub const VISIBILITY_CLEAR_SHADER: ComposedShader = ComposedShader {
    name: "visibility_clear.wgsl",
    constants: &[],
    files: &[VISIBILITY_CLEAR_ENTRY],
};

/// The clear's WGSL file.
const VISIBILITY_CLEAR_ENTRY: WgslFile =
    crate::wgsl_file!(nested "render/visibility/visibility_clear.wgsl");

/// Keys one workgroup of the clear writes (`CLEAR_GROUP_SIZE` in WGSL).
const CLEAR_GROUP_SIZE: u64 = 256;

/// Workgroups along a dispatch's first dimension at most (WebGPU's limit).
const MAX_GROUPS_ACROSS: u64 = 65_535;

/// Bytes per pixel of the visibility buffer: one 64-bit key, the pixel's depth above its
/// visibility id, which every fragment of the visibility pass merges with `atomicMax`, so the
/// nearest wins whatever the order fragments arrive in (each deferred draw owns a run of ids,
/// one per triangle, handed out per frame). A storage buffer, not a colour attachment: on the
/// GPUs we measure, a full-screen pass that writes depth and an `R32Uint` attachment takes about
/// twice as long as depth and a 64-bit atomic (sandbox/BENCHMARKS.md, "What the numbers mean").
pub const VISIBILITY_BYTES_PER_PIXEL: u64 = 8;

/// Hands out a frame's visibility ids: each batch of deferred draws a run of one id per
/// triangle per draw, from 1 (0 marks no draw). At most `u32::MAX` ids a frame: past that a
/// batch gets none (its pixels keep id 0 and show the background) and the frame says so once.
#[derive(Debug, Default)]
pub(crate) struct VisibilityIds {
    next: u64,
    warned: bool,
}

impl VisibilityIds {
    /// Starts a frame.
    pub(crate) fn reset(&mut self) {
        self.next = 1;
    }

    /// The first of `count` consecutive ids, or `None` when the frame has run out.
    pub(crate) fn allocate(&mut self, count: u64) -> Option<u32> {
        let first = self.next.max(1);
        let end = first + count;
        if end > u64::from(u32::MAX) {
            if !self.warned {
                log::error!(
                    "a deferred frame needs more than {} visibility ids (one per triangle per draw): some draws are left out",
                    u32::MAX
                );
                self.warned = true;
            }
            return None;
        }
        self.next = end;
        u32::try_from(first).ok()
    }
}

/// The visibility buffer of one target, made on the first deferred frame and kept.
#[derive(Debug)]
pub(crate) struct VisibilityBuffer {
    /// One [`VISIBILITY_BYTES_PER_PIXEL`] key per pixel, row by row (cleared before each
    /// visibility pass: 0 is "no draw"), then as many candidate keys (`DrawPhase::Candidates`),
    /// cleared on frames that have candidates and on the next (every resolve reads them).
    pub(crate) keys: wgpu::Buffer,
    /// Whether the candidate keys may hold a candidate.
    candidates_written: std::cell::Cell<bool>,
    /// The [`RenderTarget::id`] it was made for.
    pub(crate) target: u64,
    /// The clear's pipeline and its bind group over `keys`.
    clear: (wgpu::ComputePipeline, wgpu::BindGroup),
    /// The settled depth as an image, made on the first frame that reads it.
    settled_depth: Option<settled_depth::SettledDepthImage>,
    /// Its pipeline, compiled with the first image and kept through resizes.
    settled_depth_pipeline: Option<wgpu::ComputePipeline>,
}

impl VisibilityBuffer {
    pub(crate) fn new(gpu: &GpuContext, target: &RenderTarget) -> Self {
        let module = VISIBILITY_CLEAR_SHADER.create_module(&gpu.device);
        let pipeline = gpu
            .device
            .create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                label: Some("visibility clear"),
                layout: None,
                module: &module,
                entry_point: Some("cs_clear_visibility"),
                compilation_options: Default::default(),
                cache: None,
            });
        Self::with_clear(gpu, target, pipeline)
    }

    /// The buffer of `target`, cleared by `pipeline` (compiled once per device: a resize makes a
    /// new buffer and keeps it).
    fn with_clear(
        gpu: &GpuContext,
        target: &RenderTarget,
        pipeline: wgpu::ComputePipeline,
    ) -> Self {
        let keys = gpu.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("visibility buffer"),
            size: 2 * visibility_bytes(target),
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let bind_group = gpu.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("visibility clear"),
            layout: &pipeline.get_bind_group_layout(0),
            entries: &[wgpu::BindGroupEntry {
                binding: 0,
                resource: keys.as_entire_binding(),
            }],
        });
        Self {
            keys,
            candidates_written: std::cell::Cell::new(true),
            target: target.id(),
            clear: (pipeline, bind_group),
            settled_depth: None,
            settled_depth_pipeline: None,
        }
    }

    /// Records the clear of every key to 0 ("no draw"), the candidate keys too where this frame
    /// (`candidates`) or the last had some, then the `polygons` pass where the frame runs it,
    /// as a compute pass that begins `time`'s span (and `ends_span`: ends it too).
    pub(crate) fn record_clear(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        time: Option<&PassTimestamps>,
        candidates: bool,
        polygons: Option<&VisiblePolygons>,
        ends_span: bool,
    ) {
        let written = self.candidates_written.replace(candidates);
        let halves = 1 + u64::from(candidates || written);
        let keys = self.keys.size() / 2 * halves / VISIBILITY_BYTES_PER_PIXEL;
        let groups = keys.div_ceil(CLEAR_GROUP_SIZE);
        let across = groups.clamp(1, MAX_GROUPS_ACROSS);
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("visibility clear"),
            timestamp_writes: time.map(|time| time.compute_part(true, ends_span)),
        });
        pass.set_pipeline(&self.clear.0);
        pass.set_bind_group(0, &self.clear.1, &[]);
        // Both fit in u32: `keys` is bound as one storage buffer.
        pass.dispatch_workgroups(across as u32, groups.div_ceil(across) as u32, 1);
        if let Some(polygons) = polygons {
            polygons.record(&mut pass);
        }
    }

    /// Makes the settled depth's image for `target` (this frame writes it), unless made.
    pub(crate) fn prepare_settled_depth(&mut self, gpu: &GpuContext, target: &RenderTarget) {
        if self
            .settled_depth
            .as_ref()
            .is_some_and(|image| image.fits(target))
        {
            return;
        }
        let pipeline = self
            .settled_depth_pipeline
            .get_or_insert_with(|| settled_depth::settled_depth_pipeline(gpu));
        self.settled_depth = Some(settled_depth::SettledDepthImage::new(
            gpu,
            target,
            pipeline.clone(),
            &self.keys,
        ));
    }

    /// The settled depth's image, once a frame has needed it.
    pub(crate) fn settled_depth_view(&self) -> Option<&wgpu::TextureView> {
        self.settled_depth.as_ref().map(|image| image.view())
    }

    /// Records the settled depth's pass into `pass`, after the resolve's dispatches.
    pub(crate) fn record_settled_depth(&self, pass: &mut wgpu::ComputePass<'_>) {
        if let Some(image) = &self.settled_depth {
            image.record(pass);
        }
    }

    /// Serves `target` too: a target of the same size (the split view swaps two each frame)
    /// reuses the buffer instead of a new allocation.
    pub(crate) fn follow(&mut self, gpu: &GpuContext, target: &RenderTarget) {
        if self.target == target.id() {
            return;
        }
        if self.keys.size() == 2 * visibility_bytes(target) {
            self.target = target.id();
        } else {
            // The settled depth's pipeline stays for the image of the new size.
            let settled_depth_pipeline = self.settled_depth_pipeline.take();
            *self = Self::with_clear(gpu, target, self.clear.0.clone());
            self.settled_depth_pipeline = settled_depth_pipeline;
        }
    }
}

/// The bytes of `target`'s visibility keys (the buffer holds as many candidate keys after them).
pub(crate) fn visibility_bytes(target: &RenderTarget) -> u64 {
    let (width, height) = target.size();
    u64::from(width) * u64::from(height) * VISIBILITY_BYTES_PER_PIXEL
}

/// Whether the device can hold and bind `target`'s visibility buffer.
pub(crate) fn visibility_fits(gpu: &GpuContext, target: &RenderTarget) -> bool {
    gpu.storage_buffer_fits(2 * visibility_bytes(target))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn visibility_ids_are_handed_out_in_runs_from_one_until_they_run_out() {
        let mut ids = VisibilityIds::default();
        ids.reset();
        assert_eq!(ids.allocate(6), Some(1));
        assert_eq!(ids.allocate(2), Some(7));
        assert_eq!(ids.allocate(u64::from(u32::MAX)), None);
        assert_eq!(ids.allocate(1), Some(9));
        ids.reset();
        assert_eq!(ids.allocate(1), Some(1));
    }
}
