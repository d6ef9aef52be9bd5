//! A grid displaced by a height field: the real geometry that parallax mapping imitates, for
//! reference images and for timing parallax mapping against geometry.

use super::{Mesh, MeshError};
use crate::HeightField;

/// Most cells along one side of [`Mesh::displaced_grid`]: 8192² cells are 134 million triangles
/// and about 3 GiB of vertices, past what a frame should hold.
pub const MAX_GRID_CELLS: u32 = 8192;

impl Mesh {
    /// The plane of [`Mesh::plane_tiled`] split into `cells`×`cells` squares whose vertices sink
    /// by `(1 − h) × depth` below it, `h` being `field` sampled (bilinear, repeating) at the
    /// vertex's UV: height 1 stays on the plane, 0 is `depth` deep, as the parallax material
    /// reads a height map. Normals and tangents stay the flat plane's, so a normal map shades
    /// the grid exactly as it shades the flat plane under parallax mapping.
    pub fn displaced_grid(
        size: f32,
        tiling: f32,
        field: &HeightField,
        depth: f32,
        cells: u32,
    ) -> Result<Self, MeshError> {
        if !(1..=MAX_GRID_CELLS).contains(&cells) {
            return Err(MeshError::GridCells {
                what: "displaced grid",
                cells,
                limit: MAX_GRID_CELLS,
            });
        }
        let flat = Mesh::plane_tiled(size, tiling);
        let side = cells as usize + 1;
        let mut positions = Vec::with_capacity(side * side);
        let mut uvs = Vec::with_capacity(side * side);
        // Row by row along +Z (v), each row along +X (u), as the flat plane's UVs run.
        for row in 0..side {
            let fz = row as f32 / cells as f32;
            for column in 0..side {
                let fx = column as f32 / cells as f32;
                let uv = [fx * tiling, fz * tiling];
                let sunk = (1.0 - field.sample(uv[0], uv[1])) * depth;
                positions.push([(fx - 0.5) * size, -sunk, (fz - 0.5) * size]);
                uvs.push(uv);
            }
        }
        let mut indices = Vec::with_capacity(cells as usize * cells as usize * 6);
        for row in 0..cells {
            for column in 0..cells {
                let at = |r: u32, c: u32| r * (cells + 1) + c;
                let (near_left, far_left) = (at(row, column), at(row + 1, column));
                let (near_right, far_right) = (at(row, column + 1), at(row + 1, column + 1));
                // Counter-clockwise from above, as in the flat plane.
                indices.extend_from_slice(&[near_left, far_left, far_right]);
                indices.extend_from_slice(&[near_left, far_right, near_right]);
            }
        }
        let mesh = Mesh {
            normals: vec![flat.normals[0]; positions.len()],
            tangents: vec![flat.tangents[0]; positions.len()],
            positions,
            uvs,
            colors: Vec::new(),
            indices,
        };
        mesh.validate()?;
        Ok(mesh)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn vertices_sink_by_the_missing_height_and_keep_the_flat_frame() {
        // Height 1 in the left half of the texture, 0 in the right half.
        let field = HeightField::from_fn(4, 4, |u, _| if u < 0.5 { 1.0 } else { 0.0 });
        let mesh = Mesh::displaced_grid(2.0, 1.0, &field, 0.25, 8).unwrap();
        assert_eq!(mesh.positions.len(), 81);
        assert_eq!(mesh.triangle_count(), 128);
        let flat = Mesh::plane(2.0);
        for ((position, uv), normal) in mesh.positions.iter().zip(&mesh.uvs).zip(&mesh.normals) {
            let expected = -(1.0 - field.sample(uv[0], uv[1])) * 0.25;
            assert!((position[1] - expected).abs() < 1e-6);
            assert_eq!(*normal, flat.normals[0]);
        }
        // Texel centre of the first column: on the plane; of the third: fully sunk.
        let at = |column: usize| mesh.positions[2 * 9 + column][1];
        assert_eq!(at(1), 0.0);
        assert_eq!(at(5), -0.25);
        assert!(mesh.tangents.iter().all(|t| *t == flat.tangents[0]));
    }

    #[test]
    fn a_flat_field_gives_the_plane_and_triangles_face_up() {
        let field = HeightField::from_fn(2, 2, |_, _| 1.0);
        let mesh = Mesh::displaced_grid(1.0, 3.0, &field, 1.0, 4).unwrap();
        assert!(mesh.positions.iter().all(|p| p[1] == 0.0));
        assert_eq!(mesh.uvs.last(), Some(&[3.0, 3.0]));
        for triangle in mesh.indices.chunks(3) {
            let [a, b, c] =
                [0, 1, 2].map(|i| glam::Vec3::from(mesh.positions[triangle[i] as usize]));
            assert!((b - a).cross(c - a).y > 0.0, "counter-clockwise from above");
        }
    }

    #[test]
    fn cell_counts_outside_the_limit_are_errors() {
        let field = HeightField::from_fn(2, 2, |_, _| 1.0);
        for cells in [0, MAX_GRID_CELLS + 1] {
            let error = Mesh::displaced_grid(1.0, 1.0, &field, 1.0, cells).unwrap_err();
            assert_eq!(
                error.to_string(),
                format!("displaced grid of {cells} cells per side is outside 1..=8192")
            );
        }
    }
}
