//! Memory as the operating system and wgpu see it: the process's resident set, and the GPU
//! objects wgpu holds alive, for tests that a long run leaves nothing behind frame after frame.

use pom::{App, GpuContext};

/// The process's resident memory in KiB (`VmRSS` of /proc/self/status), or `None` where the
/// system has no such file.
pub fn resident_kib() -> Option<u64> {
    resident_kib_of("self")
}

/// The resident memory in KiB of process `pid` ("self" for this one), from /proc.
pub fn resident_kib_of(pid: &str) -> Option<u64> {
    let status = std::fs::read_to_string(format!("/proc/{pid}/status")).ok()?;
    status
        .lines()
        .find_map(|line| line.strip_prefix("VmRSS:"))
        .and_then(|value| value.trim().trim_end_matches("kB").trim().parse().ok())
}

/// The live GPU objects an app could leak. Textures are counted by their memory: wgpu-hal's
/// texture count is not raised on Vulkan when a texture is made, its texture memory is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct LiveObjects {
    /// Live buffers.
    pub buffers: isize,
    /// Bytes of live textures.
    pub texture_memory: isize,
    /// Bytes of live buffers.
    pub buffer_memory: isize,
    /// Live texture views.
    pub texture_views: isize,
    /// Live bind groups.
    pub bind_groups: isize,
    /// Live render and compute pipelines.
    pub pipelines: isize,
    /// Live samplers.
    pub samplers: isize,
}

/// The live GPU objects of `app`, counted with the GPU idle: objects dropped while a
/// submission used them are freed only once it is done.
pub fn live_objects(app: &App) -> LiveObjects {
    let gpu = app
        .resources
        .get::<GpuContext>()
        .expect("a finished app has its GPU context");
    gpu.device
        .poll(pom::wgpu::PollType::wait_indefinitely())
        .expect("the device answers a poll");
    let counters = gpu.device.get_internal_counters().hal;
    LiveObjects {
        buffers: counters.buffers.read(),
        texture_memory: counters.texture_memory.read(),
        buffer_memory: counters.buffer_memory.read(),
        texture_views: counters.texture_views.read(),
        bind_groups: counters.bind_groups.read(),
        pipelines: counters.render_pipelines.read() + counters.compute_pipelines.read(),
        samplers: counters.samplers.read(),
    }
}

/// Resident memory at two points of a long run, and whether it stayed within `tolerance` (a
/// fraction: 0.05 is 5 %) of the first.
#[derive(Clone, Copy, Debug)]
pub struct ResidentGrowth {
    /// KiB resident at the first point.
    pub early_kib: u64,
    /// KiB resident at the second point.
    pub late_kib: u64,
}

impl ResidentGrowth {
    /// Whether the late figure is within `tolerance` (a fraction) above the early one.
    pub fn within(&self, tolerance: f64) -> bool {
        self.late_kib as f64 <= self.early_kib as f64 * (1.0 + tolerance)
    }

    /// Bytes gained per frame over `frames` frames between the two points.
    pub fn bytes_per_frame(&self, frames: u64) -> f64 {
        (self.late_kib as f64 - self.early_kib as f64) * 1024.0 / frames as f64
    }
}
