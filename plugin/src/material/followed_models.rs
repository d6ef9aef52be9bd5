//! The models TAA follows from frame to frame: each drawn entity's model on the last TAA
//! frame, where its motion starts from.
//!
//! Draws arrive in the order the Extract stage met their entities, which stays the same from
//! frame to frame until entities are spawned, despawned or change components. So the last
//! frame's models are kept in that order and a draw first looks at its own position there: a
//! sequential walk through memory. Only where the entity found there is another one is a map
//! of last frame's entities built, once for that frame. Two maps looked up and filled for
//! every draw (hashing, and reads scattered over memory) cost a large share of the CPU frame
//! with many draws (sandbox/BENCHMARKS.md, "Following models").

use std::collections::HashMap;

use glam::Mat4;

use crate::render::anti_aliasing::ObjectMotions;

/// Last TAA frame's entities and models in draw order, and this frame's as they come; and
/// this frame's motion number of each draw.
#[derive(Default)]
pub(super) struct FollowedModels {
    last: Vec<(hecs::Entity, Mat4)>,
    current: Vec<(hecs::Entity, Mat4)>,
    /// Where each of last frame's entities stands in `last`, made on the first miss of a frame.
    positions: Option<HashMap<hecs::Entity, usize>>,
    numbers: Vec<u32>,
    /// The draws whose motion number was not 0 on the last frame.
    moved: Vec<usize>,
    /// A frame followed in place: each changed draw's motion number.
    changed_numbers: Vec<(usize, u32)>,
}

impl FollowedModels {
    /// Follows this TAA frame's draws (entity and model, in draw order) from the last one, adds
    /// the motion of each that moved to `motions`, and returns each draw's motion number (0:
    /// still, or not drawn last frame).
    pub(super) fn number_motions(
        &mut self,
        draws: impl Iterator<Item = (hecs::Entity, Mat4)>,
        motions: &mut ObjectMotions,
    ) -> &[u32] {
        self.begin_frame();
        let mut numbers = std::mem::take(&mut self.numbers);
        numbers.clear();
        self.moved.clear();
        for (draw, (entity, model)) in draws.enumerate() {
            let number = match self.follow(entity, model) {
                Some(previous) if previous != model => motions.push(previous, model),
                _ => 0,
            };
            if number != 0 {
                self.moved.push(draw);
            }
            numbers.push(number);
        }
        self.numbers = numbers;
        &self.numbers
    }

    /// Whether the last frame followed `draws` draws (a TAA frame of as many): a frame whose
    /// draws are the same entities may then be followed in place.
    pub(super) fn follows(&self, draws: usize) -> bool {
        self.current.len() == draws
    }

    /// Follows a TAA frame whose draws are last frame's entities in the same order, only the
    /// `changed` ones (draw, model) with a new model: adds each motion to `motions` and returns
    /// the motion number of every draw whose number may differ from last frame's (those that
    /// moved then, now still, and the changed ones, in that order; a later one wins).
    pub(super) fn number_changed_motions(
        &mut self,
        changed: impl Iterator<Item = (usize, Mat4)>,
        motions: &mut ObjectMotions,
    ) -> &[(usize, u32)] {
        self.positions = None;
        let mut numbers = std::mem::take(&mut self.changed_numbers);
        numbers.clear();
        numbers.extend(self.moved.drain(..).map(|draw| (draw, 0)));
        for (draw, model) in changed {
            let previous = std::mem::replace(&mut self.current[draw].1, model);
            let number = if previous == model {
                0
            } else {
                motions.push(previous, model)
            };
            if number != 0 {
                self.moved.push(draw);
            }
            numbers.push((draw, number));
        }
        self.changed_numbers = numbers;
        &self.changed_numbers
    }

    /// Starts a TAA frame: the models recorded so far become last frame's.
    fn begin_frame(&mut self) {
        std::mem::swap(&mut self.last, &mut self.current);
        self.current.clear();
        self.positions = None;
    }

    /// Records `entity`'s `model` as this frame's next draw and returns its model on the last
    /// frame, if it was drawn then.
    fn follow(&mut self, entity: hecs::Entity, model: Mat4) -> Option<Mat4> {
        let draw = self.current.len();
        self.current.push((entity, model));
        match self.last.get(draw) {
            Some(&(last_entity, last_model)) if last_entity == entity => Some(last_model),
            _ => {
                let last = &self.last;
                let positions = self.positions.get_or_insert_with(|| {
                    last.iter()
                        .enumerate()
                        .map(|(position, &(entity, _))| (entity, position))
                        .collect()
                });
                positions.get(&entity).map(|&position| last[position].1)
            }
        }
    }

    /// Forgets every model (a frame without TAA): the next TAA frame starts still. Returns
    /// whether there was anything to forget.
    pub(super) fn forget(&mut self) -> bool {
        let any = !self.last.is_empty() || !self.current.is_empty();
        self.last.clear();
        self.current.clear();
        self.moved.clear();
        self.positions = None;
        any
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn entities(count: usize) -> Vec<hecs::Entity> {
        let mut world = hecs::World::new();
        (0..count).map(|_| world.spawn(())).collect()
    }

    fn follow_all(
        followed: &mut FollowedModels,
        draws: &[(hecs::Entity, Mat4)],
    ) -> Vec<Option<Mat4>> {
        followed.begin_frame();
        draws
            .iter()
            .map(|&(entity, model)| followed.follow(entity, model))
            .collect()
    }

    #[test]
    fn a_draw_follows_its_entity_through_a_change_of_order() {
        let all = entities(3);
        let model = |k: f32| Mat4::from_translation(glam::Vec3::splat(k));
        let mut followed = FollowedModels::default();
        let first: Vec<_> = all
            .iter()
            .zip(0..)
            .map(|(&e, k)| (e, model(k as f32)))
            .collect();
        assert_eq!(follow_all(&mut followed, &first), [None; 3]);
        // The same order: each draw finds its place.
        let moved: Vec<_> = first.iter().map(|&(e, m)| (e, m * model(1.0))).collect();
        let previous = follow_all(&mut followed, &moved);
        assert_eq!(
            previous,
            first.iter().map(|&(_, m)| Some(m)).collect::<Vec<_>>()
        );
        // Another order, one entity gone and a new one: each is found by its entity.
        let newcomer = entities(4)[3];
        let reordered = [moved[2], (newcomer, model(9.0)), moved[0]];
        let previous = follow_all(&mut followed, &reordered);
        assert_eq!(previous, [Some(moved[2].1), None, Some(moved[0].1)]);
        // A frame without TAA in between: the next one starts still.
        assert!(followed.forget());
        assert_eq!(follow_all(&mut followed, &reordered), [None; 3]);
    }
}
