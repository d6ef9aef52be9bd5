//! A storage buffer of per-draw structs that re-uploads only the entries that changed.

use std::ops::Range;

use bytemuck::Pod;

use super::GpuContext;
use super::scatter_upload::{ScatterQueue, ScatterUpload};

/// The longest run of unchanged bytes an upload writes again rather than start another write.
const MERGE_GAP_BYTES: u64 = 4096;

/// The most runs an upload writes with a call each; more are scattered by the GPU
/// ([`ScatterUpload`]).
const MOST_WRITTEN_RUNS: usize = 16;

/// An array of `T` on the GPU, rewritten each frame by [`ObjectBuffer::upload`], which writes
/// only the runs of entries that differ from the last upload.
#[derive(Debug)]
pub struct ObjectBuffer<T> {
    label: &'static str,
    buffer: wgpu::Buffer,
    uploaded: Vec<T>,
    /// Made on the first upload of many scattered runs.
    scatter: Option<ScatterUpload>,
}

impl<T: Pod + PartialEq> ObjectBuffer<T> {
    const ENTRY_SIZE: u64 = std::mem::size_of::<T>() as u64;

    /// An empty buffer with room for `capacity` entries.
    pub fn new(gpu: &GpuContext, label: &'static str, capacity: u64) -> Self {
        Self {
            label,
            buffer: Self::create(gpu, label, capacity),
            uploaded: Vec::new(),
            scatter: None,
        }
    }

    fn create(gpu: &GpuContext, label: &str, capacity: u64) -> wgpu::Buffer {
        gpu.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some(label),
            size: capacity.max(1) * Self::ENTRY_SIZE,
            // COPY_SRC: tests read it back.
            usage: wgpu::BufferUsages::STORAGE
                | wgpu::BufferUsages::COPY_DST
                | wgpu::BufferUsages::COPY_SRC,
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
        let runs = changed_runs(&self.uploaded, entries, 0..entries.len(), Self::merge_gap());
        // The copy mirrors only what changed: entries past the old end are all in runs.
        self.uploaded.resize(entries.len(), T::zeroed());
        let written = self.write_runs(gpu, entries, runs);
        (written, grew)
    }

    /// Makes the GPU copy equal `entries` where only the entries at `candidates` (in increasing
    /// order) may have changed since the last upload, of as many entries; many scattered
    /// changes are written by a dispatch queued on `scatters`. Returns the bytes written; `None`
    /// (nothing written) where the count differs: call [`ObjectBuffer::upload`].
    pub(crate) fn upload_candidates(
        &mut self,
        gpu: &GpuContext,
        (entries, candidates): (&[T], &[usize]),
        scatters: &mut ScatterQueue,
    ) -> Option<u64> {
        if entries.len() != self.uploaded.len() {
            return None;
        }
        let runs = changed_runs(
            &self.uploaded,
            entries,
            candidates.iter().copied(),
            Self::merge_gap(),
        );
        if runs.len() <= MOST_WRITTEN_RUNS || Self::ENTRY_SIZE % 4 != 0 {
            return Some(self.write_runs(gpu, entries, runs));
        }
        let slots: Vec<u32> = candidates
            .iter()
            .copied()
            .filter(|&index| self.uploaded[index] != entries[index])
            .map(|index| index as u32)
            .collect();
        let words = slots
            .iter()
            .map(|&slot| bytemuck::bytes_of(&entries[slot as usize]));
        let scatter = self.scatter.get_or_insert_with(|| ScatterUpload::new(gpu));
        let per_entry = (Self::ENTRY_SIZE / 4) as u32;
        let written = scatter.write(gpu, (&self.buffer, scatters), (&slots, per_entry), words);
        for &slot in &slots {
            self.uploaded[slot as usize] = entries[slot as usize];
        }
        Some(written)
    }

    /// Entries of unchanged gap a run takes in rather than end.
    fn merge_gap() -> usize {
        (MERGE_GAP_BYTES / Self::ENTRY_SIZE.max(1)) as usize
    }

    /// Writes `runs` of `entries` and mirrors them in the copy; returns the bytes written.
    fn write_runs(&mut self, gpu: &GpuContext, entries: &[T], runs: Vec<Range<usize>>) -> u64 {
        let mut written = 0;
        for run in runs {
            let changed = &entries[run.clone()];
            let bytes: &[u8] = bytemuck::cast_slice(changed);
            gpu.write_buffer(&self.buffer, run.start as u64 * Self::ENTRY_SIZE, bytes);
            written += bytes.len() as u64;
            self.uploaded[run].copy_from_slice(changed);
        }
        written
    }
}

/// The runs of `entries` that differ from `uploaded` among the `candidates` (increasing
/// indices; an entry past the end of `uploaded` differs), each to be written with one call: unchanged gaps of up to `merge_gap` entries are written again
/// inside a run, because a write call costs far more than copying a few KiB (a tenth of the
/// draws moving, scattered, made a call each, and their frame was slower than all of them
/// moving: sandbox/BENCHMARKS.md, "CPU side").
fn changed_runs<T: PartialEq>(
    uploaded: &[T],
    entries: &[T],
    candidates: impl Iterator<Item = usize>,
    merge_gap: usize,
) -> Vec<Range<usize>> {
    let changed = |index: usize| uploaded.get(index) != Some(&entries[index]);
    let mut runs: Vec<Range<usize>> = Vec::new();
    for index in candidates.filter(|&index| changed(index)) {
        match runs.last_mut() {
            Some(run) if index - run.end <= merge_gap => run.end = index + 1,
            _ => runs.push(index..index + 1),
        }
    }
    runs
}

#[cfg(test)]
pub(crate) mod tests {
    use super::{ObjectBuffer, ScatterQueue, changed_runs};
    use crate::GpuContext;

    /// The bytes of `buffer`, read back.
    pub(crate) fn read_back(gpu: &GpuContext, buffer: &wgpu::Buffer) -> Vec<u8> {
        let staging = gpu.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("read back"),
            size: buffer.size(),
            usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
            mapped_at_creation: false,
        });
        let mut encoder = gpu.device.create_command_encoder(&Default::default());
        encoder.copy_buffer_to_buffer(buffer, 0, &staging, 0, buffer.size());
        gpu.queue.submit([encoder.finish()]);
        staging.map_async(wgpu::MapMode::Read, .., |result| result.unwrap());
        gpu.device
            .poll(wgpu::PollType::wait_indefinitely())
            .unwrap();
        staging.get_mapped_range(..).unwrap().to_vec()
    }

    #[test]
    fn scattered_changes_are_written_to_their_slots_in_one_upload() {
        let gpu = GpuContext::headless().unwrap();
        // Entries of 1 KiB: runs merge across gaps of up to four entries.
        let mut entries: Vec<[u32; 256]> = (0..200).map(|index| [index; 256]).collect();
        let mut buffer = ObjectBuffer::new(&gpu, "scattered", 200);
        buffer.upload(&gpu, &entries);
        // Every sixth entry changes, and one candidate does not: 34 runs, past the most
        // written with a call each.
        let candidates: Vec<usize> = (0..200).step_by(6).chain([199]).collect();
        for &index in &candidates[..34] {
            entries[index] = [1000 + index as u32; 256];
            entries[index][7] = 7;
        }
        let mut scatters = ScatterQueue::default();
        let written = buffer
            .upload_candidates(&gpu, (&entries, &candidates), &mut scatters)
            .unwrap();
        assert!(buffer.scatter.is_some(), "scattered on the GPU");
        let mut encoder = gpu.device.create_command_encoder(&Default::default());
        scatters.record(&mut encoder);
        gpu.queue.submit([encoder.finish()]);
        // The header, the slots and the changed entries only.
        assert_eq!(written, (2 + 34 + 34 * 256) * 4);
        let expected: &[u8] = bytemuck::cast_slice(&entries);
        assert!(read_back(&gpu, buffer.buffer())[..expected.len()] == *expected);
        assert_eq!(
            buffer.upload_candidates(&gpu, (&entries, &candidates), &mut scatters),
            Some(0),
            "nothing left to write"
        );
    }

    #[test]
    fn changed_entries_are_written_in_runs_that_take_in_short_gaps() {
        let uploaded = [0, 0, 0, 0, 0, 0, 0, 0];
        let entries = [1, 0, 1, 0, 0, 0, 1, 0, 1, 1];
        // Gaps of one entry are merged, the gap of three is not; entries past the old end
        // always count as changed.
        assert_eq!(changed_runs(&uploaded, &entries, 0..10, 1), [0..3, 6..10]);
        assert_eq!(
            changed_runs(&uploaded, &entries, 0..10, 0),
            [0..1, 2..3, 6..7, 8..10]
        );
        // (One run of all ten, spelt as a struct: clippy reads `[0..10]` as a slip for a range.)
        assert_eq!(
            changed_runs(&uploaded, &entries, 0..10, 3),
            [std::ops::Range { start: 0, end: 10 }]
        );
        assert!(changed_runs(&entries, &entries, 0..10, 8).is_empty());
        // Only the candidates are looked at: the change at 6 is not among them.
        assert_eq!(
            changed_runs(&uploaded, &entries, [0, 2, 8].into_iter(), 1),
            [0..3, 8..9]
        );
    }
}
