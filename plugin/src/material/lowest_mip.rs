//! A bound on the lowest mip level any pixel of an object can sample, for per-object LOD (the
//! parallax material draws an object whose every pixel is past its LOD threshold with its
//! normal-mapping pipeline: see `parallax/mod.rs`).
//!
//! The bound is conservative: it comes from the object's bounding sphere, its least texture
//! density and the camera's pixel size at the sphere's nearest point.

use std::collections::HashMap;

use glam::{Mat3, Mat4, Vec3};

use crate::{AssetId, Assets, Camera, GlobalTransform, Mesh, Projection};

/// What the LOD test needs of a mesh, in object space.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MeshLodBounds {
    /// Centre of a sphere holding every vertex.
    pub center: Vec3,
    /// Its radius.
    pub radius: f32,
    /// The least UV area per unit of surface area over its triangles (0 when some triangle has
    /// no UV area: such a mesh never switches).
    pub min_uv_per_area: f32,
}

impl MeshLodBounds {
    /// The bounds of `mesh`, or `None` when it has no triangle with area.
    pub fn of(mesh: &Mesh) -> Option<Self> {
        let positions: Vec<Vec3> = mesh.positions.iter().map(|p| Vec3::from(*p)).collect();
        let (min, max) = positions.iter().fold(
            (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY)),
            |(min, max), p| (min.min(*p), max.max(*p)),
        );
        let center = (min + max) * 0.5;
        let radius = positions
            .iter()
            .map(|p| p.distance(center))
            .fold(0.0, f32::max);
        let mut min_uv_per_area = f32::INFINITY;
        for triangle in mesh.indices.chunks_exact(3) {
            let corner = |i: usize| triangle[i] as usize;
            let (Some(a), Some(b), Some(c)) = (
                positions.get(corner(0)),
                positions.get(corner(1)),
                positions.get(corner(2)),
            ) else {
                continue;
            };
            let area = (*b - *a).cross(*c - *a).length() * 0.5;
            // Also skips NaN areas (the comparison is false).
            if area.is_nan() || area <= f32::MIN_POSITIVE {
                continue;
            }
            let uv = |i: usize| {
                mesh.uvs
                    .get(corner(i))
                    .map_or(glam::Vec2::ZERO, |uv| glam::Vec2::from(*uv))
            };
            let (ua, ub, uc) = (uv(0), uv(1), uv(2));
            let uv_area = (ub - ua).perp_dot(uc - ua).abs() * 0.5;
            min_uv_per_area = min_uv_per_area.min(uv_area / area);
        }
        (min_uv_per_area.is_finite() && center.is_finite() && radius.is_finite()).then_some(Self {
            center,
            radius,
            min_uv_per_area,
        })
    }
}

/// [`MeshLodBounds`] of the meshes seen so far, recomputed when a mesh changes. A resource.
#[derive(Debug, Default)]
pub struct MeshLodCache(HashMap<AssetId<Mesh>, (u64, Option<MeshLodBounds>)>);

impl MeshLodCache {
    /// The bounds of `id` in `meshes`, computed on first use and after each change.
    pub fn bounds(&mut self, meshes: &Assets<Mesh>, id: AssetId<Mesh>) -> Option<MeshLodBounds> {
        let version = meshes.version(id)?;
        match self.0.get(&id) {
            Some((seen, bounds)) if *seen == version => *bounds,
            _ => {
                let bounds = meshes.get(id).and_then(MeshLodBounds::of);
                self.0.insert(id, (version, bounds));
                bounds
            }
        }
    }

    /// Forgets meshes that no longer exist.
    pub fn retain_existing(&mut self, meshes: &Assets<Mesh>) {
        self.0.retain(|id, _| meshes.version(*id).is_some());
    }
}

/// How large a pixel is in the world, for the active camera and a target `height` pixels tall.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PixelFootprint {
    position: Vec3,
    /// Perspective: the smallest pixel's size per unit of distance; orthographic: 0.
    per_distance: f32,
    /// Orthographic: the pixel's size; perspective: 0.
    fixed: f32,
}

impl PixelFootprint {
    /// The footprint of `camera` at `transform` rendering `width`×`height` pixels.
    pub fn new(camera: &Camera, transform: &GlobalTransform, (width, height): (u32, u32)) -> Self {
        let rows = height.max(1) as f32;
        let aspect = width.max(1) as f32 / rows;
        match camera.projection {
            Projection::Perspective { fov_y, .. } => {
                let tan_half = (fov_y.clamp(1e-4, std::f32::consts::PI - 1e-4) * 0.5).tan();
                // A pixel at the frustum's corner subtends cos²θ of one on the axis.
                let corner_cos2 = 1.0 / (1.0 + tan_half * tan_half * (1.0 + aspect * aspect));
                Self {
                    position: transform.translation(),
                    per_distance: 2.0 * tan_half / rows * corner_cos2,
                    fixed: 0.0,
                }
            }
            Projection::Orthographic { height, .. } => Self {
                position: transform.translation(),
                per_distance: 0.0,
                fixed: height.max(0.0) / rows,
            },
        }
    }

    fn smallest_at(&self, distance: f32) -> f32 {
        self.fixed + self.per_distance * distance.max(0.0)
    }
}

/// The lowest mip level (as the shader's `mip_level` computes it, for a texture of
/// `texture_size` texels) that any pixel of the object with `bounds` and transform `model`
/// can get, or `None` when it cannot be bounded.
pub fn lowest_mip(
    bounds: &MeshLodBounds,
    model: &Mat4,
    footprint: &PixelFootprint,
    texture_size: (u32, u32),
) -> Option<f32> {
    // The largest stretch of the transform bounds both the sphere and the area growth: the
    // spectral norm, bounded by the largest absolute column sum of MᵀM (exact for rotations
    // and uniform scales).
    let linear = Mat3::from_mat4(*model);
    let gram = linear.transpose() * linear;
    let stretch = (0..3)
        .map(|column| gram.col(column).abs().element_sum())
        .fold(0.0, f32::max)
        .sqrt();
    let center = model.transform_point3(bounds.center);
    let nearest = center.distance(footprint.position) - bounds.radius * stretch;
    let pixel = footprint.smallest_at(nearest);
    let uv_per_world_area = bounds.min_uv_per_area / (stretch * stretch).max(f32::MIN_POSITIVE);
    let texels = texture_size.0 as f32 * texture_size.1 as f32;
    // The shader's level is at least half the log2 of the texel area one pixel covers.
    let texel_area = uv_per_world_area * texels * pixel * pixel;
    if texel_area == 0.0 {
        // The shader never goes below level 0.
        return Some(0.0);
    }
    let mip = 0.5 * texel_area.log2();
    mip.is_finite().then_some(mip.max(0.0))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Transform;

    #[test]
    fn a_plane_has_its_density_and_a_sphere_that_holds_it() {
        let bounds = MeshLodBounds::of(&Mesh::plane_tiled(2.0, 4.0)).unwrap();
        // 4² UV units over 2² world units.
        assert!((bounds.min_uv_per_area - 4.0).abs() < 1e-5);
        assert!(bounds.center.length() < 1e-6);
        assert!((bounds.radius - 2.0_f32.sqrt()).abs() < 1e-5);
        let no_uvs = Mesh {
            uvs: Vec::new(),
            ..Mesh::plane(1.0)
        };
        assert_eq!(MeshLodBounds::of(&no_uvs).unwrap().min_uv_per_area, 0.0);
    }

    #[test]
    fn the_bound_grows_with_distance_and_tiling_and_stays_below_the_true_level() {
        let camera = Camera::perspective(60.0);
        let footprint = |z: f32| {
            let transform = Transform::from_xyz(0.0, z, 0.0)
                .looking_at(Vec3::ZERO, Vec3::Z)
                .to_affine();
            PixelFootprint::new(&camera, &GlobalTransform(transform), (512, 512))
        };
        let plane = MeshLodBounds::of(&Mesh::plane(1.0)).unwrap();
        let mip = |z: f32| lowest_mip(&plane, &Mat4::IDENTITY, &footprint(z), (256, 256)).unwrap();
        assert_eq!(mip(0.5), 0.0, "inside the sphere nothing is known");
        assert!(mip(100.0) > mip(10.0));
        // At 100 units a pixel facing the camera spans about 100·2·tan 30°/512 = 0.226 units,
        // 57.8 texels: level 5.85; the bound lies below, within the corner factor.
        let level = mip(100.0);
        assert!(level < 5.86 && level > 5.0, "{level}");
        let tiled = MeshLodBounds::of(&Mesh::plane_tiled(1.0, 8.0)).unwrap();
        let tiled_mip = lowest_mip(&tiled, &Mat4::IDENTITY, &footprint(100.0), (256, 256)).unwrap();
        assert!(
            (tiled_mip - level - 3.0).abs() < 1e-3,
            "8× tiling is 3 levels up"
        );
    }
}
