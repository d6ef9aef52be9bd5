//! The Extract stage of a material: each drawable entity's mesh, transform and material copied
//! into [`ExtractedMaterials`], and a material's problems logged once per change
//! ([`MaterialWarnings`]).

use std::collections::HashMap;
use std::marker::PhantomData;

use hecs::{Entity, World};

use super::Material;
use super::batches::ExtractedDraw;
use super::registry::MaterialRegistry;
use crate::{GlobalTransform, Handle, Mesh, NotShadowCaster, NotShadowReceiver, Resources};

/// This frame's draws of `M`, as extracted, and which of them changed since the last frame.
/// A resource.
pub(crate) struct ExtractedMaterials<M> {
    pub(crate) draws: Vec<ExtractedDraw<M>>,
    /// The draws whose mesh, transform, shadow roles or material changed this frame, in order;
    /// meaningful where `same_entities`.
    pub(crate) changed: Vec<usize>,
    /// The changed draws whose material changed (not only their transform, mesh or roles), in
    /// order.
    pub(crate) changed_materials: Vec<usize>,
    /// Whether every draw is the same entity's as last frame, and no draw came or went: the
    /// Prepare stage may then update only the `changed` ones.
    pub(crate) same_entities: bool,
    /// Whether a shadow caster's material reads the frame's noise
    /// ([`Material::casts_with_frame_noise`]).
    pub(crate) casters_read_frame_noise: bool,
}

/// The problems last logged for each entity whose material of type `M` is being clamped, so a
/// bad value is logged once per change, not every frame. Problems are compared as text: a NaN
/// never equals itself, a material holding one would be "changed" every frame. A resource.
#[derive(Debug)]
pub struct MaterialWarnings<M>(HashMap<Entity, Vec<String>>, PhantomData<fn() -> M>);

impl<M> MaterialWarnings<M> {
    /// Number of entities whose material is being clamped.
    pub fn len(&self) -> usize {
        self.0.len()
    }

    /// Whether no material needed clamping.
    pub fn is_empty(&self) -> bool {
        self.0.is_empty()
    }
}

impl<M: Material> MaterialWarnings<M> {
    /// Logs the problems of `entity`'s `material` where they differ from those last logged.
    fn log_changed(&mut self, entity: Entity, material: &M) {
        let problems = material.problems();
        if problems.is_empty() {
            // Valid again: forget it, so a later bad value is logged anew.
            if !self.0.is_empty() {
                self.0.remove(&entity);
            }
        } else if self.0.get(&entity) != Some(&problems) {
            for problem in &problems {
                log::warn!("{} material of {entity:?}: {problem}; clamped", M::NAME);
            }
            self.0.insert(entity, problems);
        }
    }
}

/// Whether a draw casts and receives scene shadows (its marker components).
#[derive(Clone, Copy)]
struct ShadowRoles {
    casts: bool,
    receives: bool,
}

/// The Extract stage's system of material `M`: copies each drawable entity's mesh, transform
/// and material, and logs a material's problems once per change.
pub(super) fn extract_materials<M: Material>(world: &mut World, resources: &mut Resources) {
    let fallback = resources
        .get::<MaterialRegistry>()
        .is_some_and(MaterialRegistry::draws_meshes_without_material::<M>);
    if !resources.contains::<ExtractedMaterials<M>>() {
        resources.insert(ExtractedMaterials::<M> {
            draws: Vec::new(),
            changed: Vec::new(),
            changed_materials: Vec::new(),
            same_entities: false,
            casters_read_frame_noise: false,
        });
    }
    if !resources.contains::<MaterialWarnings<M>>() {
        resources.insert(MaterialWarnings::<M>(HashMap::new(), PhantomData));
    }
    resources.scope(|resources, extracted: &mut ExtractedMaterials<M>| {
        resources.scope(|resources, warnings: &mut MaterialWarnings<M>| {
            extract_into(world, resources, fallback, extracted, warnings);
        })
    });
}

/// Writes this frame's draws into `extracted`: the entities with material `M`, then (with
/// `fallback`) the meshes that have no registered material.
fn extract_into<M: Material>(
    world: &World,
    resources: &Resources,
    fallback: bool,
    extracted: &mut ExtractedMaterials<M>,
    warnings: &mut MaterialWarnings<M>,
) {
    extracted.changed.clear();
    extracted.changed_materials.clear();
    extracted.same_entities = true;
    extracted.casters_read_frame_noise = false;
    let mut writer = DrawWriter {
        extracted,
        warnings,
        written: 0,
    };
    writer.push_entities(world);
    if fallback && let Some(registry) = resources.get::<MaterialRegistry>() {
        writer.push_meshes_without_material(world, registry);
    }
    writer.finish(world);
}

/// Rewrites last frame's draws in place, slot after slot: a draw equal to the one in the same
/// slot last frame is left alone (not even its material's problems are looked at again), and a
/// material equal to last frame's is not cloned again (a clone bumps every texture handle's
/// reference count, and dropping the old one lowers it: tens of thousands of atomic operations
/// a frame for nothing).
struct DrawWriter<'a, M> {
    extracted: &'a mut ExtractedMaterials<M>,
    warnings: &'a mut MaterialWarnings<M>,
    /// The slots written this frame.
    written: usize,
}

impl<M: Material> DrawWriter<'_, M> {
    /// Writes every entity that has material `M`, a mesh and a transform.
    fn push_entities(&mut self, world: &World) {
        for (entity, mesh, transform, material, not_caster, not_receiver) in world
            .query::<(
                Entity,
                &Handle<Mesh>,
                &GlobalTransform,
                &M,
                Option<&NotShadowCaster>,
                Option<&NotShadowReceiver>,
            )>()
            .iter()
        {
            let shadows = ShadowRoles {
                casts: not_caster.is_none(),
                receives: not_receiver.is_none(),
            };
            self.push(entity, true, mesh, transform, material, shadows);
        }
    }

    /// Writes, with `M::default()`, every mesh entity that has none of `registry`'s materials.
    fn push_meshes_without_material(&mut self, world: &World, registry: &MaterialRegistry) {
        let default = M::default();
        // Whole archetypes at a time: an entity with any registered material is skipped
        // without looking it up.
        for archetype in world.archetypes() {
            if registry.has_any(archetype) {
                continue;
            }
            if let (Some(meshes), Some(transforms)) = (
                archetype.get::<&Handle<Mesh>>(),
                archetype.get::<&GlobalTransform>(),
            ) {
                let shadows = ShadowRoles {
                    casts: !archetype.has::<NotShadowCaster>(),
                    receives: !archetype.has::<NotShadowReceiver>(),
                };
                for ((id, mesh), transform) in archetype
                    .ids()
                    .iter()
                    .zip(meshes.iter())
                    .zip(transforms.iter())
                {
                    // SAFETY: `id` is one of `archetype`'s, borrowed from `world` for this loop,
                    // so it names a live entity of `world` (what hecs documents `ids` for).
                    let entity = unsafe { world.find_entity_from_id(*id) };
                    self.push(entity, false, mesh, transform, &default, shadows);
                }
            }
        }
    }

    /// Writes the next slot, unless the transform is not finite; logs the material's problems
    /// where `log_problems` (not for the default material of meshes without one).
    fn push(
        &mut self,
        entity: Entity,
        log_problems: bool,
        mesh: &Handle<Mesh>,
        transform: &GlobalTransform,
        material: &M,
        shadows: ShadowRoles,
    ) {
        self.extracted.casters_read_frame_noise |=
            shadows.casts && material.casts_with_frame_noise();
        let model = transform.to_mat4();
        let slot = self.written;
        // Last frame's draw in this slot, where it is this one unchanged: nothing to write (its
        // transform was finite then).
        if let Some(draw) = self.extracted.draws.get(slot)
            && draw.entity == entity
            && draw.model == model
            && draw.mesh == mesh.id()
            && (draw.casts_shadows, draw.receives_shadows) == (shadows.casts, shadows.receives)
            && draw.material == *material
        {
            self.written += 1;
            return;
        }
        if !model.is_finite() {
            log::warn!(
                "{} mesh {:?} has a non-finite transform: not drawn",
                M::NAME,
                mesh.id()
            );
            return;
        }
        self.written += 1;
        let Some(draw) = self.extracted.draws.get_mut(slot) else {
            if log_problems {
                self.warnings.log_changed(entity, material);
            }
            self.extracted.same_entities = false;
            self.extracted.draws.push(ExtractedDraw {
                entity,
                mesh: mesh.id(),
                model,
                material: material.clone(),
                casts_shadows: shadows.casts,
                receives_shadows: shadows.receives,
            });
            return;
        };
        let same_entity = draw.entity == entity;
        let material_changed = draw.material != *material;
        // An entity's unchanged material had its problems looked at when it last changed.
        if log_problems && (material_changed || !same_entity) {
            self.warnings.log_changed(entity, material);
        }
        self.extracted.same_entities &= same_entity;
        self.extracted.changed.push(slot);
        draw.entity = entity;
        draw.mesh = mesh.id();
        draw.model = model;
        draw.casts_shadows = shadows.casts;
        draw.receives_shadows = shadows.receives;
        if material_changed {
            draw.material = material.clone();
            self.extracted.changed_materials.push(slot);
        }
    }

    /// Drops last frame's draws past this frame's, and the warnings of despawned entities.
    fn finish(self, world: &World) {
        self.extracted.same_entities &= self.written == self.extracted.draws.len();
        self.extracted.draws.truncate(self.written);
        self.warnings.0.retain(|entity, _| world.contains(*entity));
    }
}
