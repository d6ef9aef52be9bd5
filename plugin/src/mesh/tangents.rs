//! MikkTSpace tangents, the convention normal-map bakers use.

use glam::Vec3;

use super::Mesh;

struct MikkGeometry<'a> {
    mesh: &'a Mesh,
    tangents: Vec<[f32; 4]>,
}

impl MikkGeometry<'_> {
    fn vertex(&self, face: usize, vert: usize) -> usize {
        self.mesh.indices[face * 3 + vert] as usize
    }
}

impl bevy_mikktspace::Geometry for MikkGeometry<'_> {
    fn num_faces(&self) -> usize {
        self.mesh.indices.len() / 3
    }

    fn num_vertices_of_face(&self, _face: usize) -> usize {
        3
    }

    fn position(&self, face: usize, vert: usize) -> [f32; 3] {
        self.mesh.positions[self.vertex(face, vert)]
    }

    fn normal(&self, face: usize, vert: usize) -> [f32; 3] {
        self.mesh.normals[self.vertex(face, vert)]
    }

    fn tex_coord(&self, face: usize, vert: usize) -> [f32; 2] {
        self.mesh.uvs[self.vertex(face, vert)]
    }

    fn set_tangent(
        &mut self,
        tangent_space: Option<bevy_mikktspace::TangentSpace>,
        face: usize,
        vert: usize,
    ) {
        if let Some(space) = tangent_space {
            let vertex = self.vertex(face, vert);
            self.tangents[vertex] = space.tangent_encoded();
        }
    }
}

/// MikkTSpace tangents for a validated mesh with normals and UVs.
///
/// Vertices the algorithm leaves without a tangent (degenerate triangles, missing UVs) get an
/// arbitrary unit vector perpendicular to their normal, so shading stays finite.
pub fn generate_tangents(mesh: &Mesh) -> Vec<[f32; 4]> {
    let vertex_count = mesh.positions.len();
    let mut tangents = vec![[0.0; 4]; vertex_count];
    let complete = mesh.validate().is_ok()
        && mesh.normals.len() == vertex_count
        && mesh.uvs.len() == vertex_count;
    if complete {
        let mut geometry = MikkGeometry {
            mesh,
            tangents: std::mem::take(&mut tangents),
        };
        // The crate's error type has no variants: generation cannot fail.
        let _ = bevy_mikktspace::generate_tangents(&mut geometry);
        tangents = geometry.tangents;
    }
    for (vertex, tangent) in tangents.iter_mut().enumerate() {
        let xyz = Vec3::new(tangent[0], tangent[1], tangent[2]);
        if xyz.is_finite() && xyz.length_squared() > 1e-12 {
            continue;
        }
        let normal = mesh
            .normals
            .get(vertex)
            .map(|n| Vec3::from(*n))
            .and_then(Vec3::try_normalize)
            .unwrap_or(Vec3::Z);
        *tangent = normal.any_orthonormal_vector().extend(1.0).into();
    }
    tangents
}
