//! [`MaterialWarnings`]: a material's problems logged once per change, for an entity's own
//! material and for a shared one (once for all that hold it).

use std::collections::HashMap;

use hecs::Entity;

use super::Material;
use super::batches::ExtractedDraw;
use crate::AssetId;

/// The problems last logged for each entity whose own material of type `M` is being clamped (or
/// whose handle finds no shared material), and for each shared material being clamped (once for
/// all that hold it), so a bad value is logged once per change, not every frame. Problems are
/// compared as text: a NaN never equals itself, a material holding one would be "changed" every
/// frame. A resource.
#[derive(Debug)]
pub struct MaterialWarnings<M> {
    pub(super) entities: HashMap<Entity, Vec<String>>,
    pub(super) shared: HashMap<AssetId<M>, Vec<String>>,
}

// By hand: derived, it would ask `M: Default`.
impl<M> Default for MaterialWarnings<M> {
    fn default() -> Self {
        Self {
            entities: HashMap::new(),
            shared: HashMap::new(),
        }
    }
}

impl<M> MaterialWarnings<M> {
    /// Number of entities whose own material is being clamped or whose shared one is not found,
    /// and of shared materials being clamped.
    pub fn len(&self) -> usize {
        self.entities.len() + self.shared.len()
    }

    /// Whether no material needed clamping, and every shared one was found.
    pub fn is_empty(&self) -> bool {
        self.entities.is_empty() && self.shared.is_empty()
    }
}

impl<M: Material> MaterialWarnings<M> {
    /// Logs the problems of `draw`'s `material` where they differ from those last logged: its
    /// entity's own, or the shared one's.
    pub(super) fn log_draw(&mut self, draw: &ExtractedDraw<M>, material: &M) {
        match draw.shared {
            Some((id, _)) => self.log_shared(draw.entity, id, material),
            None => self.log_problems(draw.entity, clamped(material)),
        }
    }

    /// Logs `entity`'s `problems` with its material where they differ from those last logged.
    pub(super) fn log_problems(&mut self, entity: Entity, problems: Vec<String>) {
        log_once(&mut self.entities, entity, problems, |problem| {
            log::warn!("{} material of {entity:?}: {problem}", M::NAME);
        });
    }

    /// Logs the problems of the shared material `id`, held by `entity` (whose own warnings
    /// are forgotten), where they differ from those last logged for it.
    fn log_shared(&mut self, entity: Entity, id: AssetId<M>, material: &M) {
        if !self.entities.is_empty() {
            self.entities.remove(&entity);
        }
        let problems = clamped(material);
        log_once(&mut self.shared, id, problems, |problem| {
            log::warn!("shared {} material {id:?}: {problem}", M::NAME);
        });
    }
}

/// `material`'s problems, each saying it is clamped.
fn clamped<M: Material>(material: &M) -> Vec<String> {
    let problems = material.problems();
    problems.into_iter().map(|p| p + "; clamped").collect()
}

/// Logs `problems` with `log` and keeps them for `key`, unless they are what was kept; none
/// forgets the key, so a later problem is logged anew.
fn log_once<K: std::hash::Hash + Eq>(
    logged: &mut HashMap<K, Vec<String>>,
    key: K,
    problems: Vec<String>,
    log: impl Fn(&str),
) {
    if problems.is_empty() {
        if !logged.is_empty() {
            logged.remove(&key);
        }
    } else if logged.get(&key) != Some(&problems) {
        for problem in &problems {
            log(problem);
        }
        logged.insert(key, problems);
    }
}
