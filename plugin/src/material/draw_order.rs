//! The order a material's draws are drawn in: one [`SortEntry`] per draw, sorted opaque
//! batches first (nearest first within a batch), then blended draws farthest first.

use std::cmp::Ordering;

use glam::Vec3;

use super::batches::ExtractedDraw;
use crate::gpu::BoundTextures;
use crate::{AssetId, Mesh};

/// What the sort keeps from frame to frame: last frame's sorted order (the draws' indices),
/// and storage it reuses.
pub(super) struct SortMemory<K> {
    last_sorted: Vec<usize>,
    unsorted: Vec<SortEntry<K>>,
}

impl<K> SortMemory<K> {
    /// Notes that the draws of sorted slots `a` and `b` traded places.
    pub(super) fn swap(&mut self, a: usize, b: usize) {
        if a.max(b) < self.last_sorted.len() {
            self.last_sorted.swap(a, b);
        }
    }
}

impl<K> Default for SortMemory<K> {
    fn default() -> Self {
        Self {
            last_sorted: Vec::new(),
            unsorted: Vec::new(),
        }
    }
}

/// One draw's place in the order, and what decides it.
#[derive(Clone, Copy)]
pub(super) struct SortEntry<K> {
    pub(super) key: K,
    pub(super) casts_shadows: bool,
    pub(super) textures: BoundTextures,
    pub(super) mesh: AssetId<Mesh>,
    /// Distance from the eye to the object's origin along the view, as ordered bits: the
    /// instances of one batch are drawn nearest first.
    view_depth: u32,
    /// The view depth of the nearest point of the draw's bounding sphere: its batch reaches the
    /// frame's nearest-first prepass at its nearest instance's.
    pub(super) nearest_depth: f32,
    /// Whether the draw blends: blended draws come after the opaque ones, farthest first, each a
    /// batch of its own (the frame's transparent phase orders them across materials).
    pub(super) blends: bool,
    /// For a blended draw, `!` the ordered bits of its centre's view depth (farthest first);
    /// 0 for an opaque one.
    far_first: u32,
    /// For a blended draw, its centre's view depth (behind the eye: 0).
    pub(super) centre_depth: f32,
    /// The draw's index among the extracted draws.
    pub(super) draw: usize,
}

impl<K: Copy + Ord> SortEntry<K> {
    /// The entry of `draw`, the `index`th extracted, drawn with `key` and `textures`; its
    /// origin's view depth seen from `eye` (position, forward), its nearest point's
    /// (`nearest_depth`), and for a blended draw its centre's (`centre_depth`; `None` for an
    /// opaque one).
    pub(super) fn new<M>(
        draw: &ExtractedDraw<M>,
        index: usize,
        (key, textures): (K, BoundTextures),
        eye: (Vec3, Vec3),
        nearest_depth: f32,
        centre_depth: Option<f32>,
    ) -> Self {
        let centre_depth = centre_depth.map(|depth| f32::from_bits(depth_order_bits(depth)));
        Self {
            key,
            casts_shadows: draw.casts_shadows,
            textures,
            mesh: draw.mesh,
            view_depth: depth_order_bits(view_depth(draw.model.w_axis.truncate(), eye)),
            nearest_depth,
            blends: centre_depth.is_some(),
            far_first: centre_depth.map_or(0, |depth| !depth.to_bits()),
            centre_depth: centre_depth.unwrap_or(0.0),
            draw: index,
        }
    }

    /// How this entry's batch stands against `other`'s: blending (and a blended draw's depth),
    /// pipeline, shadow role, textures, mesh. Field by field, by reference: the textures are
    /// most of an entry, and a tuple of copies made each comparison cost a copy of them.
    fn batch_order(&self, other: &Self) -> Ordering {
        self.blends
            .cmp(&other.blends)
            .then(self.far_first.cmp(&other.far_first))
            .then_with(|| self.key.cmp(&other.key))
            .then(self.casts_shadows.cmp(&other.casts_shadows))
            .then_with(|| self.textures.cmp(&other.textures))
            .then_with(|| self.mesh.cmp(&other.mesh))
    }

    /// How this entry stands against `other` in the order: the batch, then depth, then the
    /// world's order.
    fn order(&self, other: &Self) -> Ordering {
        self.batch_order(other)
            .then_with(|| self.order_in_batch(other))
    }

    /// How this entry stands against `other` of the same batch: by depth and draw alone (what
    /// a batch's entries differ in).
    fn order_in_batch(&self, other: &Self) -> Ordering {
        self.view_depth
            .cmp(&other.view_depth)
            .then(self.draw.cmp(&other.draw))
    }

    /// Whether this entry comes before `other` of the same batch.
    pub(super) fn precedes_in_batch(&self, other: &Self) -> bool {
        self.order_in_batch(other).is_lt()
    }

    /// Whether `other` belongs to the same batch as this entry and stands in the same place
    /// among the batches (all but depth and draw agree).
    pub(super) fn same_batch(&self, other: &Self) -> bool {
        self.batch_order(other).is_eq()
    }

    /// Sorts `order` (entries in extraction order: entry `i` is draw `i`): opaque batches first
    /// (pipeline, textures, mesh), then nearest first within a batch: the prepass then rejects
    /// hidden copies early (sandbox/BENCHMARKS.md, "Stacked planes (overdraw) and depth offset").
    /// Blended draws after them, farthest first. Stable: draws that share everything keep the
    /// order of the world's query.
    ///
    /// The draws come in the world's order every frame, which need not be the sorted one (many
    /// draws spawned in a grid took milliseconds a frame to sort, sandbox/BENCHMARKS.md,
    /// "Following models"). So where there are as many draws as last frame, they are first put
    /// in last frame's sorted order (kept in `memory`), which a still camera finds sorted in one
    /// pass and a moving one nearly so.
    pub(super) fn sort(order: &mut Vec<Self>, memory: &mut SortMemory<K>) {
        debug_assert!(
            order
                .iter()
                .enumerate()
                .all(|(index, entry)| entry.draw == index)
        );
        let SortMemory {
            last_sorted,
            unsorted,
        } = memory;
        if last_sorted.len() == order.len() {
            unsorted.clear();
            unsorted.extend(last_sorted.iter().map(|&draw| order[draw]));
            std::mem::swap(order, unsorted);
        }
        if !order.is_sorted_by(|a, b| a.order(b) != Ordering::Greater) {
            order.sort_unstable_by(Self::order);
        }
        last_sorted.clear();
        last_sorted.extend(order.iter().map(|entry| entry.draw));
    }
}

/// The distance from the eye to `point` along the view, `eye` being (position, forward).
pub(super) fn view_depth(point: Vec3, (eye, forward): (Vec3, Vec3)) -> f32 {
    (point - eye).dot(forward)
}

/// `depth` as bits that order like the number (depths behind the eye count as 0).
fn depth_order_bits(depth: f32) -> u32 {
    if depth > 0.0 { depth.to_bits() } else { 0 }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Assets;

    /// Draw `index` with batch key `key` at `depth` (opaque, no textures, one mesh).
    fn entry(index: usize, key: u32, depth: u32, mesh: AssetId<Mesh>) -> SortEntry<u32> {
        SortEntry {
            key,
            casts_shadows: true,
            textures: BoundTextures {
                images: Default::default(),
                derived: Default::default(),
            },
            mesh,
            view_depth: depth,
            nearest_depth: depth as f32,
            blends: false,
            far_first: 0,
            centre_depth: 0.0,
            draw: index,
        }
    }

    /// The draws in the order `sort` puts them, starting from `last_sorted` (replaced by it).
    fn sorted_draws(entries: &[SortEntry<u32>], last_sorted: &mut Vec<usize>) -> Vec<usize> {
        let mut order = entries.to_vec();
        let mut memory = SortMemory {
            last_sorted: std::mem::take(last_sorted),
            unsorted: Vec::new(),
        };
        SortEntry::sort(&mut order, &mut memory);
        *last_sorted = memory.last_sorted;
        order.iter().map(|entry| entry.draw).collect()
    }

    #[test]
    fn last_frames_order_changes_nothing_but_the_work() {
        let mesh = Assets::<Mesh>::default().add(Mesh::plane(1.0)).id();
        // Keys 0..3, depths descending with the world's order, and ties (same key and depth).
        let entries: Vec<_> = (0..40)
            .map(|index| entry(index, (index % 3) as u32, 100 - (index / 2) as u32, mesh))
            .collect();
        let mut fresh = Vec::new();
        let expected = sorted_draws(&entries, &mut fresh);
        assert_eq!(
            fresh, expected,
            "the sorted order is kept for the next frame"
        );
        // Key first, nearest first, ties in the world's order.
        assert!(expected.windows(2).all(|pair| {
            let (a, b) = (&entries[pair[0]], &entries[pair[1]]);
            (a.key, a.view_depth, a.draw) < (b.key, b.view_depth, b.draw)
        }));
        // Starting from last frame's order, or from any other, gives the same order.
        assert_eq!(sorted_draws(&entries, &mut expected.clone()), expected);
        let reversed: Vec<usize> = (0..entries.len()).rev().collect();
        assert_eq!(sorted_draws(&entries, &mut reversed.clone()), expected);
        // Another count of draws starts from the world's order.
        assert_eq!(sorted_draws(&entries, &mut vec![0, 1]), expected);
    }
}
