//! GPU pass timing with timestamp queries: a [`GpuTimer`] hands each pass its
//! `timestamp_writes`, resolves the queries after the frame and publishes the durations in the
//! [`GpuTimings`] resource.
//!
//! The resolve and the copy to a mappable buffer go in a separate submission after the frame's
//! passes: on Vulkan a copy recorded in the same encoder as the timestamps can read zeros. Pairs
//! whose end is zero or not after their begin are rejected rather than reported as 0 ms.

use std::collections::BTreeMap;
use std::sync::Arc;
use std::sync::atomic::{AtomicU8, Ordering};
use std::time::Duration;

use crate::gpu::GpuContext;
use crate::{AppError, Resources};

/// Timestamp pairs one frame can hold (passes timed per frame, at most).
pub const MAX_TIMED_PASSES: u32 = 32;
/// Readback buffers in the non-blocking ring: how many frames may be in flight unread.
const READBACK_RING: usize = 4;
const BLOCKING_TIMEOUT: Duration = Duration::from_secs(60);

/// How the timer waits for the GPU's answers.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
#[non_exhaustive]
pub enum TimingMode {
    /// Never stall: read a frame or more late from a ring of readback buffers; a frame whose
    /// buffers are all still busy is simply not timed. For live windows.
    #[default]
    NonBlocking,
    /// Wait for each frame's timestamps before the Render stage ends. For benchmarks.
    Blocking,
}

/// The latest per-pass GPU durations. A resource, always present after [`crate::render::RenderPlugin`].
///
/// # Example
/// ```no_run
/// # fn main() -> Result<(), Box<dyn std::error::Error>> {
/// let mut app = pom::App::new();
/// app.add_plugin(pom::RenderPlugin::new(64, 64));
/// for _ in 0..4 {
///     app.update()?;
/// }
/// match app.resources.get::<pom::GpuTimings>() {
///     Some(pom::GpuTimings::Supported { passes, .. }) => {
///         for (pass, ms) in passes {
///             println!("{pass}: {ms:.3} ms");
///         }
///     }
///     _ => println!("GPU timing unsupported by this adapter"),
/// }
/// # Ok(()) }
/// ```
#[derive(Clone, Debug, PartialEq)]
pub enum GpuTimings {
    /// The adapter has no `TIMESTAMP_QUERY` (or timing was turned off): no figures will come.
    Unsupported,
    /// Timing works; `passes` holds the newest complete reading.
    Supported {
        /// Milliseconds per pass name ("main pass", "sobel pass", ...); passes sharing a name in
        /// one frame are summed. Empty until the first frame's timestamps are read.
        passes: BTreeMap<String, f64>,
        /// The frame number ([`GpuTimer`]'s count of Render stages) those figures belong to.
        frame: u64,
        /// Pairs rejected so far because their end was zero or not after their begin.
        rejected: u64,
    },
}

impl GpuTimings {
    /// The frame number of the newest reading (`None` before the first, or without timing):
    /// a reader that sees it unchanged after a frame knows that frame gave no reading.
    pub fn reading_frame(&self) -> Option<u64> {
        match self {
            Self::Supported { passes, frame, .. } if !passes.is_empty() => Some(*frame),
            _ => None,
        }
    }

    /// The milliseconds of the pass named `name` in the newest reading, if any.
    pub fn pass_ms(&self, name: &str) -> Option<f64> {
        match self {
            Self::Supported { passes, .. } => passes.get(name).copied(),
            Self::Unsupported => None,
        }
    }
}

/// The query indices one pass writes, with the query set they live in.
#[derive(Clone, Debug)]
pub struct PassTimestamps {
    query_set: wgpu::QuerySet,
    begin: u32,
}

impl PassTimestamps {
    /// The `timestamp_writes` for a render pass.
    pub fn render(&self) -> wgpu::RenderPassTimestampWrites<'_> {
        wgpu::RenderPassTimestampWrites {
            query_set: &self.query_set,
            beginning_of_pass_write_index: Some(self.begin),
            end_of_pass_write_index: Some(self.begin + 1),
        }
    }

    /// The `timestamp_writes` for one of several render passes timed as one span: the first
    /// writes the beginning, the last the end.
    pub fn render_part(&self, first: bool, last: bool) -> wgpu::RenderPassTimestampWrites<'_> {
        wgpu::RenderPassTimestampWrites {
            query_set: &self.query_set,
            beginning_of_pass_write_index: first.then_some(self.begin),
            end_of_pass_write_index: last.then_some(self.begin + 1),
        }
    }

    /// The `timestamp_writes` for a compute pass.
    pub fn compute(&self) -> wgpu::ComputePassTimestampWrites<'_> {
        self.compute_part(true, true)
    }

    /// The `timestamp_writes` for a compute pass that is one of several passes timed as one
    /// span: the first writes the beginning, the last the end.
    pub fn compute_part(&self, first: bool, last: bool) -> wgpu::ComputePassTimestampWrites<'_> {
        wgpu::ComputePassTimestampWrites {
            query_set: &self.query_set,
            beginning_of_pass_write_index: first.then_some(self.begin),
            end_of_pass_write_index: last.then_some(self.begin + 1),
        }
    }
}

// Readback slot states, shared with the map callback.
const SLOT_FREE: u8 = 0;
const SLOT_MAPPING: u8 = 1;
const SLOT_MAPPED: u8 = 2;
const SLOT_FAILED: u8 = 3;

struct ReadbackSlot {
    buffer: wgpu::Buffer,
    state: Arc<AtomicU8>,
    names: Vec<String>,
    frame: u64,
}

/// Timestamp queries for the passes of one frame. A resource; systems call
/// [`GpuTimer::pass`] before opening a pass, and [`resolve_gpu_timings`] ends the frame.
pub struct GpuTimer {
    query_set: wgpu::QuerySet,
    resolve: wgpu::Buffer,
    ring: Vec<ReadbackSlot>,
    names: Vec<String>,
    mode: TimingMode,
    period_ns: f64,
    frame: u64,
}

impl std::fmt::Debug for GpuTimer {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("GpuTimer")
            .field("mode", &self.mode)
            .field("period_ns", &self.period_ns)
            .field("frame", &self.frame)
            .finish()
    }
}

impl GpuTimer {
    /// A timer, or `None` when the device was created without `TIMESTAMP_QUERY`.
    pub fn new(gpu: &GpuContext, mode: TimingMode) -> Option<Self> {
        if !gpu
            .device
            .features()
            .contains(wgpu::Features::TIMESTAMP_QUERY)
        {
            return None;
        }
        let device = &gpu.device;
        let query_set = device.create_query_set(&wgpu::QuerySetDescriptor {
            label: Some("pass timestamps"),
            ty: wgpu::QueryType::Timestamp,
            count: MAX_TIMED_PASSES * 2,
        });
        let bytes = u64::from(MAX_TIMED_PASSES) * 2 * wgpu::QUERY_SIZE as u64;
        let resolve = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("timestamp resolve"),
            size: bytes,
            usage: wgpu::BufferUsages::QUERY_RESOLVE | wgpu::BufferUsages::COPY_SRC,
            mapped_at_creation: false,
        });
        let slots = match mode {
            TimingMode::NonBlocking => READBACK_RING,
            TimingMode::Blocking => 1,
        };
        let ring = (0..slots)
            .map(|_| ReadbackSlot {
                buffer: device.create_buffer(&wgpu::BufferDescriptor {
                    label: Some("timestamp readback"),
                    size: bytes,
                    usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
                    mapped_at_creation: false,
                }),
                state: Arc::new(AtomicU8::new(SLOT_FREE)),
                names: Vec::new(),
                frame: 0,
            })
            .collect();
        Some(Self {
            query_set,
            resolve,
            ring,
            names: Vec::new(),
            mode,
            period_ns: f64::from(gpu.queue.get_timestamp_period()),
            frame: 0,
        })
    }

    /// The mode the timer was made with.
    pub fn mode(&self) -> TimingMode {
        self.mode
    }

    /// Reserves a timestamp pair for a pass named `name` in this frame; `None` when the frame
    /// already times `MAX_TIMED_PASSES` passes (the pass then runs untimed).
    pub fn pass(&mut self, name: &str) -> Option<PassTimestamps> {
        let index = u32::try_from(self.names.len()).ok()?;
        if index >= MAX_TIMED_PASSES {
            return None;
        }
        self.names.push(name.to_owned());
        Some(PassTimestamps {
            query_set: self.query_set.clone(),
            begin: index * 2,
        })
    }

    /// Ends the frame: submits the resolve and copy of this frame's queries (a separate
    /// submission), and returns the newest reading that is ready, if any.
    fn end_frame(&mut self, gpu: &GpuContext, timings: &mut GpuTimings) {
        self.frame += 1;
        self.collect_ready(&gpu.device, timings);
        let names = std::mem::take(&mut self.names);
        if names.is_empty() {
            return;
        }
        let Some(slot) = self
            .ring
            .iter_mut()
            .find(|slot| slot.state.load(Ordering::Acquire) == SLOT_FREE)
        else {
            // Every readback buffer is still in flight: skip this frame rather than stall.
            return;
        };
        let queries = u32::try_from(names.len() * 2).unwrap_or(MAX_TIMED_PASSES * 2);
        let mut encoder = gpu
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("timestamp resolve encoder"),
            });
        encoder.resolve_query_set(&self.query_set, 0..queries, &self.resolve, 0);
        let bytes = u64::from(queries) * wgpu::QUERY_SIZE as u64;
        encoder.copy_buffer_to_buffer(&self.resolve, 0, &slot.buffer, 0, bytes);
        let submission = gpu.queue.submit([encoder.finish()]);
        slot.names = names;
        slot.frame = self.frame;
        slot.state.store(SLOT_MAPPING, Ordering::Release);
        let state = Arc::clone(&slot.state);
        slot.buffer
            .map_async(wgpu::MapMode::Read, ..bytes, move |result| {
                let next = if result.is_ok() {
                    SLOT_MAPPED
                } else {
                    SLOT_FAILED
                };
                state.store(next, Ordering::Release);
            });
        let poll = match self.mode {
            TimingMode::NonBlocking => wgpu::PollType::Poll,
            TimingMode::Blocking => wgpu::PollType::Wait {
                submission_index: Some(submission),
                timeout: Some(BLOCKING_TIMEOUT),
            },
        };
        if let Err(error) = gpu.device.poll(poll) {
            log::warn!("GPU timing: polling the device failed: {error}");
        }
        self.collect_ready(&gpu.device, timings);
    }

    // Reads every mapped slot, oldest frame first, so `timings` ends at the newest.
    fn collect_ready(&mut self, device: &wgpu::Device, timings: &mut GpuTimings) {
        let mut ready: Vec<usize> = (0..self.ring.len())
            .filter(|&i| {
                matches!(
                    self.ring[i].state.load(Ordering::Acquire),
                    SLOT_MAPPED | SLOT_FAILED
                )
            })
            .collect();
        ready.sort_by_key(|&i| self.ring[i].frame);
        for index in ready {
            let slot = &mut self.ring[index];
            if slot.state.load(Ordering::Acquire) == SLOT_MAPPED {
                let reading = read_slot(slot, self.period_ns);
                // A device lost since the map destroyed the buffer with it; unmapping it then is
                // an error of no consequence, kept out of the uncaptured errors.
                let scope = device.push_error_scope(wgpu::ErrorFilter::Validation);
                slot.buffer.unmap();
                let _ = pollster::block_on(scope.pop());
                if let GpuTimings::Supported {
                    passes,
                    frame,
                    rejected,
                } = timings
                    && slot.frame >= *frame
                {
                    *rejected += reading.rejected;
                    if !reading.passes.is_empty() {
                        *passes = reading.passes;
                        *frame = slot.frame;
                    }
                }
            } else {
                log::warn!("GPU timing: mapping a readback buffer failed");
            }
            slot.state.store(SLOT_FREE, Ordering::Release);
        }
    }
}

struct Reading {
    passes: BTreeMap<String, f64>,
    rejected: u64,
}

fn read_slot(slot: &ReadbackSlot, period_ns: f64) -> Reading {
    let mut reading = Reading {
        passes: BTreeMap::new(),
        rejected: 0,
    };
    let bytes = (slot.names.len() * 2 * wgpu::QUERY_SIZE as usize) as u64;
    let Ok(mapped) = slot.buffer.get_mapped_range(..bytes) else {
        return reading;
    };
    let ticks: Vec<u64> = bytemuck::pod_collect_to_vec(&mapped);
    for (name, pair) in slot.names.iter().zip(ticks.chunks_exact(2)) {
        match pass_milliseconds(pair[0], pair[1], period_ns) {
            Some(ms) => *reading.passes.entry(name.clone()).or_insert(0.0) += ms,
            None => reading.rejected += 1,
        }
    }
    reading
}

/// Milliseconds between two raw timestamps, or `None` for a zero or non-increasing pair
/// (a timestamp the driver never wrote, or a reading from the wrong submission).
pub fn pass_milliseconds(begin: u64, end: u64, period_ns: f64) -> Option<f64> {
    if begin == 0 || end <= begin {
        return None;
    }
    let ms = (end - begin) as f64 * period_ns / 1.0e6;
    (ms.is_finite() && ms > 0.0).then_some(ms)
}

/// Reserves a timestamp pair named `name` from the app's [`GpuTimer`], if timing is on.
pub fn time_pass(resources: &mut Resources, name: &str) -> Option<PassTimestamps> {
    resources.get_mut::<GpuTimer>()?.pass(name)
}

/// The Render stage's last system: resolves this frame's timestamps in their own submission
/// and updates [`GpuTimings`]. Does nothing when timing is off.
pub fn resolve_gpu_timings(_: &mut hecs::World, resources: &mut Resources) -> Result<(), AppError> {
    if !resources.contains::<GpuTimer>() {
        return Ok(());
    }
    if !resources.contains::<GpuTimings>() {
        resources.insert(GpuTimings::Supported {
            passes: BTreeMap::new(),
            frame: 0,
            rejected: 0,
        });
    }
    resources.scope(|resources, timer: &mut GpuTimer| {
        resources.scope(|resources, timings: &mut GpuTimings| {
            if let Some(gpu) = resources.get::<GpuContext>() {
                timer.end_frame(gpu, timings);
            }
        })
    });
    Ok(())
}

/// Turns GPU timing on in `mode` (or off with `None`) for an app whose [`crate::render::RenderPlugin`]
/// has finished; returns whether timing is now on. Without adapter support it stays off and
/// [`GpuTimings::Unsupported`] says so.
pub fn set_gpu_timing(resources: &mut Resources, mode: Option<TimingMode>) -> bool {
    resources.remove::<GpuTimer>();
    let timer = match (mode, resources.get::<GpuContext>()) {
        (Some(mode), Some(gpu)) => GpuTimer::new(gpu, mode),
        _ => None,
    };
    let on = timer.is_some();
    match timer {
        Some(timer) => {
            resources.insert(timer);
            resources.insert(GpuTimings::Supported {
                passes: BTreeMap::new(),
                frame: 0,
                rejected: 0,
            });
        }
        None => {
            resources.insert(GpuTimings::Unsupported);
        }
    }
    on
}

#[cfg(test)]
mod tests {
    use super::pass_milliseconds;

    #[test]
    fn rejects_zero_and_non_increasing_pairs() {
        assert_eq!(pass_milliseconds(0, 10, 1.0), None);
        assert_eq!(pass_milliseconds(10, 10, 1.0), None);
        assert_eq!(pass_milliseconds(10, 5, 1.0), None);
        assert_eq!(pass_milliseconds(1_000, 3_000_000, 1.0), Some(2.999));
        assert_eq!(pass_milliseconds(1, 1_000_001, 2.0), Some(2.0));
    }
}
