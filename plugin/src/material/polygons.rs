//! Which of a material's batches the polygon pass finds on a deferred frame
//! ([`crate::render::VisiblePolygons`]): those of a few large triangles whose visibility pass
//! only merges their keys (no fragment of theirs discards or moves the depth) and whose pixels
//! the resolve shades, so nothing after the visibility pass needs them in the depth attachment.

use glam::{Mat4, Vec3};

use super::Material;
use super::batches::{Batch, MaterialBatches};
use super::deferred::ResolveTargets;
use crate::gpu::ShaderEntry;
use crate::render::{
    DrawPhase, MAX_LISTED_TRIANGLES, MAX_POLYGON_TRIANGLES, MIN_POLYGON_PIXELS, VisiblePolygon,
};
use crate::{Assets, Mesh};

/// A material's triangles the polygon pass finds this frame.
#[derive(Debug, Default)]
pub(crate) struct ListedPolygons {
    /// For the visibility keys.
    pub(crate) visible: Vec<VisiblePolygon>,
    /// Depth-offset polygons, for the candidate keys.
    pub(crate) candidates: Vec<VisiblePolygon>,
}

impl<M: Material> MaterialBatches<M> {
    /// Lists this frame's batches the polygon pass may find (remembered for
    /// [`MaterialBatches::nearest_first`]) and returns their triangles as `targets`' camera
    /// sees them: those found for the visibility keys, then the depth-offset polygons found for
    /// the candidate keys.
    pub(crate) fn list_polygons(
        &mut self,
        meshes: &Assets<Mesh>,
        targets: &ResolveTargets<'_>,
    ) -> ListedPolygons {
        self.polygon_batches.clear();
        let mut listed = ListedPolygons::default();
        if !targets.view_projection.inverse().is_finite() {
            return listed;
        }
        // Each key's verdict once a frame: a scene of many batches has few keys.
        let mut verdicts: Vec<(M::Key, Option<bool>)> = Vec::new();
        for (index, batch) in self.batches.iter().enumerate() {
            if batch.visibility_ids.start == 0 || batch_triangles(batch) > MAX_POLYGON_TRIANGLES {
                continue;
            }
            let verdict = match verdicts.iter().find(|(key, _)| *key == batch.key) {
                Some(&(_, verdict)) => verdict,
                None => {
                    let verdict = self.found_as(batch.key);
                    verdicts.push((batch.key, verdict));
                    verdict
                }
            };
            let Some(candidate) = verdict else {
                continue;
            };
            let list = if candidate {
                &mut listed.candidates
            } else {
                &mut listed.visible
            };
            let Some(mesh) = meshes.get(batch.mesh) else {
                continue;
            };
            if batch_triangles(batch) > MAX_LISTED_TRIANGLES - list.len() {
                continue;
            }
            let polygons = self.batch_polygons(batch, mesh, targets);
            let pixels: u64 = polygons.iter().map(VisiblePolygon::pixels).sum();
            if pixels >= MIN_POLYGON_PIXELS {
                self.polygon_batches.push(index as u32);
                list.extend(polygons);
            }
        }
        listed
    }

    /// Lists no batch (a frame that runs forward).
    pub(crate) fn list_no_polygons(&mut self) -> ListedPolygons {
        self.polygon_batches.clear();
        ListedPolygons::default()
    }

    /// Whether the polygon pass may stand in for the pass that draws `key`'s polygons, and
    /// which: `Some(false)` where it draws in the visibility pass with the core's
    /// `fs_visibility`, `Some(true)` where it draws in the candidate pass (depth offset); both
    /// resolve in compute.
    fn found_as(&self, key: M::Key) -> Option<bool> {
        if !self.pipelines.resolves_in_compute(key) {
            return None;
        }
        let candidate = M::settles_depth_in_resolve(key);
        let found = if candidate {
            self.pipelines.pass_in(DrawPhase::Candidates, key).is_some()
        } else {
            self.pipelines.pass_in(DrawPhase::Prepass, key).is_some()
                && M::visibility_fragment(key) == ShaderEntry::entry("fs_visibility")
        };
        found.then_some(candidate)
    }

    /// `batch`'s triangles in world space, each instance's with its ids, that can show on
    /// `targets`.
    fn batch_polygons(
        &self,
        batch: &Batch<M::Key>,
        mesh: &Mesh,
        targets: &ResolveTargets<'_>,
    ) -> Vec<VisiblePolygon> {
        let cull = M::cull_mode(batch.key);
        let mut polygons = Vec::new();
        for slot in batch.instances.clone() {
            let Some(transform) = self.transform_data.get(slot as usize) else {
                continue;
            };
            let model = &glam::Mat4::from_cols_array_2d(&transform.model);
            if transform.first_visibility_id == 0 {
                continue;
            }
            for (triangle, corners) in mesh.indices.chunks_exact(3).enumerate() {
                let corner = |index: u32| corner_in_world(mesh, index, model);
                let (Some(a), Some(b), Some(c)) =
                    (corner(corners[0]), corner(corners[1]), corner(corners[2]))
                else {
                    continue;
                };
                let id = transform.first_visibility_id + triangle as u32;
                polygons.extend(VisiblePolygon::new(
                    [a, b, c],
                    id,
                    cull,
                    targets.view_projection,
                    targets.size,
                ));
            }
        }
        polygons
    }
}

/// Triangles a batch draws, over all its instances.
fn batch_triangles<K>(batch: &Batch<K>) -> usize {
    (batch.instances.len()).saturating_mul(batch.triangles as usize)
}

/// Vertex `index` of `mesh` placed by `model` (`None` past the mesh's vertices).
fn corner_in_world(mesh: &Mesh, index: u32, model: &Mat4) -> Option<Vec3> {
    let position = mesh.positions.get(index as usize)?;
    Some(model.transform_point3(Vec3::from_array(*position)))
}
