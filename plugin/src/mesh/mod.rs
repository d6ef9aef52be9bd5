//! Triangle meshes: vertex attributes, validation, primitives and tangent generation.

mod displaced;
pub(crate) mod primitives;
mod tangents;
mod terrain;

pub use displaced::MAX_GRID_CELLS;
pub use tangents::generate_tangents;

/// What is wrong with a mesh's data.
#[derive(Debug, thiserror::Error, PartialEq)]
#[non_exhaustive]
pub enum MeshError {
    /// An attribute has a different number of entries than there are positions.
    #[error("mesh attribute {attribute} has {found} entries but there are {expected} positions")]
    AttributeLength {
        /// The attribute's name.
        attribute: &'static str,
        /// Its entry count.
        found: usize,
        /// The position count.
        expected: usize,
    },
    /// The index count is not a multiple of three.
    #[error("mesh has {0} indices, which is not a whole number of triangles")]
    PartialTriangle(usize),
    /// An index refers past the last vertex.
    #[error("mesh index {index} at position {at} is out of range for {vertices} vertices")]
    IndexOutOfRange {
        /// The bad index.
        index: u32,
        /// Where it is in the index list.
        at: usize,
        /// The vertex count.
        vertices: usize,
    },
    /// A position is NaN or infinite.
    #[error("mesh position {0} is not finite")]
    NonFinitePosition(usize),
    /// A normal, texture coordinate, tangent or colour is NaN or infinite.
    #[error("mesh {attribute} of vertex {vertex} is not finite")]
    NonFiniteAttribute {
        /// The attribute's name (`normals`, `uvs`, `tangents` or `colors`).
        attribute: &'static str,
        /// The vertex.
        vertex: usize,
    },
    /// The mesh has no triangles.
    #[error("mesh has no triangles")]
    Empty,
    /// A displaced grid or a terrain was asked for with too few or too many cells.
    #[error("{what} of {cells} cells per side is outside 1..={limit}")]
    GridCells {
        /// What was asked for (`displaced grid` or `terrain`).
        what: &'static str,
        /// Cells asked for along one side.
        cells: u32,
        /// [`MAX_GRID_CELLS`].
        limit: u32,
    },
    /// The mesh's vertex or index buffer is larger than the device can make and bind.
    #[error("mesh {buffer} would take {bytes} bytes, over the device's limit of {limit}")]
    TooLarge {
        /// Which buffer (`vertex buffer` or `index buffer`).
        buffer: &'static str,
        /// Its size in bytes.
        bytes: u64,
        /// The device's largest buffer bound whole as storage.
        limit: u64,
    },
    /// A terrain's size (x, y, z) is not finite, or not positive across (x, z) or negative in
    /// height (y).
    #[error("terrain size {0:?} must be finite, positive in x and z and not negative in y")]
    TerrainSize([f32; 3]),
}

/// An indexed triangle list with the attributes the lit materials need.
///
/// Normals, UVs and tangents are optional when building; [`Mesh::validate`] checks lengths and
/// indices, and the renderer fills missing normals (flat) and tangents (MikkTSpace) before upload.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Mesh {
    /// Vertex positions.
    pub positions: Vec<[f32; 3]>,
    /// Unit vertex normals (empty: computed as flat normals).
    pub normals: Vec<[f32; 3]>,
    /// Texture coordinates (empty: all zero).
    pub uvs: Vec<[f32; 2]>,
    /// MikkTSpace tangents, `w` = bitangent sign (empty: generated).
    pub tangents: Vec<[f32; 4]>,
    /// Linear RGBA per vertex, multiplied with the material's base colour (empty: white).
    pub colors: Vec<[f32; 4]>,
    /// Three indices per triangle, counter-clockwise seen from the front.
    pub indices: Vec<u32>,
}

impl Mesh {
    /// Checks that every attribute matches the position count, every index is in range and
    /// every value is finite.
    pub fn validate(&self) -> Result<(), MeshError> {
        let expected = self.positions.len();
        for (attribute, found) in [
            ("normals", self.normals.len()),
            ("uvs", self.uvs.len()),
            ("tangents", self.tangents.len()),
            ("colors", self.colors.len()),
        ] {
            if found != 0 && found != expected {
                return Err(MeshError::AttributeLength {
                    attribute,
                    found,
                    expected,
                });
            }
        }
        if self.indices.is_empty() {
            return Err(MeshError::Empty);
        }
        if !self.indices.len().is_multiple_of(3) {
            return Err(MeshError::PartialTriangle(self.indices.len()));
        }
        if let Some((at, &index)) = self
            .indices
            .iter()
            .enumerate()
            .find(|(_, index)| **index as usize >= expected)
        {
            return Err(MeshError::IndexOutOfRange {
                index,
                at,
                vertices: expected,
            });
        }
        if let Some(at) = self
            .positions
            .iter()
            .position(|p| p.iter().any(|c| !c.is_finite()))
        {
            return Err(MeshError::NonFinitePosition(at));
        }
        self.check_finite_attributes()
    }

    /// Every normal, texture coordinate, tangent and colour is finite: one NaN would shade its
    /// triangles (and, through filtering, their neighbours) with NaN.
    fn check_finite_attributes(&self) -> Result<(), MeshError> {
        fn first_non_finite<const N: usize>(values: &[[f32; N]]) -> Option<usize> {
            values
                .iter()
                .position(|value| value.iter().any(|c| !c.is_finite()))
        }
        for (attribute, vertex) in [
            ("normals", first_non_finite(&self.normals)),
            ("uvs", first_non_finite(&self.uvs)),
            ("tangents", first_non_finite(&self.tangents)),
            ("colors", first_non_finite(&self.colors)),
        ] {
            if let Some(vertex) = vertex {
                return Err(MeshError::NonFiniteAttribute { attribute, vertex });
            }
        }
        Ok(())
    }

    /// Number of triangles.
    pub fn triangle_count(&self) -> usize {
        self.indices.len() / 3
    }

    /// Fills in whatever attributes are missing so the mesh can be drawn with lighting and
    /// normal maps: flat normals (per-triangle, splitting shared vertices), zero UVs, and
    /// MikkTSpace tangents. Validates first.
    pub fn with_generated_attributes(mut self) -> Result<Self, MeshError> {
        self.validate()?;
        if self.normals.is_empty() {
            self = self.unshared_with_flat_normals();
        }
        if self.uvs.is_empty() {
            self.uvs = vec![[0.0; 2]; self.positions.len()];
        }
        if self.tangents.is_empty() {
            self.tangents = generate_tangents(&self);
        }
        Ok(self)
    }

    /// Gives every triangle its own three vertices with the face normal.
    fn unshared_with_flat_normals(&self) -> Self {
        let mut flat = Mesh::default();
        for (triangle_index, triangle) in self.indices.chunks_exact(3).enumerate() {
            let corners = [0, 1, 2].map(|k| glam::Vec3::from(self.positions[triangle[k] as usize]));
            let normal = (corners[1] - corners[0])
                .cross(corners[2] - corners[0])
                .try_normalize()
                .unwrap_or(glam::Vec3::Z);
            for (corner, &index) in triangle.iter().enumerate() {
                flat.positions.push(self.positions[index as usize]);
                flat.normals.push(normal.into());
                if !self.uvs.is_empty() {
                    flat.uvs.push(self.uvs[index as usize]);
                }
                if !self.colors.is_empty() {
                    flat.colors.push(self.colors[index as usize]);
                }
                flat.indices.push((triangle_index * 3 + corner) as u32);
            }
        }
        flat
    }
}
