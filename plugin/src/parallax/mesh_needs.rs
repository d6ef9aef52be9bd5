//! What the parallax material's modes need of a mesh, and the warnings where a mesh lacks it.
//!
//! The curved silhouette: the march bends each view ray by the surface's
//! curvature, which it reads from the change of the interpolated vertex normal across the pixel
//! (pom.wgsl, `normal_curvature`): a mesh without normals of its own (the flat ones generated
//! for it do not change across a triangle), without texture coordinates (no tangent frame to
//! bend in) or with triangles of no area gives it nothing there, and the material draws as
//! `off` on it (pom.wgsl's `ray_bend` is 0 where the normal or the texture coordinate does not
//! change across the pixel).
//!
//! Triplanar mapping mixes its projections by the normal: on a mesh without normals the flat
//! ones generated for it change the mix at every edge, so the texture breaks along them.
//!
//! Each such entity and mesh is warned about once.

use std::collections::HashSet;
use std::marker::PhantomData;

use glam::Vec3;
use hecs::{Entity, World};

use super::{ParallaxOcclusionMaterial, Silhouette, TextureMapping};
use crate::material::{ExtractedDraw, ExtractedMaterials};
use crate::{AssetId, Assets, Mesh, Name, Resources};

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

/// Why `mesh` gives triplanar mapping no smooth mix of its projections.
pub fn triplanar_problem(mesh: &Mesh) -> Option<String> {
    mesh.normals.is_empty().then(|| {
        "it has no normals, and the flat ones generated for it change the projections' mix at \
         every edge"
            .into()
    })
}

/// The entities (and their meshes) warned about for one mode (`Mode`: [`CurvedSilhouette`] or
/// [`TriplanarMapping`]). A resource.
#[derive(Debug)]
pub struct MeshWarnings<Mode> {
    warned: HashSet<(Entity, AssetId<Mesh>)>,
    mode: PhantomData<Mode>,
}

impl<Mode> Default for MeshWarnings<Mode> {
    fn default() -> Self {
        Self {
            warned: HashSet::new(),
            mode: PhantomData,
        }
    }
}

impl<Mode> MeshWarnings<Mode> {
    /// Whether `entity` was warned about with `mesh`.
    pub fn contains(&self, entity: Entity, mesh: AssetId<Mesh>) -> bool {
        self.warned.contains(&(entity, mesh))
    }

    /// How many entity and mesh pairs were warned about.
    pub fn len(&self) -> usize {
        self.warned.len()
    }

    /// Whether none was.
    pub fn is_empty(&self) -> bool {
        self.warned.is_empty()
    }
}

/// The curved silhouette, as a [`MeshWarnings`] mode.
#[derive(Debug)]
pub struct CurvedSilhouette;

/// Triplanar mapping, as a [`MeshWarnings`] mode.
#[derive(Debug)]
pub struct TriplanarMapping;

/// The entities a curved silhouette was warned about. A resource.
pub type CurvedSilhouetteWarnings = MeshWarnings<CurvedSilhouette>;

/// The entities triplanar mapping was warned about. A resource.
pub type TriplanarMeshWarnings = MeshWarnings<TriplanarMapping>;

/// The meshes' change count when the draws were last looked at: while the entities and the
/// meshes stay as they were, only the draws that changed are looked at again. A resource.
#[derive(Debug, Default)]
struct MeshesLookedAt(Option<u64>);

/// A parallax draw as extracted, with its material.
type DrawAndMaterial<'a> = (
    &'a ExtractedDraw<ParallaxOcclusionMaterial>,
    &'a ParallaxOcclusionMaterial,
);

/// The Extract stage's system that warns, once per entity and mesh, where a curved silhouette
/// meets a mesh that gives it no curvature ([`curvature_problem`]), or triplanar mapping one
/// without normals ([`triplanar_problem`]). It looks at the parallax draws the Extract stage
/// copied this frame: all of them where entities came, went or a mesh changed, else the changed
/// ones only.
pub fn warn_about_unsuitable_meshes(world: &mut World, resources: &mut Resources) {
    let (curved, triplanar, looked_at_all) = {
        let (Some(extracted), Some(meshes)) = (
            resources.get::<ExtractedMaterials<ParallaxOcclusionMaterial>>(),
            resources.get::<Assets<Mesh>>(),
        ) else {
            return;
        };
        let looked_at = resources.get::<MeshesLookedAt>().and_then(|seen| seen.0);
        let looked_at_all = !(extracted.same_entities && looked_at == Some(meshes.changes()));
        let draws: Vec<DrawAndMaterial<'_>> = if !looked_at_all {
            extracted
                .changed
                .iter()
                .map(|&index| (&extracted.draws[index], &extracted.materials[index]))
                .collect()
        } else {
            extracted.draws.iter().zip(&extracted.materials).collect()
        };
        let curved = unsuitable_meshes::<CurvedSilhouette>(
            (world, resources, meshes),
            &draws,
            |material| material.silhouette == Silhouette::Curved,
            curvature_problem,
            "the curved silhouette of {named} draws as off on its mesh",
        );
        let triplanar = unsuitable_meshes::<TriplanarMapping>(
            (world, resources, meshes),
            &draws,
            |material| material.mapping == TextureMapping::Triplanar,
            triplanar_problem,
            "the triplanar mapping of {named} breaks at the edges of its mesh",
        );
        (curved, triplanar, looked_at_all)
    };
    let changes = resources.get::<Assets<Mesh>>().map(Assets::changes);
    resources.insert(MeshesLookedAt(changes));
    // Where entities came or went or a mesh changed, the warnings of despawned entities and
    // freed meshes go: entities spawned and despawned every frame must not grow the sets.
    if looked_at_all {
        forget_gone::<CurvedSilhouette>(world, resources);
        forget_gone::<TriplanarMapping>(world, resources);
    }
    if !curved.is_empty() {
        resources
            .get_or_default::<CurvedSilhouetteWarnings>()
            .warned
            .extend(curved);
    }
    if !triplanar.is_empty() {
        resources
            .get_or_default::<TriplanarMeshWarnings>()
            .warned
            .extend(triplanar);
    }
}

/// Drops the warnings of `Mode` about entities that no longer exist or meshes no longer stored.
fn forget_gone<Mode: Send + Sync + 'static>(world: &World, resources: &mut Resources) {
    let Some(mut warnings) = resources.remove::<MeshWarnings<Mode>>() else {
        return;
    };
    if let Some(meshes) = resources.get::<Assets<Mesh>>() {
        warnings
            .warned
            .retain(|(entity, mesh)| world.contains(*entity) && meshes.contains(*mesh));
    }
    resources.insert(warnings);
}

/// Logs, and returns, each of `draws` not yet warned about where `applies` to the material and
/// `problem` finds one in the mesh; `what` says what happens, `{named}` standing for the entity.
fn unsuitable_meshes<Mode: Send + Sync + 'static>(
    (world, resources, meshes): (&World, &Resources, &Assets<Mesh>),
    draws: &[DrawAndMaterial<'_>],
    applies: impl Fn(&ParallaxOcclusionMaterial) -> bool,
    problem: impl Fn(&Mesh) -> Option<String>,
    what: &str,
) -> Vec<(Entity, AssetId<Mesh>)> {
    let warned = resources.get::<MeshWarnings<Mode>>();
    let mut newly = Vec::new();
    for (draw, material) in draws {
        let key = (draw.entity, draw.mesh);
        if !applies(material) || warned.is_some_and(|warned| warned.warned.contains(&key)) {
            continue;
        }
        if let Some(problem) = meshes.get(draw.mesh).and_then(&problem) {
            let named = world.get::<&Name>(draw.entity).map_or_else(
                |_| format!("{:?}", draw.entity),
                |name| format!("\"{}\"", *name),
            );
            log::warn!(
                "{} {:?}: {problem}",
                what.replace("{named}", &named),
                draw.mesh
            );
            newly.push(key);
        }
    }
    newly
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

    #[test]
    fn triplanar_mapping_needs_normals_not_texture_coordinates() {
        let no_uvs = Mesh {
            uvs: Vec::new(),
            tangents: Vec::new(),
            ..Mesh::uv_sphere(1.0, 12, 6)
        };
        assert_eq!(triplanar_problem(&no_uvs), None);
        let bare = Mesh {
            normals: Vec::new(),
            ..no_uvs
        };
        assert!(triplanar_problem(&bare).unwrap().contains("no normals"));
    }
}
