//! Triplanar mapping, the CPU reference of the parallax material's triplanar mode: a texture
//! projected along each world axis, the three mixed by how squarely the surface faces each.
//!
//! Each projection maps world units to texture units by `1 / scale` and is oriented so that a
//! face looking along its axis, seen from outside, shows the texture unmirrored with u to the
//! right and v down the image (as glTF's UVs run): along ±X, u runs along ∓Z and v down −Y;
//! along ±Y (seen from above with −Z up, or from below with +Z up), u along +X and v along
//! ±Z; along ±Z, u along ±X and v down −Y.

use glam::{Vec2, Vec3};

use crate::HeightField;

/// The texture coordinates of the world point `position` in the projections along X, Y and Z,
/// for a surface of unit `normal` there (whose signs pick each projection's orientation), one
/// texture repeat every `scale` world units.
pub fn triplanar_uvs(position: Vec3, normal: Vec3, scale: f32) -> [Vec2; 3] {
    let side = |value: f32| if value < 0.0 { -1.0 } else { 1.0 };
    let p = position / scale;
    [
        Vec2::new(-p.z * side(normal.x), -p.y),
        Vec2::new(p.x, p.z * side(normal.y)),
        Vec2::new(p.x * side(normal.z), -p.y),
    ]
}

/// The share of the mix below which a projection is left out (`TRIPLANAR_MIN_SHARE` of
/// triplanar.wgsl): the shares are lowered by it and normalized again, so they stay continuous
/// and a surface facing mostly one axis reads one texture.
pub const TRIPLANAR_MIN_SHARE: f32 = 0.05;

/// The shares of the projections along X, Y and Z (summing to 1) for a surface of unit
/// `normal`: each axis's component raised to `sharpness` (1 and up; higher narrows the seams
/// where projections meet), normalized, lowered by [`TRIPLANAR_MIN_SHARE`] and normalized again.
pub fn triplanar_weights(normal: Vec3, sharpness: f32) -> Vec3 {
    let raised = normal.abs().powf(sharpness.max(1.0));
    let total = raised.element_sum();
    if total <= 0.0 || !total.is_finite() {
        return Vec3::Y;
    }
    let kept = (raised / total - Vec3::splat(TRIPLANAR_MIN_SHARE)).max(Vec3::ZERO);
    kept / kept.element_sum()
}

/// The height `field` gives a surface at `position` of unit `normal`: the three projections'
/// heights mixed by [`triplanar_weights`].
pub fn triplanar_height(
    field: &HeightField,
    position: Vec3,
    normal: Vec3,
    scale: f32,
    sharpness: f32,
) -> f32 {
    let weights = triplanar_weights(normal, sharpness);
    let [x, y, z] = triplanar_uvs(position, normal, scale).map(|uv| field.sample(uv.x, uv.y));
    weights.dot(Vec3::new(x, y, z))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_face_of_a_cube_shows_the_texture_unmirrored() {
        // Each face of a cube: its outward normal, and the directions to the right and up the
        // image of a viewer outside it (up: +Y on the sides, −Z above, +Z below).
        for (normal, right, up) in crate::mesh::primitives::CUBE_FACES {
            // Right and up must make a right-handed frame with the normal towards the viewer.
            assert_eq!(right.cross(up), normal);
            let axis = normal.abs().max_position();
            let centre = normal * 0.5 + Vec3::new(0.1, 0.2, 0.3) * (Vec3::ONE - normal.abs());
            let uv = |point: Vec3| triplanar_uvs(point, normal, 0.5)[axis];
            let (at, to_right, to_top) = (
                uv(centre),
                uv(centre + right * 0.01),
                uv(centre + up * 0.01),
            );
            // u grows to the right, v down the image, one repeat per half unit.
            assert!(
                (to_right - at).abs_diff_eq(Vec2::new(0.02, 0.0), 1e-5),
                "{normal}: {at} → {to_right}"
            );
            assert!(
                (to_top - at).abs_diff_eq(Vec2::new(0.0, -0.02), 1e-5),
                "{normal}: {at} → {to_top}"
            );
        }
    }

    #[test]
    fn the_projections_shares_follow_the_normal_and_sum_to_one() {
        assert_eq!(triplanar_weights(Vec3::NEG_Y, 4.0), Vec3::Y);
        let diagonal = Vec3::new(1.0, 1.0, 0.0).normalize();
        assert!(triplanar_weights(diagonal, 8.0).abs_diff_eq(Vec3::new(0.5, 0.5, 0.0), 1e-6));
        let tilted = Vec3::new(0.3, 0.9, 0.2).normalize();
        let (soft, sharp) = (
            triplanar_weights(tilted, 1.0),
            triplanar_weights(tilted, 16.0),
        );
        for weights in [soft, sharp] {
            assert!((weights.element_sum() - 1.0).abs() < 1e-6);
        }
        // Sharper: the axis the surface faces most takes more of the mix.
        assert!(sharp.y > soft.y && sharp.y > 0.99, "{soft} {sharp}");
        assert_eq!(triplanar_weights(Vec3::ZERO, 4.0), Vec3::Y);
        // A projection with a small share is left out, and the shares stay continuous there.
        let barely = |x: f32| triplanar_weights(Vec3::new(x, 1.0, 0.0).normalize(), 1.0).x;
        let edge = TRIPLANAR_MIN_SHARE / (1.0 - TRIPLANAR_MIN_SHARE);
        assert_eq!(barely(edge * 0.99), 0.0);
        assert!(barely(edge * 1.01) < 1e-3);
    }

    #[test]
    fn a_face_reads_the_field_through_its_own_projection() {
        let field = HeightField::from_fn(8, 8, |u, v| u * 0.5 + v * 0.25);
        let point = Vec3::new(0.3, 1.0, 0.15);
        let height = triplanar_height(&field, point, Vec3::Y, 2.0, 4.0);
        assert!((height - field.sample(0.15, 0.075)).abs() < 1e-6);
        // Where two projections share the surface, the height is between theirs.
        let normal = Vec3::new(1.0, 1.0, 0.0).normalize();
        let [x, y, _] = triplanar_uvs(point, normal, 2.0).map(|uv| field.sample(uv.x, uv.y));
        let mixed = triplanar_height(&field, point, normal, 2.0, 4.0);
        assert!((mixed - (x + y) * 0.5).abs() < 1e-6);
    }
}
