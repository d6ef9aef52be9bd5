//! The per-frame camera and light uniform buffer that every main-pass pipeline binds at
//! group 0, binding 0.

use bytemuck::Zeroable;
use wgpu::util::DeviceExt;

use super::GpuContext;
use super::gpu_types::FrameUniform;

/// The frame uniform on the GPU, rewritten only when the camera or lights change.
#[derive(Debug)]
pub struct FrameUniformBuffer {
    buffer: wgpu::Buffer,
    uploaded: Option<FrameUniform>,
}

impl FrameUniformBuffer {
    /// The byte size of [`FrameUniform`], for bind group layouts.
    pub const SIZE: u64 = std::mem::size_of::<FrameUniform>() as u64;

    /// Creates the buffer, zeroed.
    pub fn new(gpu: &GpuContext) -> Self {
        Self {
            buffer: gpu
                .device
                .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                    label: Some("frame uniform"),
                    contents: bytemuck::bytes_of(&FrameUniform::zeroed()),
                    usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
                }),
            uploaded: None,
        }
    }

    /// The buffer; it is never replaced, so bind groups may keep it.
    pub fn buffer(&self) -> &wgpu::Buffer {
        &self.buffer
    }

    /// Writes `frame` if it differs from the last upload; returns the bytes written.
    pub fn upload(&mut self, gpu: &GpuContext, frame: &FrameUniform) -> u64 {
        if self.uploaded.as_ref() == Some(frame) {
            return 0;
        }
        gpu.queue
            .write_buffer(&self.buffer, 0, bytemuck::bytes_of(frame));
        self.uploaded = Some(*frame);
        Self::SIZE
    }

    /// The layout entry for binding 0 of a pass's group 0.
    pub fn layout_entry() -> wgpu::BindGroupLayoutEntry {
        wgpu::BindGroupLayoutEntry {
            binding: 0,
            visibility: wgpu::ShaderStages::VERTEX_FRAGMENT,
            ty: wgpu::BindingType::Buffer {
                ty: wgpu::BufferBindingType::Uniform,
                has_dynamic_offset: false,
                min_binding_size: wgpu::BufferSize::new(Self::SIZE),
            },
            count: None,
        }
    }
}
