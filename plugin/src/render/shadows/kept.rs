//! Shadow maps kept while nothing they show changes. A map is drawn again only where its view
//! (where the light looks from, its size and layer, the frame's noise) differs from the one it
//! was last drawn with, the maps' texture was made anew, or a shadow caster changed since: its
//! transform or material, the batches or pipelines that draw casters, or a mesh or texture
//! uploaded again. A moving sun redraws its cascades; a spot or point light that stayed, and
//! whose casters stayed, keeps its maps.

use std::collections::HashMap;
use std::sync::atomic::{AtomicU64, Ordering};

use crate::render::ShadowViewPlan;
use crate::shadows::ShadowCasterChanges;

/// How many shadow maps were drawn and how many kept from an earlier frame. A resource the
/// shadows plugin adds.
#[derive(Debug, Default)]
pub struct ShadowMapStats {
    drawn: AtomicU64,
    kept: AtomicU64,
}

impl ShadowMapStats {
    /// Shadow maps drawn since the app started.
    pub fn drawn(&self) -> u64 {
        self.drawn.load(Ordering::Relaxed)
    }

    /// Shadow maps kept (not drawn again) since the app started.
    pub fn kept(&self) -> u64 {
        self.kept.load(Ordering::Relaxed)
    }

    pub(crate) fn count(&self, drawn: bool) {
        let counter = if drawn { &self.drawn } else { &self.kept };
        counter.fetch_add(1, Ordering::Relaxed);
    }
}

/// What one layer of the maps was last drawn with.
#[derive(Clone, Copy, Debug, PartialEq)]
struct DrawnView {
    plan: ShadowViewPlan,
    /// The frame's per-frame noise seed and anti-aliasing flag where a caster reads them (a
    /// jittered march), else 0.
    noise: [u32; 2],
    layer_size: u32,
}

/// The layers drawn on earlier frames, and what they were drawn with. The shadow node's state.
#[derive(Debug, Default)]
pub(super) struct KeptShadowViews {
    drawn: HashMap<u32, DrawnView>,
    /// The casters and the maps' texture generation the layers were drawn with.
    casters: Option<(ShadowCasterChanges, u64)>,
}

impl KeptShadowViews {
    /// Starts a frame: forgets every layer where the casters changed or the maps were made anew.
    pub(super) fn begin_frame(&mut self, casters: ShadowCasterChanges, maps_generation: u64) {
        let now = (casters, maps_generation);
        if self.casters != Some(now) {
            self.drawn.clear();
            self.casters = Some(now);
        }
    }

    /// Whether layer `plan.gpu.layer` must be drawn for `plan`; records it as drawn if so.
    pub(super) fn needs_drawing(
        &mut self,
        plan: &ShadowViewPlan,
        noise: [u32; 2],
        layer_size: u32,
    ) -> bool {
        let view = DrawnView {
            plan: *plan,
            noise,
            layer_size,
        };
        self.drawn.insert(plan.gpu.layer, view) != Some(view)
    }
}
