//! A phase's draws of every material in one list sorted by view depth, across materials and
//! batches. The transparent phase draws farthest first: blending is not commutative, so two
//! panes of different materials compose correctly only when the one behind is drawn first,
//! whichever material each belongs to or in what order they were spawned (Bevy's
//! `Transparent3d` phase sorts the same way, by the view depth of each object's centre). The
//! prepass and the deferred path's candidates draw nearest first: the depth test then rejects
//! what a nearer draw hides before its fragments run, whichever batch or material it belongs to
//! (on the deferred path a hidden plane then costs its depth test, not a visibility merge).

use std::any::TypeId;
use std::ops::Range;

use super::{DrawPhase, RenderPhases};
use crate::Resources;

/// One draw: who draws it, which of its draws, and how far it is along the view.
#[derive(Clone, Copy, Debug, PartialEq)]
struct SortedItem {
    /// View-space depth that orders the draw (along the camera's forward axis).
    view_depth: f32,
    /// The draw's owner (a material type).
    owner: TypeId,
    /// What the owner calls the draw (a material: the index of its batch).
    draw: u32,
    /// The polygon pass finds the draw's visibility on frames that run it (prepass only).
    polygon: bool,
}

/// Draw numbers in drawing order, cut into runs of one owner.
#[derive(Debug, Default)]
struct Runs {
    draws: Vec<u32>,
    runs: Vec<(TypeId, Range<usize>)>,
}

impl Runs {
    fn push(&mut self, owner: TypeId, draw: u32) {
        let index = self.draws.len();
        self.draws.push(draw);
        match self.runs.last_mut() {
            Some((last, run)) if *last == owner => run.end = index + 1,
            _ => self.runs.push((owner, index..index + 1)),
        }
    }

    fn clear(&mut self) {
        self.draws.clear();
        self.runs.clear();
    }
}

/// This frame's draws of one phase, of every material, sorted before the phase records them.
/// Each owner replaces its own draws when it prepares. Part of the [`super::Renderer`].
#[derive(Debug)]
pub(crate) struct SortedDraws {
    phase: DrawPhase,
    items: Vec<SortedItem>,
    /// Every draw in sorted order.
    all: Runs,
    /// The same without the polygon pass's draws, made where any draw is one (else `all`).
    rasterized: Runs,
    /// Whether any draw of this frame is the polygon pass's.
    any_polygon: bool,
}

impl SortedDraws {
    /// The draws of `phase`: the transparent phase sorts them farthest first, any other nearest
    /// first.
    pub(crate) fn new(phase: DrawPhase) -> Self {
        Self {
            phase,
            items: Vec::new(),
            all: Runs::default(),
            rasterized: Runs::default(),
            any_polygon: false,
        }
    }

    /// Replaces `Owner`'s draws of this frame with `draws`: (view depth, draw number).
    pub(crate) fn replace<Owner: 'static>(&mut self, draws: impl Iterator<Item = (f32, u32)>) {
        self.replace_marked::<Owner>(draws.map(|(view_depth, draw)| (view_depth, draw, false)));
    }

    /// [`SortedDraws::replace`] with each draw marked where the polygon pass finds its
    /// visibility on frames that run it: (view depth, draw number, polygon).
    pub(crate) fn replace_marked<Owner: 'static>(
        &mut self,
        draws: impl Iterator<Item = (f32, u32, bool)>,
    ) {
        let owner = TypeId::of::<Owner>();
        self.items.retain(|item| item.owner != owner);
        self.items
            .extend(draws.map(|(view_depth, draw, polygon)| SortedItem {
                view_depth,
                owner,
                draw,
                polygon,
            }));
    }

    /// Whether no owner has a draw this frame.
    pub(crate) fn is_empty(&self) -> bool {
        self.items.is_empty()
    }

    /// Sorts the draws (farthest first for the transparent phase, else nearest first) and
    /// groups them into runs of one owner. Stable: draws at the same depth keep the order their
    /// owners gave (an owner's draws in its own order). A non-finite depth sorts last.
    pub(crate) fn sort(&mut self) {
        let farthest_first = self.phase == DrawPhase::Transparent;
        let depth = |item: &SortedItem| match (item.view_depth.is_finite(), farthest_first) {
            (true, true) => -item.view_depth,
            (true, false) => item.view_depth,
            (false, _) => f32::INFINITY,
        };
        if !self
            .items
            .is_sorted_by(|a, b| depth(a).total_cmp(&depth(b)).is_le())
        {
            self.items.sort_by(|a, b| depth(a).total_cmp(&depth(b)));
        }
        self.all.clear();
        self.rasterized.clear();
        self.any_polygon = self.items.iter().any(|item| item.polygon);
        for item in &self.items {
            self.all.push(item.owner, item.draw);
            if self.any_polygon && !item.polygon {
                self.rasterized.push(item.owner, item.draw);
            }
        }
    }

    /// Whether the polygon pass finds every draw (none is left to rasterize).
    pub(crate) fn all_polygons(&self) -> bool {
        self.items.iter().all(|item| item.polygon)
    }

    /// Records the sorted draws into the phase's `pass` (`without_polygons`: but those the
    /// polygon pass found), each run of one owner by the owner's drawer in `phases`.
    pub(crate) fn record(
        &self,
        phases: &RenderPhases,
        resources: &Resources,
        pass: &mut wgpu::RenderPass<'_>,
        without_polygons: bool,
    ) {
        for (owner, draws) in self.runs(without_polygons) {
            if let Some(draw) = phases.sorted_draw(self.phase, owner) {
                draw(resources, pass, draws);
            }
        }
    }

    /// The sorted draws as runs of one owner each, in drawing order: the owner and its draw
    /// numbers.
    /// (`without_polygons`: but those the polygon pass finds.)
    pub(crate) fn runs(
        &self,
        without_polygons: bool,
    ) -> impl Iterator<Item = (TypeId, &[u32])> + '_ {
        let runs = if without_polygons && self.any_polygon {
            &self.rasterized
        } else {
            &self.all
        };
        runs.runs
            .iter()
            .map(|(owner, run)| (*owner, &runs.draws[run.clone()]))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    struct Glass;
    struct Smoke;

    fn sorted(phase: &mut SortedDraws) -> Vec<(TypeId, Vec<u32>)> {
        phase.sort();
        phase
            .runs(false)
            .map(|(owner, draws)| (owner, draws.to_vec()))
            .collect()
    }

    #[test]
    fn draws_of_two_owners_interleave_farthest_first() {
        let mut phase = SortedDraws::new(DrawPhase::Transparent);
        phase.replace::<Glass>([(1.0, 0), (5.0, 1)].into_iter());
        phase.replace::<Smoke>([(3.0, 0), (7.0, 1)].into_iter());
        let (glass, smoke) = (TypeId::of::<Glass>(), TypeId::of::<Smoke>());
        assert_eq!(
            sorted(&mut phase),
            [
                (smoke, vec![1]),
                (glass, vec![1]),
                (smoke, vec![0]),
                (glass, vec![0])
            ]
        );
    }

    #[test]
    fn an_owner_replaces_only_its_own_draws_and_neighbours_of_one_owner_are_one_run() {
        let mut phase = SortedDraws::new(DrawPhase::Transparent);
        phase.replace::<Glass>([(1.0, 0)].into_iter());
        phase.replace::<Smoke>([(9.0, 0), (8.0, 1), (f32::NAN, 2)].into_iter());
        phase.replace::<Glass>([(2.0, 3), (2.0, 4)].into_iter());
        let (glass, smoke) = (TypeId::of::<Glass>(), TypeId::of::<Smoke>());
        assert_eq!(
            sorted(&mut phase),
            [(smoke, vec![0, 1]), (glass, vec![3, 4]), (smoke, vec![2])]
        );
        phase.replace::<Smoke>(std::iter::empty());
        phase.replace::<Glass>(std::iter::empty());
        assert!(phase.is_empty());
        assert_eq!(sorted(&mut phase), []);
    }

    #[test]
    fn the_prepass_sorts_nearest_first_across_owners() {
        let mut phase = SortedDraws::new(DrawPhase::Prepass);
        phase.replace::<Glass>([(4.0, 0), (1.0, 1)].into_iter());
        phase.replace::<Smoke>([(2.0, 0), (f32::INFINITY, 1)].into_iter());
        let (glass, smoke) = (TypeId::of::<Glass>(), TypeId::of::<Smoke>());
        assert_eq!(
            sorted(&mut phase),
            [
                (glass, vec![1]),
                (smoke, vec![0]),
                (glass, vec![0]),
                (smoke, vec![1])
            ]
        );
    }

    #[test]
    fn the_visibility_pass_leaves_out_what_the_polygon_pass_finds() {
        let mut phase = SortedDraws::new(DrawPhase::Prepass);
        phase.replace_marked::<Glass>([(1.0, 0, true), (3.0, 1, false)].into_iter());
        phase.replace::<Smoke>([(2.0, 0)].into_iter());
        phase.sort();
        let (glass, smoke) = (TypeId::of::<Glass>(), TypeId::of::<Smoke>());
        let runs = |without| -> Vec<(TypeId, Vec<u32>)> {
            phase
                .runs(without)
                .map(|(owner, draws)| (owner, draws.to_vec()))
                .collect()
        };
        assert_eq!(
            runs(false),
            [(glass, vec![0]), (smoke, vec![0]), (glass, vec![1])]
        );
        assert_eq!(runs(true), [(smoke, vec![0]), (glass, vec![1])]);
    }
}
