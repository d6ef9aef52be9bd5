//! A storage buffer of per-draw structs that re-uploads only the entries that changed.

use bytemuck::Pod;

use super::GpuContext;

/// An array of `T` on the GPU, rewritten each frame by [`ObjectBuffer::upload`], which writes
/// only the runs of entries that differ from the last upload.
#[derive(Debug)]
pub struct ObjectBuffer<T> {
    label: &'static str,
    buffer: wgpu::Buffer,
    uploaded: Vec<T>,
}

impl<T: Pod + PartialEq> ObjectBuffer<T> {
    const ENTRY_SIZE: u64 = std::mem::size_of::<T>() as u64;

    /// An empty buffer with room for `capacity` entries.
    pub fn new(gpu: &GpuContext, label: &'static str, capacity: u64) -> Self {
        Self {
            label,
            buffer: Self::create(gpu, label, capacity),
            uploaded: Vec::new(),
        }
    }

    fn create(gpu: &GpuContext, label: &str, capacity: u64) -> wgpu::Buffer {
        gpu.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some(label),
            size: capacity.max(1) * Self::ENTRY_SIZE,
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        })
    }

    /// The layout entry of a read-only storage binding of this array, for both shader stages.
    pub fn layout_entry(binding: u32) -> wgpu::BindGroupLayoutEntry {
        wgpu::BindGroupLayoutEntry {
            binding,
            visibility: wgpu::ShaderStages::VERTEX_FRAGMENT.union(wgpu::ShaderStages::COMPUTE),
            ty: wgpu::BindingType::Buffer {
                ty: wgpu::BufferBindingType::Storage { read_only: true },
                has_dynamic_offset: false,
                min_binding_size: wgpu::BufferSize::new(Self::ENTRY_SIZE),
            },
            count: None,
        }
    }

    /// The buffer, for bind groups. It is replaced when it grows: see [`ObjectBuffer::upload`].
    pub fn buffer(&self) -> &wgpu::Buffer {
        &self.buffer
    }

    /// Makes the GPU copy equal `entries`. Returns the bytes written and whether the buffer was
    /// replaced by a larger one (bind groups that use it must then be rebuilt).
    pub fn upload(&mut self, gpu: &GpuContext, entries: &[T]) -> (u64, bool) {
        let capacity = self.buffer.size() / Self::ENTRY_SIZE;
        let grew = entries.len() as u64 > capacity;
        if grew {
            let new_capacity = (entries.len() as u64).next_power_of_two();
            self.buffer = Self::create(gpu, self.label, new_capacity);
            // The new buffer holds nothing yet.
            self.uploaded.clear();
        }
        // Write each run of consecutive changed entries with one call.
        let mut written = 0;
        let mut index = 0;
        while index < entries.len() {
            if self.uploaded.get(index) == Some(&entries[index]) {
                index += 1;
                continue;
            }
            let start = index;
            while index < entries.len() && self.uploaded.get(index) != Some(&entries[index]) {
                index += 1;
            }
            let bytes: &[u8] = bytemuck::cast_slice(&entries[start..index]);
            gpu.queue
                .write_buffer(&self.buffer, start as u64 * Self::ENTRY_SIZE, bytes);
            written += bytes.len() as u64;
        }
        self.uploaded.clear();
        self.uploaded.extend_from_slice(entries);
        (written, grew)
    }
}
