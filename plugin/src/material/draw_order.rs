//! The order a material's draws are drawn in: one [`SortEntry`] per draw, sorted opaque
//! batches first (nearest first within a batch), then blended draws farthest first.

use glam::Vec3;

use super::batches::ExtractedDraw;
use crate::render::texture_bind_groups::BoundTextures;
use crate::{AssetId, Mesh};

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

    /// Sorts `order`: opaque batches first (pipeline, textures, mesh), then nearest first within
    /// a batch: the prepass then rejects hidden copies early (measured in
    /// sandbox/BENCHMARKS.md, "overdraw"). Blended draws after them, farthest first. Stable:
    /// draws that share everything keep the order of the world's query. Most frames come in the
    /// order the last one was sorted into (a still camera), which the check finds in one pass.
    pub(super) fn sort(order: &mut [Self]) {
        let sort_key = |entry: &Self| {
            (
                entry.blends,
                entry.far_first,
                entry.key,
                entry.casts_shadows,
                entry.textures,
                entry.mesh,
                entry.view_depth,
            )
        };
        if !order.is_sorted_by_key(sort_key) {
            order.sort_by_key(sort_key);
        }
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
