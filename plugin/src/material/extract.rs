//! The Extract stage of a material: each drawable entity's mesh, transform and material copied
//! into [`ExtractedMaterials`], and a material's problems logged once per change
//! ([`MaterialWarnings`], material_warnings.rs). An entity's material is its own component `M`,
//! or a `Handle<M>` to one shared in [`Assets<M>`], whose version tells whether it changed
//! without reading it.

use hecs::{Entity, World};

use super::Material;
use super::batches::ExtractedDraw;
use super::material_warnings::MaterialWarnings;
use super::registry::MaterialRegistry;
use crate::{
    AssetId, Assets, GlobalTransform, Handle, Mesh, NotShadowCaster, NotShadowReceiver, Resources,
};

/// This frame's draws of `M`, as extracted, and which of them changed since the last frame.
/// A resource.
pub(crate) struct ExtractedMaterials<M> {
    pub(crate) draws: Vec<ExtractedDraw<M>>,
    /// Each draw's material, in the draws' order.
    pub(crate) materials: Vec<M>,
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

/// Where an entity's material is: its own component, or a shared one in [`Assets<M>`] at
/// `version`.
enum Source<'a, M> {
    Own(&'a M),
    Shared {
        id: AssetId<M>,
        version: u64,
        material: &'a M,
    },
}

// By hand: derived, they would ask `M: Copy`.
impl<M> Clone for Source<'_, M> {
    fn clone(&self) -> Self {
        *self
    }
}
impl<M> Copy for Source<'_, M> {}

/// Whether a draw casts and receives scene shadows (its marker components).
#[derive(Clone, Copy)]
struct ShadowRoles {
    casts: bool,
    receives: bool,
}

impl ShadowRoles {
    /// The roles of an entity with or without each marker.
    fn of(not_caster: Option<&NotShadowCaster>, not_receiver: Option<&NotShadowReceiver>) -> Self {
        Self {
            casts: not_caster.is_none(),
            receives: not_receiver.is_none(),
        }
    }
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
            materials: Vec::new(),
            changed: Vec::new(),
            changed_materials: Vec::new(),
            same_entities: false,
            casters_read_frame_noise: false,
        });
    }
    if !resources.contains::<MaterialWarnings<M>>() {
        resources.insert(MaterialWarnings::<M>::default());
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
    writer.push_entities(world, resources.get::<Assets<M>>());
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
    /// Writes every entity that has material `M` of its own, a mesh and a transform, then every
    /// one that holds a handle to a shared `M` instead (one with both draws with its own).
    fn push_entities(&mut self, world: &World, shared: Option<&Assets<M>>) {
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
            let shadows = ShadowRoles::of(not_caster, not_receiver);
            self.push(
                entity,
                true,
                mesh,
                transform,
                Source::Own(material),
                shadows,
            );
        }
        let Some(assets) = shared else {
            return;
        };
        for (entity, mesh, transform, handle, not_caster, not_receiver) in world
            .query::<(
                Entity,
                &Handle<Mesh>,
                &GlobalTransform,
                &Handle<M>,
                Option<&NotShadowCaster>,
                Option<&NotShadowReceiver>,
            )>()
            .without::<&M>()
            .iter()
        {
            let Some((material, version)) = assets.get_with_version(handle) else {
                self.warnings.log_problems(
                    entity,
                    vec![format!(
                        "its handle {:?} is to no material in the app's Assets<{}>: not drawn",
                        handle.id(),
                        M::NAME
                    )],
                );
                continue;
            };
            let shadows = ShadowRoles::of(not_caster, not_receiver);
            let source = Source::Shared {
                id: handle.id(),
                version,
                material,
            };
            self.push(entity, true, mesh, transform, source, shadows);
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
                    self.push(
                        entity,
                        false,
                        mesh,
                        transform,
                        Source::Own(&default),
                        shadows,
                    );
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
        source: Source<'_, M>,
        shadows: ShadowRoles,
    ) {
        let (material, shared) = match source {
            Source::Own(material) => (material, None),
            Source::Shared {
                id,
                version,
                material,
            } => (material, Some((id, version))),
        };
        let model = transform.to_mat4();
        let slot = self.written;
        // Last frame's draw in this slot, where it is this one unchanged: nothing to write (its
        // transform was finite then). A shared material is told unchanged by its version, an
        // own one by comparing it.
        if let Some(last) = self.extracted.draws.get(slot)
            && last.entity == entity
            && last.model == model
            && last.mesh == mesh.id()
            && last.shared == shared
            && (last.casts_shadows, last.receives_shadows) == (shadows.casts, shadows.receives)
            && (shared.is_some() || self.extracted.materials[slot] == *material)
        {
            self.extracted.casters_read_frame_noise |= last.casts_with_frame_noise;
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
        let draw = ExtractedDraw {
            model,
            entity,
            mesh: mesh.id(),
            shared,
            casts_shadows: shadows.casts,
            receives_shadows: shadows.receives,
            casts_with_frame_noise: shadows.casts && material.casts_with_frame_noise(),
        };
        self.extracted.casters_read_frame_noise |= draw.casts_with_frame_noise;
        self.written += 1;
        self.write(slot, draw, material, log_problems);
    }

    /// Writes `draw` and its `material` into `slot` (past the last: a new slot), listing it as
    /// changed. Not inlined: the loop over the unchanged draws stays small.
    #[inline(never)]
    fn write(&mut self, slot: usize, draw: ExtractedDraw<M>, material: &M, log_problems: bool) {
        let entity = draw.entity;
        let Some(last) = self.extracted.draws.get_mut(slot) else {
            if log_problems {
                self.warnings.log_draw(&draw, material);
            }
            self.extracted.same_entities = false;
            self.extracted.draws.push(draw);
            self.extracted.materials.push(material.clone());
            return;
        };
        let same_entity = last.entity == entity;
        // A shared material accessed mutably but left as it was is not a new material.
        let material_changed = self.extracted.materials[slot] != *material;
        // An entity's unchanged material had its problems looked at when it last changed.
        if log_problems && (material_changed || !same_entity) {
            self.warnings.log_draw(&draw, material);
        }
        self.extracted.same_entities &= same_entity;
        self.extracted.changed.push(slot);
        *last = draw;
        if material_changed {
            self.extracted.materials[slot] = material.clone();
            self.extracted.changed_materials.push(slot);
        }
    }

    /// Drops last frame's draws past this frame's, and the warnings of despawned entities.
    fn finish(self, world: &World) {
        self.extracted.same_entities &= self.written == self.extracted.draws.len();
        self.extracted.draws.truncate(self.written);
        self.extracted.materials.truncate(self.written);
        self.warnings
            .entities
            .retain(|entity, _| world.contains(*entity));
        // A shared material no draw holds any more is forgotten.
        if !self.warnings.shared.is_empty() {
            let held: std::collections::HashSet<AssetId<M>> = self
                .extracted
                .draws
                .iter()
                .filter_map(|draw| draw.shared.map(|(id, _)| id))
                .collect();
            self.warnings.shared.retain(|id, _| held.contains(id));
        }
    }
}

#[cfg(test)]
mod tests {
    use glam::Affine3A;

    use super::*;
    use crate::ParallaxOcclusionMaterial;

    type Pom = ParallaxOcclusionMaterial;

    /// A world of `own` entities with a material of their own and `shared` holding a handle to
    /// one material in the resources' store; returns the store's handle.
    fn scene(own: usize, shared: usize) -> (World, Resources, Handle<Pom>) {
        let mut world = World::new();
        let mut resources = Resources::default();
        let mesh = resources
            .get_or_default::<Assets<Mesh>>()
            .add(Mesh::plane(1.0));
        let handle = resources
            .get_or_default::<Assets<Pom>>()
            .add(Pom::default());
        for index in 0..own + shared {
            let place = GlobalTransform(Affine3A::from_translation(glam::Vec3::X * index as f32));
            if index < own {
                world.spawn((mesh.clone(), place, Pom::default()));
            } else {
                world.spawn((mesh.clone(), place, handle.clone()));
            }
        }
        (world, resources, handle)
    }

    fn extract(world: &mut World, resources: &mut Resources) -> (Vec<usize>, Vec<usize>, bool) {
        extract_materials::<Pom>(world, resources);
        let extracted = resources.get::<ExtractedMaterials<Pom>>().unwrap();
        (
            extracted.changed.clone(),
            extracted.changed_materials.clone(),
            extracted.same_entities,
        )
    }

    #[test]
    fn a_shared_material_is_told_unchanged_by_its_version_and_changed_for_every_holder() {
        let (mut world, mut resources, handle) = scene(2, 3);
        let (_, _, same) = extract(&mut world, &mut resources);
        assert!(!same, "the first frame's draws are new");
        assert_eq!(extract(&mut world, &mut resources), (vec![], vec![], true));

        resources
            .get_mut::<Assets<Pom>>()
            .unwrap()
            .get_mut(&handle)
            .unwrap()
            .height_scale = 0.1;
        let (changed, changed_materials, same) = extract(&mut world, &mut resources);
        assert_eq!(
            (changed, changed_materials, same),
            (vec![2, 3, 4], vec![2, 3, 4], true)
        );
        let extracted = resources.get::<ExtractedMaterials<Pom>>().unwrap();
        let scales: Vec<f32> = extracted.materials.iter().map(|m| m.height_scale).collect();
        assert_eq!(scales, [0.05, 0.05, 0.1, 0.1, 0.1]);
        assert_eq!(extract(&mut world, &mut resources), (vec![], vec![], true));

        // Accessed mutably and left as it was: the new version is noted, the material is not new.
        resources.get_mut::<Assets<Pom>>().unwrap().get_mut(&handle);
        assert_eq!(
            extract(&mut world, &mut resources),
            (vec![2, 3, 4], vec![], true)
        );
        assert_eq!(extract(&mut world, &mut resources), (vec![], vec![], true));
    }

    #[test]
    fn a_handle_swapped_for_another_changes_its_draw_alone() {
        let (mut world, mut resources, _) = scene(0, 3);
        extract(&mut world, &mut resources);
        let other = resources.get_mut::<Assets<Pom>>().unwrap().add(Pom {
            jitter_march: true,
            ..Pom::default()
        });
        let entity = world.iter().nth(1).unwrap().entity();
        world.insert_one(entity, other).unwrap();
        let (changed, changed_materials, _) = extract(&mut world, &mut resources);
        // The entity moved to another archetype: it is drawn last now, in another slot.
        assert!(!changed.is_empty() && changed == changed_materials);
        let extracted = resources.get::<ExtractedMaterials<Pom>>().unwrap();
        let slot = extracted
            .draws
            .iter()
            .position(|draw| draw.entity == entity)
            .unwrap();
        assert!(extracted.materials[slot].jitter_march);
        assert!(extracted.draws[slot].casts_with_frame_noise);
        assert!(extracted.casters_read_frame_noise);
        assert_eq!(extract(&mut world, &mut resources), (vec![], vec![], true));
        // Left alone, its draw still says its material reads the frame's noise.
        assert!(
            resources
                .get::<ExtractedMaterials<Pom>>()
                .unwrap()
                .casters_read_frame_noise
        );
    }

    #[test]
    fn an_entity_with_its_own_material_and_a_handle_draws_once_with_its_own() {
        let (mut world, mut resources, handle) = scene(1, 0);
        let entity = world.iter().next().unwrap().entity();
        world.insert_one(entity, handle).unwrap();
        extract(&mut world, &mut resources);
        let extracted = resources.get::<ExtractedMaterials<Pom>>().unwrap();
        assert_eq!(extracted.draws.len(), 1);
        assert_eq!(extracted.draws[0].shared, None);
    }

    #[test]
    fn a_bad_shared_material_is_warned_about_once_for_all_that_hold_it() {
        let (mut world, mut resources, handle) = scene(1, 50);
        let own = world.iter().next().unwrap().entity();
        world.get::<&mut Pom>(own).unwrap().max_samples = 0;
        extract(&mut world, &mut resources);
        let store = resources.get_mut::<Assets<Pom>>().unwrap();
        store.get_mut(&handle).unwrap().height_scale = f32::NAN;
        extract(&mut world, &mut resources);
        let warnings = resources.get::<MaterialWarnings<Pom>>().unwrap();
        assert_eq!((warnings.entities.len(), warnings.shared.len()), (1, 1));
        assert!(warnings.shared.contains_key(&handle.id()));

        // The entity with a bad material of its own takes the shared one: its warning goes.
        world.remove_one::<Pom>(own).unwrap();
        world.insert_one(own, handle.clone()).unwrap();
        extract(&mut world, &mut resources);
        let warnings = resources.get::<MaterialWarnings<Pom>>().unwrap();
        assert_eq!((warnings.entities.len(), warnings.shared.len()), (0, 1));

        let store = resources.get_mut::<Assets<Pom>>().unwrap();
        store.get_mut(&handle).unwrap().height_scale = 0.05;
        extract(&mut world, &mut resources);
        assert!(resources.get::<MaterialWarnings<Pom>>().unwrap().is_empty());
    }

    #[test]
    fn a_handle_to_no_material_in_the_store_is_not_drawn_and_warned_about_once() {
        let (mut world, mut resources, _) = scene(1, 1);
        // A handle of another store: no material of the app's has its id's generation.
        let mut elsewhere = Assets::<Pom>::default();
        elsewhere.add(Pom::default());
        let stranger = elsewhere.add(Pom::default());
        let mesh = resources
            .get_mut::<Assets<Mesh>>()
            .unwrap()
            .add(Mesh::plane(1.0));
        let lost = world.spawn((mesh, GlobalTransform(Affine3A::IDENTITY), stranger));
        for _ in 0..3 {
            extract(&mut world, &mut resources);
            let extracted = resources.get::<ExtractedMaterials<Pom>>().unwrap();
            assert_eq!(extracted.draws.len(), 2);
            assert!(extracted.draws.iter().all(|draw| draw.entity != lost));
            let warnings = resources.get::<MaterialWarnings<Pom>>().unwrap();
            assert_eq!(
                (warnings.len(), warnings.entities.contains_key(&lost)),
                (1, true)
            );
        }
        world.despawn(lost).unwrap();
        extract(&mut world, &mut resources);
        assert!(resources.get::<MaterialWarnings<Pom>>().unwrap().is_empty());
    }
}
