//! The per-frame camera and light uniform buffer that every mesh pipeline binds at group 0,
//! binding 0 with a dynamic offset: slot 0 holds the camera's view, the next slots the shadow
//! maps' views (the same frame seen from a light), so one bind group serves every pass.

use bytemuck::Zeroable;

use super::gpu_types::FrameUniform;
use super::shadow_maps::MAX_SHADOW_VIEWS;
use crate::gpu::GpuContext;

/// The frame uniform on the GPU, each slot rewritten only when it changes.
#[derive(Debug)]
pub struct FrameUniformBuffer {
    buffer: wgpu::Buffer,
    /// Bytes from one slot to the next (the device's uniform offset alignment).
    stride: u64,
    uploaded: Vec<FrameUniform>,
}

impl FrameUniformBuffer {
    /// The byte size of [`FrameUniform`], for bind group layouts.
    pub const SIZE: u64 = std::mem::size_of::<FrameUniform>() as u64;
    /// Slots: the camera's and one per shadow map.
    pub const SLOTS: usize = 1 + MAX_SHADOW_VIEWS;

    /// Creates the buffer, zeroed.
    pub fn new(gpu: &GpuContext) -> Self {
        let alignment = u64::from(gpu.device.limits().min_uniform_buffer_offset_alignment);
        let stride = Self::SIZE.div_ceil(alignment) * alignment;
        Self {
            buffer: gpu.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("frame uniform"),
                size: stride * Self::SLOTS as u64,
                usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            }),
            stride,
            uploaded: vec![FrameUniform::zeroed(); Self::SLOTS],
        }
    }

    /// The binding of one slot (bound with [`FrameUniformBuffer::offset`] as dynamic offset);
    /// the buffer is never replaced, so bind groups may keep it.
    pub fn binding(&self) -> wgpu::BindingResource<'_> {
        wgpu::BindingResource::Buffer(wgpu::BufferBinding {
            buffer: &self.buffer,
            offset: 0,
            size: wgpu::BufferSize::new(Self::SIZE),
        })
    }

    /// The dynamic offset of `slot` (0: the camera; 1 + i: shadow map i).
    pub fn offset(&self, slot: u32) -> u32 {
        (u64::from(slot) * self.stride) as u32
    }

    /// Writes the slots that differ from the last upload: `camera` into slot 0, `views` into
    /// the next ones (at most [`MAX_SHADOW_VIEWS`]); returns the bytes written.
    pub fn upload(
        &mut self,
        gpu: &GpuContext,
        camera: &FrameUniform,
        views: &[FrameUniform],
    ) -> u64 {
        let mut written = 0;
        for (slot, frame) in std::iter::once(camera)
            .chain(views.iter().take(MAX_SHADOW_VIEWS))
            .enumerate()
        {
            if self.uploaded[slot] == *frame {
                continue;
            }
            gpu.write_buffer(
                &self.buffer,
                slot as u64 * self.stride,
                bytemuck::bytes_of(frame),
            );
            self.uploaded[slot] = *frame;
            written += Self::SIZE;
        }
        written
    }

    /// The layout entry of the frame in a pass's group 0 ([`super::frame_group::FRAME`]).
    pub fn layout_entry() -> wgpu::BindGroupLayoutEntry {
        wgpu::BindGroupLayoutEntry {
            binding: super::frame_group::FRAME,
            visibility: wgpu::ShaderStages::VERTEX_FRAGMENT.union(wgpu::ShaderStages::COMPUTE),
            ty: wgpu::BindingType::Buffer {
                ty: wgpu::BufferBindingType::Uniform,
                has_dynamic_offset: true,
                min_binding_size: wgpu::BufferSize::new(Self::SIZE),
            },
            count: None,
        }
    }
}
