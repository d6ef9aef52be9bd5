//! Built-in shapes, each with positions, normals, UVs and MikkTSpace tangents.

use std::f32::consts::{PI, TAU};

use glam::Vec3;

use super::{Mesh, generate_tangents};

/// The faces of [`Mesh::cube`]: (outward normal, u axis, v axis), u running to the right and
/// v up the image as seen from outside, with u × v = normal so the winding faces outwards.
pub(crate) const CUBE_FACES: [(Vec3, Vec3, Vec3); 6] = [
    (Vec3::X, Vec3::NEG_Z, Vec3::Y),
    (Vec3::NEG_X, Vec3::Z, Vec3::Y),
    (Vec3::Y, Vec3::X, Vec3::NEG_Z),
    (Vec3::NEG_Y, Vec3::X, Vec3::Z),
    (Vec3::Z, Vec3::X, Vec3::Y),
    (Vec3::NEG_Z, Vec3::NEG_X, Vec3::Y),
];

impl Mesh {
    /// A square of side `size` in the XZ plane facing +Y, UV 0..1 across it (u along +X,
    /// v along +Z).
    pub fn plane(size: f32) -> Self {
        Self::plane_tiled(size, 1.0)
    }

    /// Like [`Mesh::plane`] with UVs running 0..`tiling`, so a texture repeats `tiling` times.
    pub fn plane_tiled(size: f32, tiling: f32) -> Self {
        let half = size * 0.5;
        let corners = [(-1.0, -1.0), (-1.0, 1.0), (1.0, 1.0), (1.0, -1.0)];
        let mut mesh = Mesh {
            positions: corners.map(|(x, z)| [x * half, 0.0, z * half]).to_vec(),
            normals: vec![[0.0, 1.0, 0.0]; 4],
            uvs: corners
                .map(|(x, z)| [(x + 1.0) * 0.5 * tiling, (z + 1.0) * 0.5 * tiling])
                .to_vec(),
            tangents: Vec::new(),
            colors: Vec::new(),
            indices: vec![0, 1, 2, 0, 2, 3],
        };
        mesh.tangents = generate_tangents(&mesh);
        mesh
    }

    /// An axis-aligned cube of side `size` centred on the origin; each face has UV 0..1.
    pub fn cube(size: f32) -> Self {
        let half = size * 0.5;
        let mut mesh = Mesh::default();
        for (normal, u_axis, v_axis) in CUBE_FACES {
            let first = mesh.positions.len() as u32;
            for (s, t) in [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)] {
                mesh.positions
                    .push(((normal + u_axis * s + v_axis * t) * half).into());
                mesh.normals.push(normal.into());
                // Image rows run downwards, so v grows as t falls.
                mesh.uvs.push([(s + 1.0) * 0.5, (1.0 - t) * 0.5]);
            }
            mesh.indices
                .extend([first, first + 1, first + 2, first, first + 2, first + 3]);
        }
        mesh.tangents = generate_tangents(&mesh);
        mesh
    }

    /// A sphere of `radius` made of `sectors` slices around +Y and `stacks` bands from pole to
    /// pole (at least 3 and 2); u runs once around, v from the top pole (0) to the bottom (1).
    pub fn uv_sphere(radius: f32, sectors: u32, stacks: u32) -> Self {
        let sectors = sectors.max(3);
        let stacks = stacks.max(2);
        let mut mesh = Mesh::default();
        for stack in 0..=stacks {
            let v = stack as f32 / stacks as f32;
            let polar = v * PI;
            for sector in 0..=sectors {
                let u = sector as f32 / sectors as f32;
                let azimuth = u * TAU;
                // −sin on z so u increases to the right when seen from outside.
                let normal = Vec3::new(
                    polar.sin() * azimuth.cos(),
                    polar.cos(),
                    -polar.sin() * azimuth.sin(),
                );
                mesh.positions.push((normal * radius).into());
                mesh.normals.push(normal.into());
                mesh.uvs.push([u, v]);
            }
        }
        let row = sectors + 1;
        for stack in 0..stacks {
            for sector in 0..sectors {
                let top_left = stack * row + sector;
                let bottom_left = top_left + row;
                // Skip the triangle that would collapse onto a pole.
                if stack != 0 {
                    mesh.indices.extend([top_left, bottom_left, top_left + 1]);
                }
                if stack != stacks - 1 {
                    mesh.indices
                        .extend([top_left + 1, bottom_left, bottom_left + 1]);
                }
            }
        }
        mesh.tangents = generate_tangents(&mesh);
        mesh
    }
}

impl Mesh {
    /// A closed cylinder of `radius` and `height` about +Y, centred on the origin, made of
    /// `sectors` slices (at least 3). The side wraps the texture once around (u, from +X
    /// towards −Z, so it grows to the right seen from outside) and once along the axis (v, from
    /// the top rim, 0, to the bottom, 1); each cap has the texture's unit square over its disc
    /// (u along +X, v along +Z on the top, −Z on the bottom, so both read unmirrored from
    /// outside).
    pub fn cylinder(radius: f32, height: f32, sectors: u32) -> Self {
        let sectors = sectors.max(3);
        let half = height * 0.5;
        let mut mesh = Mesh::default();
        for sector in 0..=sectors {
            let u = sector as f32 / sectors as f32;
            let azimuth = u * TAU;
            let normal = Vec3::new(azimuth.cos(), 0.0, -azimuth.sin());
            for (y, v) in [(half, 0.0), (-half, 1.0)] {
                mesh.positions.push((normal * radius + Vec3::Y * y).into());
                mesh.normals.push(normal.into());
                mesh.uvs.push([u, v]);
            }
        }
        for sector in 0..sectors {
            let (top, bottom) = (sector * 2, sector * 2 + 1);
            let (next_top, next_bottom) = (top + 2, bottom + 2);
            mesh.indices
                .extend([top, bottom, next_bottom, top, next_bottom, next_top]);
        }
        for (cap_normal, flip_v) in [(Vec3::Y, 1.0), (Vec3::NEG_Y, -1.0)] {
            let centre = mesh.positions.len() as u32;
            mesh.positions.push((cap_normal * half).into());
            mesh.normals.push(cap_normal.into());
            mesh.uvs.push([0.5, 0.5]);
            for sector in 0..sectors {
                let azimuth = sector as f32 / sectors as f32 * TAU;
                let (x, z) = (azimuth.cos(), -azimuth.sin());
                mesh.positions
                    .push((Vec3::new(x * radius, 0.0, z * radius) + cap_normal * half).into());
                mesh.normals.push(cap_normal.into());
                mesh.uvs.push([0.5 + 0.5 * x, 0.5 + 0.5 * z * flip_v]);
            }
            for sector in 0..sectors {
                let a = centre + 1 + sector;
                let b = centre + 1 + (sector + 1) % sectors;
                // Counter-clockwise seen from outside the cap.
                if cap_normal.y > 0.0 {
                    mesh.indices.extend([centre, a, b]);
                } else {
                    mesh.indices.extend([centre, b, a]);
                }
            }
        }
        mesh.tangents = generate_tangents(&mesh);
        mesh
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::MeshError;

    fn assert_outward_and_complete(mesh: &Mesh) {
        mesh.validate().unwrap();
        assert_eq!(mesh.normals.len(), mesh.positions.len());
        assert_eq!(mesh.uvs.len(), mesh.positions.len());
        assert_eq!(mesh.tangents.len(), mesh.positions.len());
        for triangle in mesh.indices.chunks_exact(3) {
            let [a, b, c] = [0, 1, 2].map(|k| Vec3::from(mesh.positions[triangle[k] as usize]));
            let face_normal = (b - a).cross(c - a);
            let vertex_normal = Vec3::from(mesh.normals[triangle[0] as usize]);
            assert!(
                face_normal.length() > 0.0,
                "degenerate triangle {triangle:?}"
            );
            assert!(
                face_normal.dot(vertex_normal) > 0.0,
                "inward triangle {triangle:?}"
            );
        }
        for (tangent, normal) in mesh.tangents.iter().zip(&mesh.normals) {
            let t = Vec3::new(tangent[0], tangent[1], tangent[2]);
            assert!(
                (t.length() - 1.0).abs() < 1e-3,
                "tangent not unit: {tangent:?}"
            );
            assert!(
                t.dot(Vec3::from(*normal)).abs() < 1e-3,
                "tangent not ⟂ normal"
            );
            assert!(tangent[3] == 1.0 || tangent[3] == -1.0);
        }
    }

    #[test]
    fn primitives_face_outwards_with_full_tangent_frames() {
        assert_outward_and_complete(&Mesh::plane(2.0));
        assert_outward_and_complete(&Mesh::cube(1.0));
        assert_outward_and_complete(&Mesh::uv_sphere(1.0, 24, 12));
        assert_outward_and_complete(&Mesh::cylinder(0.5, 1.0, 24));
    }

    #[test]
    fn plane_tangent_follows_u() {
        // u grows along +X and v along +Z, so the tangent is +X and the bitangent +Z.
        let plane = Mesh::plane(1.0);
        for (tangent, normal) in plane.tangents.iter().zip(&plane.normals) {
            let t = Vec3::new(tangent[0], tangent[1], tangent[2]);
            assert!((t - Vec3::X).length() < 1e-4);
            let bitangent = Vec3::from(*normal).cross(t) * tangent[3];
            assert!(
                (bitangent - Vec3::Z).length() < 1e-4,
                "cross(n, t) * w must be dP/dv"
            );
        }
    }

    #[test]
    fn generated_attributes_fill_what_is_missing() {
        let bare = Mesh {
            positions: vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
            indices: vec![0, 1, 2],
            ..Mesh::default()
        };
        let full = bare.with_generated_attributes().unwrap();
        assert_eq!(full.normals, vec![[0.0, 0.0, 1.0]; 3]);
        assert_eq!(full.tangents.len(), 3);
    }

    #[test]
    fn validation_names_the_problem() {
        let mut mesh = Mesh::cube(1.0);
        mesh.indices.push(999);
        assert_eq!(mesh.validate(), Err(MeshError::PartialTriangle(37)));
        mesh.indices.extend([0, 0]);
        assert!(matches!(
            mesh.validate(),
            Err(MeshError::IndexOutOfRange {
                index: 999,
                at: 36,
                ..
            })
        ));
        let mut short_normals = Mesh::cube(1.0);
        short_normals.normals.pop();
        assert!(matches!(
            short_normals.validate(),
            Err(MeshError::AttributeLength {
                attribute: "normals",
                ..
            })
        ));
        let mut nan = Mesh::cube(1.0);
        nan.positions[5][1] = f32::NAN;
        assert_eq!(nan.validate(), Err(MeshError::NonFinitePosition(5)));
    }
}
