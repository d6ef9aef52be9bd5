//! A storage buffer of per-draw structs that re-uploads only the entries that changed.

use std::ops::Range;

use bytemuck::Pod;

use super::GpuContext;

/// The longest run of unchanged bytes an upload writes again rather than start another write.
const MERGE_GAP_BYTES: u64 = 4096;

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
        let merge_gap = (MERGE_GAP_BYTES / Self::ENTRY_SIZE.max(1)) as usize;
        let runs = changed_runs(&self.uploaded, entries, merge_gap);
        // The copy mirrors only what changed: entries past the old end are all in runs.
        self.uploaded.resize(entries.len(), T::zeroed());
        let mut written = 0;
        for run in runs {
            let changed = &entries[run.clone()];
            let bytes: &[u8] = bytemuck::cast_slice(changed);
            gpu.queue
                .write_buffer(&self.buffer, run.start as u64 * Self::ENTRY_SIZE, bytes);
            written += bytes.len() as u64;
            self.uploaded[run].copy_from_slice(changed);
        }
        (written, grew)
    }
}

/// The runs of `entries` that differ from `uploaded` (an entry past its end differs), each to
/// be written with one call: unchanged gaps of up to `merge_gap` entries are written again
/// inside a run, because a write call costs far more than copying a few KiB (a tenth of the
/// draws moving, scattered, made a call each, and their frame was slower than all of them
/// moving: sandbox/BENCHMARKS.md, "CPU side").
fn changed_runs<T: PartialEq>(
    uploaded: &[T],
    entries: &[T],
    merge_gap: usize,
) -> Vec<Range<usize>> {
    let changed = |index: usize| uploaded.get(index) != Some(&entries[index]);
    let mut runs: Vec<Range<usize>> = Vec::new();
    for index in (0..entries.len()).filter(|&index| changed(index)) {
        match runs.last_mut() {
            Some(run) if index - run.end <= merge_gap => run.end = index + 1,
            _ => runs.push(index..index + 1),
        }
    }
    runs
}

#[cfg(test)]
mod tests {
    use super::changed_runs;

    #[test]
    fn changed_entries_are_written_in_runs_that_take_in_short_gaps() {
        let uploaded = [0, 0, 0, 0, 0, 0, 0, 0];
        let entries = [1, 0, 1, 0, 0, 0, 1, 0, 1, 1];
        // Gaps of one entry are merged, the gap of three is not; entries past the old end
        // always count as changed.
        assert_eq!(changed_runs(&uploaded, &entries, 1), [0..3, 6..10]);
        assert_eq!(
            changed_runs(&uploaded, &entries, 0),
            [0..1, 2..3, 6..7, 8..10]
        );
        // (One run of all ten, spelt as a struct: clippy reads `[0..10]` as a slip for a range.)
        assert_eq!(
            changed_runs(&uploaded, &entries, 3),
            [std::ops::Range { start: 0, end: 10 }]
        );
        assert!(changed_runs(&entries, &entries, 8).is_empty());
    }
}
