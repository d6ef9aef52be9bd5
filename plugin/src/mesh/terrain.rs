//! A terrain: a grid raised by a height image, with smooth normals and tangents from the
//! height's slope, for the ground that layered parallax materials paint.

use glam::{Vec2, Vec3};

use super::{MAX_GRID_CELLS, Mesh, MeshError};
use crate::HeightField;

impl Mesh {
    /// A terrain `size.x` × `size.z` world units across, centred on the origin, of
    /// `cells`×`cells` squares, each vertex raised by `field` times `size.y` (height 0 on the
    /// plane y = 0, height 1 at `size.y`). The field is sampled bilinearly between its texel
    /// centres and never wraps: its first and last texels are the terrain's edges, its first
    /// row at −Z. UVs run 0..1 across the whole terrain (U along +X, V along +Z; a material's
    /// tiling repeats its textures over it); normals and tangents follow the slope, so a
    /// normal map shades a hillside as it shades a plane.
    ///
    /// # Errors
    /// [`MeshError::GridCells`] for `cells` outside 1..=[`MAX_GRID_CELLS`],
    /// [`MeshError::TerrainSize`] for a size that is not finite or not positive across.
    pub fn terrain(field: &HeightField, size: Vec3, cells: u32) -> Result<Self, MeshError> {
        if !(1..=MAX_GRID_CELLS).contains(&cells) {
            return Err(MeshError::GridCells {
                what: "terrain",
                cells,
                limit: MAX_GRID_CELLS,
            });
        }
        if !(size.is_finite() && size.x > 0.0 && size.z > 0.0 && size.y >= 0.0) {
            return Err(MeshError::TerrainSize(size.to_array()));
        }
        let side = cells as usize + 1;
        let step = 1.0 / cells as f32;
        let uv_at = |row: usize, column: usize| Vec2::new(column as f32, row as f32) * step;
        // Each vertex's height, sampled once: the slopes below read the neighbours' from here.
        let heights: Vec<f32> = (0..side * side)
            .map(|at| clamped_sample(field, uv_at(at / side, at % side)) * size.y)
            .collect();
        let vertex_count = side * side;
        let mut mesh = Mesh {
            positions: Vec::with_capacity(vertex_count),
            normals: Vec::with_capacity(vertex_count),
            uvs: Vec::with_capacity(vertex_count),
            tangents: Vec::with_capacity(vertex_count),
            colors: Vec::new(),
            indices: Vec::with_capacity(cells as usize * cells as usize * 6),
        };
        for row in 0..side {
            for column in 0..side {
                let uv = uv_at(row, column);
                let height = heights[row * side + column];
                mesh.positions
                    .push([(uv.x - 0.5) * size.x, height, (uv.y - 0.5) * size.z]);
                mesh.uvs.push(uv.to_array());
                // The slope across the neighbouring vertices (one-sided at the edges), per
                // unit of U or V, from the heights at (row, column) index pairs.
                let across = |low: (usize, usize), high: (usize, usize), span: usize| {
                    (heights[high.0 * side + high.1] - heights[low.0 * side + low.1])
                        / (span as f32 * step)
                };
                let (left, right) = (column.saturating_sub(1), (column + 1).min(cells as usize));
                let (near, far) = (row.saturating_sub(1), (row + 1).min(cells as usize));
                let slope_u = across((row, left), (row, right), right - left);
                let slope_v = across((near, column), (far, column), far - near);
                // World-space derivatives of the surface along U (+X) and V (+Z).
                let along_u = Vec3::new(size.x, slope_u, 0.0);
                let along_v = Vec3::new(0.0, slope_v, size.z);
                let normal = along_v.cross(along_u).normalize();
                let tangent = (along_u - normal * normal.dot(along_u)).normalize();
                // The sign that makes normal × tangent × sign run along V, as MikkTSpace's.
                let sign = normal.cross(tangent).dot(along_v).signum();
                mesh.normals.push(normal.to_array());
                mesh.tangents.push(tangent.extend(sign).to_array());
            }
        }
        for row in 0..cells {
            for column in 0..cells {
                let at = |r: u32, c: u32| r * (cells + 1) + c;
                let (near_left, far_left) = (at(row, column), at(row + 1, column));
                let (near_right, far_right) = (at(row, column + 1), at(row + 1, column + 1));
                // Counter-clockwise from above, as the plane's.
                mesh.indices
                    .extend_from_slice(&[near_left, far_left, far_right]);
                mesh.indices
                    .extend_from_slice(&[near_left, far_right, near_right]);
            }
        }
        mesh.validate()?;
        Ok(mesh)
    }
}

/// The field at `uv` (0..1 from its first texel's centre to its last's), bilinear, clamped.
fn clamped_sample(field: &HeightField, uv: Vec2) -> f32 {
    let (width, height) = field.size();
    let texel = uv * Vec2::new(width as f32 - 1.0, height as f32 - 1.0);
    let first = texel.floor();
    let fraction = texel - first;
    let at = |x: f32, y: f32| {
        let x = (x as i64).clamp(0, i64::from(width) - 1);
        let y = (y as i64).clamp(0, i64::from(height) - 1);
        field.texel(x, y)
    };
    let top = at(first.x, first.y) * (1.0 - fraction.x) + at(first.x + 1.0, first.y) * fraction.x;
    let bottom = at(first.x, first.y + 1.0) * (1.0 - fraction.x)
        + at(first.x + 1.0, first.y + 1.0) * fraction.x;
    top * (1.0 - fraction.y) + bottom * fraction.y
}

#[cfg(test)]
mod tests {
    use glam::Vec3;

    use super::*;

    #[test]
    fn a_flat_field_is_a_plane_facing_up_with_the_planes_frame() {
        let field = HeightField::from_fn(3, 3, |_, _| 0.5);
        let mesh = Mesh::terrain(&field, Vec3::new(4.0, 2.0, 6.0), 4).unwrap();
        assert_eq!((mesh.positions.len(), mesh.triangle_count()), (25, 32));
        assert!(mesh.positions.iter().all(|p| p[1] == 1.0));
        assert_eq!(mesh.positions[0], [-2.0, 1.0, -3.0]);
        assert_eq!(mesh.positions[24], [2.0, 1.0, 3.0]);
        assert_eq!((mesh.uvs[0], mesh.uvs[24]), ([0.0, 0.0], [1.0, 1.0]));
        let plane = Mesh::plane(1.0);
        assert!(mesh.normals.iter().all(|n| *n == [0.0, 1.0, 0.0]));
        assert!(mesh.tangents.iter().all(|t| *t == plane.tangents[0]));
        for triangle in mesh.indices.chunks(3) {
            let [a, b, c] = [0, 1, 2].map(|i| Vec3::from(mesh.positions[triangle[i] as usize]));
            assert!((b - a).cross(c - a).y > 0.0, "counter-clockwise from above");
        }
    }

    #[test]
    fn a_ramp_tilts_the_normals_and_tangents_by_its_slope() {
        // Height rising from 0 at the first column to 1 at the last, across 8 world units,
        // 2 units high: a slope of 1/4 along +X.
        let field = HeightField::new(5, 2, [0.0, 0.25, 0.5, 0.75, 1.0].repeat(2)).unwrap();
        let mesh = Mesh::terrain(&field, Vec3::new(8.0, 2.0, 8.0), 8).unwrap();
        let expected_normal = Vec3::new(-0.25, 1.0, 0.0).normalize();
        let expected_tangent = Vec3::new(1.0, 0.25, 0.0).normalize();
        for ((position, normal), tangent) in
            mesh.positions.iter().zip(&mesh.normals).zip(&mesh.tangents)
        {
            assert!(
                (position[1] - (position[0] + 4.0) / 4.0).abs() < 1e-5,
                "{position:?}"
            );
            assert!(
                Vec3::from(*normal).abs_diff_eq(expected_normal, 1e-5),
                "{normal:?}"
            );
            let tangent = glam::Vec4::from(*tangent);
            assert!(
                tangent.truncate().abs_diff_eq(expected_tangent, 1e-5),
                "{tangent:?}"
            );
            assert_eq!(tangent.w, -1.0);
        }
    }

    #[test]
    fn the_fields_corner_texels_are_the_terrains_corners() {
        let field = HeightField::new(2, 2, vec![0.0, 1.0, 0.25, 0.5]).unwrap();
        let mesh = Mesh::terrain(&field, Vec3::new(1.0, 4.0, 1.0), 3).unwrap();
        let corners = [0, 3, 12, 15].map(|i| mesh.positions[i][1]);
        assert_eq!(corners, [0.0, 4.0, 1.0, 2.0]);
    }

    #[test]
    fn bad_cell_counts_and_sizes_are_errors_naming_them() {
        let field = HeightField::from_fn(2, 2, |_, _| 1.0);
        let size = Vec3::ONE;
        for cells in [0, MAX_GRID_CELLS + 1] {
            let error = Mesh::terrain(&field, size, cells).unwrap_err();
            assert_eq!(
                error.to_string(),
                format!("terrain of {cells} cells per side is outside 1..=8192")
            );
        }
        for bad in [
            Vec3::new(0.0, 1.0, 1.0),
            Vec3::new(1.0, 1.0, -2.0),
            Vec3::new(1.0, -1.0, 1.0),
            Vec3::new(1.0, f32::NAN, 1.0),
            Vec3::new(f32::INFINITY, 1.0, 1.0),
        ] {
            let error = Mesh::terrain(&field, bad, 4).unwrap_err();
            assert!(error.to_string().starts_with("terrain size"), "{error}");
            assert!(error.to_string().contains(&format!("{}", bad.x)), "{error}");
        }
    }
}
