//! [`FragmentInvocationCounter`]: how many times fragment shaders ran, for tests that prove
//! hidden pixels are not shaded.

use std::time::Duration;

use super::{CaptureError, GpuContext};

/// Counts the fragment-shader invocations of every material entry point that calls
/// `count_fragment_invocation()`: the parallax material's opaque-phase entry points, and on
/// the deferred path every merge into the visibility buffer (`keep_visible`), so a test sees
/// what the visibility pass did for hidden surfaces.
/// Insert it before the app's plugins finish: material plugins then compile their shaders with
/// the counting variant. A resource; for tests and measurements, not for games (an atomic per
/// pixel costs time).
#[doc(hidden)] // A test and measurement hook.
#[derive(Debug)]
pub struct FragmentInvocationCounter {
    buffer: wgpu::Buffer,
    readback: wgpu::Buffer,
}

impl FragmentInvocationCounter {
    /// A counter at zero.
    pub fn new(gpu: &GpuContext) -> Self {
        let buffer = gpu.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("fragment invocation counter"),
            size: 4,
            usage: wgpu::BufferUsages::STORAGE
                | wgpu::BufferUsages::COPY_SRC
                | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let readback = gpu.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("fragment invocation readback"),
            size: 4,
            usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
            mapped_at_creation: false,
        });
        gpu.write_buffer(&buffer, 0, &[0; 4]);
        Self { buffer, readback }
    }

    /// The storage buffer materials bind at group 0, binding 4.
    pub fn buffer(&self) -> &wgpu::Buffer {
        &self.buffer
    }

    /// Sets the count back to zero (before the next frame's submission).
    pub fn reset(&self, gpu: &GpuContext) {
        gpu.write_buffer(&self.buffer, 0, &[0; 4]);
    }

    /// The invocations counted since the last reset, once the GPU has finished.
    pub fn read(&self, gpu: &GpuContext) -> Result<u32, CaptureError> {
        let mut encoder = gpu
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("fragment invocation readback"),
            });
        encoder.copy_buffer_to_buffer(&self.buffer, 0, &self.readback, 0, 4);
        let submission = gpu.queue.submit([encoder.finish()]);
        let (sender, receiver) = std::sync::mpsc::channel();
        self.readback
            .map_async(wgpu::MapMode::Read, .., move |result| {
                let _ = sender.send(result);
            });
        gpu.device.poll(wgpu::PollType::Wait {
            submission_index: Some(submission),
            timeout: Some(Duration::from_secs(120)),
        })?;
        receiver
            .recv()
            .map_err(|_| CaptureError::Map("the map callback never ran".into()))?
            .map_err(|error| CaptureError::Map(error.to_string()))?;
        let count = {
            let mapped = self
                .readback
                .get_mapped_range(..)
                .map_err(|error| CaptureError::Map(error.to_string()))?;
            u32::from_le_bytes([mapped[0], mapped[1], mapped[2], mapped[3]])
        };
        self.readback.unmap();
        Ok(count)
    }
}
