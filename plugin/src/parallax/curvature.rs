//! What the curved silhouette needs of a mesh. The march bends each view ray by the surface's
//! curvature, which it reads from the change of the interpolated vertex normal across the pixel
//! (pom.wgsl, `normal_curvature`): a mesh without normals of its own (the flat ones generated
//! for it do not change across a triangle), without texture coordinates (no tangent frame to
//! bend in) or with triangles of no area gives it nothing there, and the material draws as
//! `off` on it (pom.wgsl's `ray_bend` is 0 where the normal or the texture coordinate does not
//! change across the pixel). Each such entity and mesh is warned about once.

use std::collections::HashSet;

use glam::Vec3;
use hecs::{Entity, World};

use super::{ParallaxOcclusionMaterial, Silhouette};
use crate::{AssetId, Assets, Handle, Mesh, Name, Resources};

/// Why `mesh` gives the curved silhouette no curvature (everywhere, or on some triangles).
pub fn curvature_problem(mesh: &Mesh) -> Option<String> {
    if mesh.normals.is_empty() {
        return Some("it has no normals (the flat ones generated for it do not curve)".into());
    }
    if mesh.uvs.is_empty() {
        return Some("it has no texture coordinates (no tangent frame to bend rays in)".into());
    }
    let degenerate = mesh
        .indices
        .chunks_exact(3)
        .filter(|triangle| {
            let [a, b, c] = [0, 1, 2].map(|k| {
                mesh.positions
                    .get(triangle[k] as usize)
                    .map_or(Vec3::ZERO, |&p| Vec3::from(p))
            });
            let (ab, ac) = (b - a, c - a);
            // No area, relative to the triangle's size (a sliver of rounding is no triangle).
            ab.cross(ac).length_squared() <= 1e-12 * ab.length_squared() * ac.length_squared()
        })
        .count();
    (degenerate > 0).then(|| {
        format!(
            "{degenerate} of its {} triangles have no area",
            mesh.triangle_count()
        )
    })
}

/// The entities (and their meshes) a curved silhouette was warned about. A resource.
#[derive(Debug, Default)]
pub struct CurvedSilhouetteWarnings(HashSet<(Entity, AssetId<Mesh>)>);

impl CurvedSilhouetteWarnings {
    /// Whether `entity` was warned about with `mesh`.
    pub fn contains(&self, entity: Entity, mesh: AssetId<Mesh>) -> bool {
        self.0.contains(&(entity, mesh))
    }

    /// How many entity and mesh pairs were warned about.
    pub fn len(&self) -> usize {
        self.0.len()
    }

    /// Whether none was.
    pub fn is_empty(&self) -> bool {
        self.0.is_empty()
    }
}

/// The Extract stage's system that warns, once per entity and mesh, where a curved silhouette
/// meets a mesh that gives it no curvature ([`curvature_problem`]).
pub fn warn_about_meshes_without_curvature(world: &mut World, resources: &mut Resources) {
    let Some(meshes) = resources.get::<Assets<Mesh>>() else {
        return;
    };
    let warned = resources.get::<CurvedSilhouetteWarnings>();
    let mut newly = Vec::new();
    for (entity, mesh, material, name) in world
        .query::<(
            Entity,
            &Handle<Mesh>,
            &ParallaxOcclusionMaterial,
            Option<&Name>,
        )>()
        .iter()
    {
        let key = (entity, mesh.id());
        if material.silhouette != Silhouette::Curved
            || warned.is_some_and(|warned| warned.0.contains(&key))
        {
            continue;
        }
        if let Some(problem) = meshes.get(mesh).and_then(curvature_problem) {
            let named = name.map_or_else(|| format!("{entity:?}"), |name| format!("\"{name}\""));
            log::warn!(
                "the curved silhouette of {named} draws as off on its mesh {:?}: {problem}",
                mesh.id()
            );
            newly.push(key);
        }
    }
    if !newly.is_empty() {
        resources
            .get_or_default::<CurvedSilhouetteWarnings>()
            .0
            .extend(newly);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_missing_piece_of_curvature_is_named() {
        assert_eq!(curvature_problem(&Mesh::uv_sphere(1.0, 12, 6)), None);
        let bare = Mesh {
            normals: Vec::new(),
            ..Mesh::cube(1.0)
        };
        assert!(curvature_problem(&bare).unwrap().contains("no normals"));
        let no_uvs = Mesh {
            uvs: Vec::new(),
            ..Mesh::cube(1.0)
        };
        assert!(
            curvature_problem(&no_uvs)
                .unwrap()
                .contains("no texture coordinates")
        );
        let mut degenerate = Mesh::cube(1.0);
        degenerate.indices.extend([0, 0, 1]);
        assert_eq!(
            curvature_problem(&degenerate).unwrap(),
            "1 of its 13 triangles have no area"
        );
    }
}
