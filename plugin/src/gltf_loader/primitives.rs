//! glTF mesh primitives to [`Mesh`]es.

use glam::{Affine2, Vec2};

use super::{GltfError, Source, describe};
use crate::{Mesh, MeshError};

/// The most vertices one glTF file's meshes may decode to, counted as drawn (a primitive
/// without normals gets three of its own per triangle): a small file whose primitives share a
/// large accessor, or whose few vertices many small indices reuse, could otherwise ask for
/// gigabytes.
pub const MAX_GLTF_VERTICES: u64 = 1 << 25;

/// The vertices `primitive` decodes to, from its accessors' counts before anything is read:
/// one per index where it has no normals (flat normals split them), else one per position.
pub(super) fn decoded_vertices(primitive: &gltf::Primitive<'_>) -> u64 {
    let positions = primitive
        .get(&gltf::Semantic::Positions)
        .map_or(0, |accessor| accessor.count());
    let indices = primitive
        .indices()
        .map_or(positions, |accessor| accessor.count());
    let drawn = if primitive.get(&gltf::Semantic::Normals).is_none() {
        indices
    } else {
        positions
    };
    drawn as u64
}

/// The vertex data of one triangle primitive, with the material's texture transform baked into
/// its coordinates, missing normals (flat) and tangents (MikkTSpace) generated.
pub(super) fn read_primitive(
    source: &Source,
    mesh: &gltf::Mesh<'_>,
    primitive: &gltf::Primitive<'_>,
    uv_transform: Affine2,
) -> Result<Mesh, GltfError> {
    let mesh_error = |reason: String| GltfError::Mesh {
        path: source.path.clone(),
        mesh: describe(mesh.name(), mesh.index()),
        primitive: primitive.index(),
        reason,
    };
    // Readers return None for a buffer that is missing or an accessor that runs past its data.
    let reader =
        primitive.reader(|buffer| source.buffers.get(buffer.index()).map(|data| &data.0[..]));
    let positions: Vec<[f32; 3]> = reader
        .read_positions()
        .ok_or_else(|| mesh_error("POSITION is missing or lies outside its buffer".into()))?
        .collect();
    let vertex_count = positions.len();
    let normals: Vec<[f32; 3]> = reader
        .read_normals()
        .map(Iterator::collect)
        .unwrap_or_default();
    let mut uvs: Vec<[f32; 2]> = reader
        .read_tex_coords(0)
        .map(|coords| coords.into_f32().collect())
        .unwrap_or_default();
    // glTF's bitangent, cross(normal, tangent) × w, points up the image (−v); ours is dP/dv.
    let mut tangents: Vec<[f32; 4]> = reader
        .read_tangents()
        .map(|tangents| tangents.map(|[x, y, z, w]| [x, y, z, -w]).collect())
        .unwrap_or_default();
    let colors: Vec<[f32; 4]> = reader
        .read_colors(0)
        .map(|colors| colors.into_rgba_f32().collect())
        .unwrap_or_default();
    let indices: Vec<u32> = match reader.read_indices() {
        Some(indices) => indices.into_u32().collect(),
        None => (0..vertex_count as u32).collect(),
    };
    if uv_transform != Affine2::IDENTITY {
        for uv in &mut uvs {
            *uv = uv_transform.transform_point2(Vec2::from(*uv)).into();
        }
        // A rotated or mirrored mapping turns the tangent frame: derive it again.
        tangents.clear();
    }
    if normals.is_empty() {
        // Flat normals split shared vertices, so any file tangents no longer line up.
        tangents.clear();
    }
    Mesh {
        positions,
        normals,
        uvs,
        tangents,
        colors,
        indices,
    }
    .with_generated_attributes()
    .map_err(|error| mesh_error(in_gltf_terms(&error)))
}

/// `error` with the attribute named as the file names it.
fn in_gltf_terms(error: &MeshError) -> String {
    match error {
        MeshError::NonFiniteAttribute { attribute, vertex } => {
            let semantic = match *attribute {
                "normals" => "NORMAL",
                "uvs" => "TEXCOORD_0 (after KHR_texture_transform, if any)",
                "tangents" => "TANGENT",
                "colors" => "COLOR_0",
                other => other,
            };
            format!("{semantic} of vertex {vertex} is not finite")
        }
        other => other.to_string(),
    }
}
