//! Preparing a frame in place: where the view, the frame's kind and the draws' entities are
//! last frame's, only the draws the Extract stage saw change are prepared again. The order, the
//! batches and the per-draw data stay; each changed draw's entry, uniform and transform are
//! rewritten in its slot, and only those slots are compared for upload (their uniforms only
//! where the material changed or the slot was swapped). A change that moves a
//! draw to another batch or another place in the order, or a mesh or texture of the batches
//! uploaded again, leaves the frame to the full preparation.

use super::draw_entries::{bound_textures, draw_entry, prepare_textures};
use super::{MaterialBatches, PrepareInputs};
use crate::gpu::{GpuAssets, UploadStats};
use crate::material::extract::ExtractedMaterials;
use crate::material::{MAX_MATERIAL_TEXTURES, Material, MeshLodCache};
use crate::render::MeshTransform;
use crate::render::anti_aliasing::ObjectMotions;

/// The most swaps per rewritten draw that put the order right in place: past a few, sorting
/// every draw again costs less.
const MOST_SWAPS_PER_CHANGE: usize = 8;

impl<M: Material> MaterialBatches<M> {
    /// Prepares the `extracted` draws that changed, in their slots, and lists the slots whose
    /// data may differ in `dirty_slots`. Returns false where it cannot (see the module), having
    /// changed nothing the full preparation does not redo.
    pub(in crate::material) fn update_in_place(
        &mut self,
        inputs: &PrepareInputs<'_>,
        extracted: &ExtractedMaterials<M>,
        assets: &mut GpuAssets,
        lod_cache: &mut MeshLodCache,
        stats: &mut UploadStats,
        motions: &mut Option<&mut ObjectMotions>,
    ) -> bool {
        self.dirty_slots.clear();
        self.uniform_slots.clear();
        self.receded_slots.clear();
        if motions.is_some() && !self.followed.follows(extracted.draws.len()) {
            return false;
        }
        if !self.batch_assets_unchanged(inputs, assets, stats)
            || self.uniforms_serial != Some(assets.upload_serial())
            || !self.rewrite_changed_entries(inputs, extracted, assets, lod_cache, stats)
        {
            return false;
        }
        if !self.reorder_within_batches() {
            return false;
        }
        if let Some(motions) = motions {
            self.renumber_motions(extracted, motions);
        }
        self.dirty_slots.sort_unstable();
        self.dirty_slots.dedup();
        self.refresh_dirty_batches();
        true
    }

    /// Makes sure every batch's mesh and textures are on the GPU; false where one was uploaded
    /// again (its facts, and so the uniforms, may have changed).
    fn batch_assets_unchanged(
        &self,
        inputs: &PrepareInputs<'_>,
        assets: &mut GpuAssets,
        stats: &mut UploadStats,
    ) -> bool {
        let before = *stats;
        for batch in &self.batches {
            stats.meshes += u32::from(assets.prepare_mesh(inputs.gpu, inputs.meshes, batch.mesh));
            prepare_textures(inputs, batch.textures, assets, stats);
        }
        *stats == before
    }

    /// Rewrites the entry, uniform and transform of each changed draw in its slot (each array
    /// read once per draw: the slots are scattered through them); false where one leaves its
    /// batch.
    fn rewrite_changed_entries(
        &mut self,
        inputs: &PrepareInputs<'_>,
        extracted: &ExtractedMaterials<M>,
        assets: &mut GpuAssets,
        lod_cache: &mut MeshLodCache,
        stats: &mut UploadStats,
    ) -> bool {
        // Neighbouring changed draws mostly share mesh and textures: look each up once per run.
        let mut last_mesh = None;
        let mut bounds = None;
        let mut last_textures = None;
        let mut facts = [None; MAX_MATERIAL_TEXTURES];
        let mut new_materials = extracted.changed_materials.iter().peekable();
        for &index in &extracted.changed {
            let new_material = new_materials.next_if_eq(&&index).is_some();
            let (draw, material) = (&extracted.draws[index], &extracted.materials[index]);
            let slot = self.slot_of_draw[index] as usize;
            // A draw's textures come from its material alone: an unchanged one keeps its own.
            let textures = if new_material {
                bound_textures(material)
            } else {
                self.order[slot].textures
            };
            if draw.mesh != self.order[slot].mesh || textures != self.order[slot].textures {
                return false;
            }
            if last_textures != Some(textures) {
                facts = prepare_textures(inputs, textures, assets, stats);
                last_textures = Some(textures);
            }
            if last_mesh != Some(draw.mesh) {
                bounds = lod_cache.bounds(inputs.meshes, draw.mesh);
                last_mesh = Some(draw.mesh);
            }
            // The uniform depends on the material and its textures only: a draw that moved
            // keeps its own, read in draw order (the changed draws' order).
            let uniform = if new_material {
                let uniform = material.per_draw(&facts);
                // The full preparation keeps the uniforms of unchanged materials from here.
                self.uniform_data[index] = uniform;
                self.sorted_uniforms[slot] = uniform;
                self.uniform_slots.push(slot);
                uniform
            } else {
                self.uniform_data[index]
            };
            let entry = draw_entry(inputs, (draw, material, index), bounds, &uniform, textures);
            if !self.order[slot].same_batch(&entry) {
                return false;
            }
            let old_depth = self.order[slot].nearest_depth;
            // Farther, or not a number: either may lift its batch's nearest depth.
            if matches!(
                entry.nearest_depth.partial_cmp(&old_depth),
                Some(std::cmp::Ordering::Greater) | None
            ) {
                self.receded_slots.push((slot, old_depth));
            }
            self.order[slot] = entry;
            self.rewrite_transform(slot, (draw.model, draw.receives_shadows));
            self.dirty_slots.push(slot);
        }
        true
    }

    /// Rewrites the transform of `slot` where its model or shadow role changed, keeping its
    /// visibility id and motion number.
    fn rewrite_transform(&mut self, slot: usize, (model, receives_shadows): (glam::Mat4, bool)) {
        let kept = self.transform_data[slot];
        if kept.places(model, receives_shadows) {
            return;
        }
        self.transform_data[slot] = MeshTransform {
            first_visibility_id: kept.first_visibility_id,
            motion: kept.motion,
            ..MeshTransform::new(model, receives_shadows)
        };
    }

    /// Puts the rewritten entries back in order within their batches (a draw that moved
    /// nearer or farther than its neighbours) by swapping neighbours, as many times as there
    /// were pairs out of order: every pair out of order holds a slot rewritten or swapped, each
    /// of which is looked at again after its last change. A slot's batch is its batch's still
    /// (the rewrite checked it), so within one only depth and draw order. False past
    /// [`MOST_SWAPS_PER_CHANGE`] swaps a rewritten draw (the full preparation sorts faster).
    fn reorder_within_batches(&mut self) -> bool {
        let mut swaps_left = MOST_SWAPS_PER_CHANGE * self.dirty_slots.len();
        let mut unchecked = self.dirty_slots.clone();
        while let Some(slot) = unchecked.pop() {
            let Some(batch) = self.batches.get(self.batch_holding(slot)) else {
                continue;
            };
            let (start, end) = (batch.instances.start as usize, batch.instances.end as usize);
            let order = &self.order;
            let pair = if slot > start && order[slot].precedes_in_batch(&order[slot - 1]) {
                (slot - 1, slot)
            } else if slot + 1 < end && order[slot + 1].precedes_in_batch(&order[slot]) {
                (slot, slot + 1)
            } else {
                continue;
            };
            if swaps_left == 0 {
                return false;
            }
            swaps_left -= 1;
            self.swap_slots(pair);
            unchecked.extend([pair.0, pair.1]);
        }
        true
    }

    /// The index of the batch whose instances hold sorted slot `slot` (the batches' count
    /// where none does).
    fn batch_holding(&self, slot: usize) -> usize {
        self.batches
            .partition_point(|batch| batch.instances.end as usize <= slot)
    }

    /// Swaps the draws of two slots of one batch, with their per-slot data; each slot keeps
    /// its visibility id.
    fn swap_slots(&mut self, (a, b): (usize, usize)) {
        self.order.swap(a, b);
        // Neighbours mostly share a material: equal uniforms stay, and are not compared again.
        if self.sorted_uniforms[a] != self.sorted_uniforms[b] {
            self.sorted_uniforms.swap(a, b);
            self.uniform_slots.extend([a, b]);
        }
        let ids = (
            self.transform_data[a].first_visibility_id,
            self.transform_data[b].first_visibility_id,
        );
        self.transform_data.swap(a, b);
        self.transform_data[a].first_visibility_id = ids.0;
        self.transform_data[b].first_visibility_id = ids.1;
        self.slot_of_draw[self.order[a].draw] = a as u32;
        self.slot_of_draw[self.order[b].draw] = b as u32;
        self.sort_memory.swap(a, b);
        self.dirty_slots.extend([a, b]);
    }

    /// Numbers the motions of a TAA frame followed in place: the changed draws', and 0 for those
    /// that moved last frame only.
    fn renumber_motions(&mut self, extracted: &ExtractedMaterials<M>, motions: &mut ObjectMotions) {
        let changed = extracted
            .changed
            .iter()
            .map(|&index| (index, extracted.draws[index].model));
        for &(draw, number) in self.followed.number_changed_motions(changed, motions) {
            let slot = self.slot_of_draw[draw] as usize;
            if self.transform_data[slot].motion != number {
                self.transform_data[slot].motion = number;
                self.dirty_slots.push(slot);
            }
        }
    }

    /// Brings up to date the nearest depth and motion of each batch holding a dirty slot
    /// (sorted): a nearer slot lowers its batch's depth at once, and a moving one marks it
    /// moving. The batch is looked over whole only where a slot that may have been its nearest
    /// receded, or where it moved last frame and none of its dirty slots moves now.
    fn refresh_dirty_batches(&mut self) {
        self.receded_slots.sort_unstable_by_key(|&(slot, _)| slot);
        let mut start = 0;
        while let Some(&first) = self.dirty_slots.get(start) {
            let index = self.batch_holding(first);
            let Some(batch) = self.batches.get_mut(index) else {
                break;
            };
            let range = batch.instances.start as usize..batch.instances.end as usize;
            let count = self.dirty_slots[start..].partition_point(|&slot| slot < range.end);
            let slots = &self.dirty_slots[start..start + count];
            start += count;
            let receded_from = self
                .receded_slots
                .partition_point(|&(slot, _)| slot < range.start);
            let receded = self.receded_slots[receded_from..]
                .iter()
                .take_while(|&&(slot, _)| slot < range.end)
                .any(|&(_, old)| old <= batch.nearest_depth);
            let (order, transforms) = (&self.order, &self.transform_data);
            batch.nearest_depth = if receded {
                order[range.clone()]
                    .iter()
                    .map(|entry| entry.nearest_depth)
                    .fold(f32::INFINITY, f32::min)
            } else {
                slots
                    .iter()
                    .map(|&slot| order[slot].nearest_depth)
                    .fold(batch.nearest_depth, f32::min)
            };
            batch.moving = slots.iter().any(|&slot| transforms[slot].motion != 0)
                || (batch.moving && transforms[range].iter().any(|t| t.motion != 0));
        }
    }
}

/// A frame prepared in place leaves the per-draw data, the order and the batches exactly as the
/// full preparation makes them: two apps run the same edits, one always prepared in full.
#[cfg(test)]
mod tests {
    use glam::{Quat, Vec3};
    use hecs::Entity;

    use super::super::MaterialBatches;
    use crate::gpu::object_buffer::tests::read_back;
    use crate::parallax::HeightSource;
    use crate::{
        AntiAliasing, App, Assets, Camera, DirectionalLight, Image, Mesh,
        ParallaxOcclusionMaterial, PomPlugin, RenderPath, RenderPlugin, TextureKind, Transform,
    };

    type Batches = MaterialBatches<ParallaxOcclusionMaterial>;

    /// A grey height texture `side` texels square.
    fn height_image(side: u32) -> Image {
        let bytes = vec![128; (side * side * 4) as usize];
        Image::from_rgba8(side, side, bytes, TextureKind::Height).unwrap()
    }

    /// Twenty planes in a grid under a camera with `anti_aliasing`, rendered on `path`, sharing
    /// one height texture.
    fn grid_app(path: RenderPath, anti_aliasing: AntiAliasing) -> (App, Vec<Entity>) {
        let mut app = App::new();
        app.add_plugin(RenderPlugin::new(48, 48).with_path(path))
            .add_plugin(PomPlugin);
        app.finish().expect("a GPU (lavapipe in tests)");
        let plane = app
            .resources
            .get_mut::<Assets<Mesh>>()
            .unwrap()
            .add(Mesh::plane(0.9));
        let height = app
            .resources
            .get_mut::<Assets<Image>>()
            .unwrap()
            .add(height_image(4));
        let material = ParallaxOcclusionMaterial {
            height_map: Some(HeightSource::Texture(height)),
            ..Default::default()
        };
        let entities = (0..20)
            .map(|index| {
                let (x, z) = ((index % 5) as f32 - 2.0, (index / 5) as f32 - 2.0);
                app.world.spawn((
                    plane.clone(),
                    material.clone(),
                    Transform::from_xyz(x, 0.0, z),
                ))
            })
            .collect();
        app.world.spawn((
            Camera::perspective(60.0),
            anti_aliasing,
            Transform::from_xyz(0.0, 4.0, 5.0).looking_at(Vec3::ZERO, Vec3::Y),
        ));
        app.world.spawn((
            DirectionalLight::default(),
            Transform::IDENTITY.looking_at(Vec3::new(-1.0, -2.0, -1.0), Vec3::Y),
        ));
        (app, entities)
    }

    /// Frame `frame`'s edit: turns in place, a material edit, a nudge that keeps the order, a
    /// move past a few neighbours (reordered in place), the edited draw moved past the next row
    /// (its uniform swapped along), a third of the draws nudged with one
    /// material edit (prepared in full, the other uniforms kept), the height texture replaced
    /// by a larger one, the nearest row moved away alike (its batch's nearest depth rises, the
    /// order stays), and a move from nearest to farthest (past every other draw: in full).
    fn edit(app: &mut App, entities: &[Entity], frame: usize) {
        let transform = |index: usize| app.world.get::<&mut Transform>(entities[index]).unwrap();
        match frame {
            9 => {
                for index in 12..19 {
                    transform(index).translation.y += 0.001;
                }
                let mut material = app
                    .world
                    .get::<&mut ParallaxOcclusionMaterial>(entities[13])
                    .unwrap();
                material.height_scale = 0.06;
            }
            10 => {
                let Some(HeightSource::Texture(height)) = app
                    .world
                    .get::<&ParallaxOcclusionMaterial>(entities[0])
                    .unwrap()
                    .height_map
                    .clone()
                else {
                    unreachable!("every plane has a height texture")
                };
                let images = app.resources.get_mut::<Assets<Image>>().unwrap();
                *images.get_mut(&height).unwrap() = height_image(8);
            }
            2 | 7 => {
                transform(3).rotation = Quat::from_rotation_y(frame as f32 * 0.3);
                transform(7).rotation = Quat::from_rotation_y(frame as f32 * 0.2);
            }
            5 => transform(10).translation.y += 0.001,
            // Past the next row, its own uniform (its material edited on frame 4) swapped with
            // theirs.
            8 => transform(5).translation.z += 1.3,
            11 => {
                for index in 15..20 {
                    transform(index).translation.z -= 0.01;
                }
            }
            12 => transform(15).translation.z -= 10.0,
            6 => transform(0).translation.z -= 6.0,
            4 => {
                app.world
                    .get::<&mut ParallaxOcclusionMaterial>(entities[5])
                    .unwrap()
                    .height_scale = 0.08;
            }
            _ => {}
        }
    }

    /// What the batches hold after a frame, as comparable values, with what the GPU holds.
    #[derive(Debug, PartialEq)]
    struct Prepared {
        transforms: Vec<crate::render::MeshTransform>,
        uniforms: Vec<u8>,
        gpu_transforms: Vec<u8>,
        gpu_uniforms: Vec<u8>,
        draws_in_order: Vec<usize>,
        batches: Vec<(std::ops::Range<u32>, std::ops::Range<u32>, bool, u32)>,
    }

    fn prepared(app: &App) -> Prepared {
        let batches = app.resources.get::<Batches>().unwrap();
        let gpu = app.resources.get::<crate::GpuContext>().unwrap();
        // The buffers past the draws' entries hold whatever their capacity left.
        let entries_on_gpu = |buffer: &wgpu::Buffer, entries: &[u8]| {
            let mut bytes = read_back(gpu, buffer);
            bytes.truncate(entries.len());
            bytes
        };
        let transforms = bytemuck::cast_slice(&batches.transform_data);
        let uniforms = bytemuck::cast_slice(&batches.sorted_uniforms);
        Prepared {
            gpu_transforms: entries_on_gpu(batches.transforms.buffer(), transforms),
            gpu_uniforms: entries_on_gpu(batches.uniforms.buffer(), uniforms),
            transforms: batches.transform_data.clone(),
            uniforms: uniforms.to_vec(),
            draws_in_order: batches.order.iter().map(|entry| entry.draw).collect(),
            batches: batches
                .batches
                .iter()
                .map(|batch| {
                    (
                        batch.instances.clone(),
                        batch.visibility_ids.clone(),
                        batch.moving,
                        batch.nearest_depth.to_bits(),
                    )
                })
                .collect(),
        }
    }

    #[test]
    fn a_frame_prepared_in_place_equals_the_full_preparation() {
        for path in [RenderPath::Forward, RenderPath::Deferred] {
            for anti_aliasing in [AntiAliasing::Off, AntiAliasing::Taa] {
                let (mut in_place, entities) = grid_app(path, anti_aliasing);
                let (mut full, full_entities) = grid_app(path, anti_aliasing);
                let mut frames_in_place = Vec::new();
                for frame in 0..14 {
                    edit(&mut in_place, &entities, frame);
                    edit(&mut full, &full_entities, frame);
                    // Prepared from nothing: no order, no uniform kept.
                    if let Some(batches) = full.resources.get_mut::<Batches>() {
                        batches.prepared_view = None;
                        batches.uniform_data.clear();
                    }
                    in_place.update().unwrap();
                    full.update().unwrap();
                    let case = format!("{path:?}, {anti_aliasing:?}, frame {frame}");
                    assert_eq!(prepared(&in_place), prepared(&full), "{case}");
                    if in_place
                        .resources
                        .get::<Batches>()
                        .unwrap()
                        .prepared_in_place
                    {
                        frames_in_place.push(frame);
                    }
                }
                // The first frame, the frame where a third of the draws changed, the texture's
                // upload and the move past every draw are prepared in full.
                assert_eq!(
                    frames_in_place,
                    [1, 2, 3, 4, 5, 6, 7, 8, 11, 13],
                    "{path:?}, {anti_aliasing:?}"
                );
            }
        }
    }
}
