//! What an automatic camera frames in a loaded scene: the meshes a viewer came to see.

use glam::Vec3;

/// A flat mesh (its thinnest side under 1 % of its widest) whose widest side is more than this
/// many times the widest side of everything that is not flat is a ground plane or a backdrop:
/// it does not decide the framing.
const BACKDROP_RATIO: f32 = 4.0;

fn union(boxes: impl IntoIterator<Item = (Vec3, Vec3)>) -> Option<(Vec3, Vec3)> {
    boxes
        .into_iter()
        .reduce(|(min_a, max_a), (min_b, max_b)| (min_a.min(min_b), max_a.max(max_b)))
}

fn widest(bounds: (Vec3, Vec3)) -> f32 {
    (bounds.1 - bounds.0).max_element()
}

fn is_flat(bounds: (Vec3, Vec3)) -> bool {
    let extent = bounds.1 - bounds.0;
    extent.min_element() <= 0.01 * extent.max_element()
}

/// The union of `meshes` (world-space boxes) without the flat ones far larger than the rest;
/// all of them when every mesh is flat.
pub(super) fn framing_bounds(meshes: &[(Vec3, Vec3)]) -> Option<(Vec3, Vec3)> {
    let Some(solid) = union(meshes.iter().copied().filter(|b| !is_flat(*b))) else {
        return union(meshes.iter().copied());
    };
    let limit = BACKDROP_RATIO * widest(solid);
    union(
        meshes
            .iter()
            .copied()
            .filter(|b| !is_flat(*b) || widest(*b) <= limit),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cube(centre: Vec3, half: f32) -> (Vec3, Vec3) {
        (centre - half, centre + half)
    }

    #[test]
    fn a_huge_ground_plane_does_not_decide_the_framing() {
        let ground = (Vec3::new(-50.0, 0.0, -50.0), Vec3::new(50.0, 0.0, 50.0));
        let objects = [cube(Vec3::new(1.0, 0.5, 0.0), 0.5), cube(Vec3::ZERO, 0.5)];
        let framed = framing_bounds(&[ground, objects[0], objects[1]]).unwrap();
        assert_eq!(
            framed,
            (Vec3::new(-0.5, -0.5, -0.5), Vec3::new(1.5, 1.0, 0.5))
        );
    }

    #[test]
    fn a_floor_the_size_of_the_scene_and_small_flat_things_stay() {
        let floor = (Vec3::new(-3.0, 0.0, -3.0), Vec3::new(3.0, 0.0, 3.0));
        let mat = (Vec3::new(0.0, 0.0, 0.0), Vec3::new(0.5, 0.0, 0.3));
        let cube = cube(Vec3::new(0.0, 1.0, 0.0), 1.0);
        assert_eq!(
            framing_bounds(&[floor, mat, cube]),
            Some((Vec3::new(-3.0, 0.0, -3.0), Vec3::new(3.0, 2.0, 3.0)))
        );
    }

    #[test]
    fn only_flat_meshes_are_framed_whole() {
        let plane = (Vec3::new(-50.0, 0.0, -50.0), Vec3::new(50.0, 0.0, 50.0));
        assert_eq!(framing_bounds(&[plane]), Some(plane));
        assert_eq!(framing_bounds(&[]), None);
    }
}
