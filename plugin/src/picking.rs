//! Picking: which entity a viewport pixel shows, by casting a ray from the active camera
//! against the world-space triangles of every mesh entity (on the CPU, no GPU read-back).

use glam::{Mat4, Vec2, Vec3};
use hecs::{Entity, World};

use crate::{Assets, GlobalTransform, Handle, Mesh, Resources, active_camera};

/// A half-line in world space: points `origin + t * direction` for `t >= 0`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ray {
    /// Where the ray starts (on the camera's near plane).
    pub origin: Vec3,
    /// Its direction (not necessarily unit length).
    pub direction: Vec3,
}

/// The nearest entity a ray hits.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PickHit {
    /// The entity whose mesh was hit.
    pub entity: Entity,
    /// The hit point in world space.
    pub point: Vec3,
    /// World-space distance from the ray's origin to the hit.
    pub distance: f32,
}

/// The ray through `pixel` (in pixels from the top-left corner of a viewport of `viewport`
/// pixels) from the first active camera; `None` without an active camera or with an empty
/// viewport.
pub fn camera_ray(world: &World, viewport: Vec2, pixel: Vec2) -> Option<Ray> {
    if !(viewport.x > 0.0 && viewport.y > 0.0) {
        return None;
    }
    let (camera, transform) = active_camera(world)?;
    let view_projection =
        camera.projection.matrix(viewport.x / viewport.y) * transform.to_mat4().inverse();
    ray_through(view_projection, viewport, pixel)
}

/// The ray through `pixel` for a view-projection matrix with wgpu's clip space (depth 0..1,
/// y up); works for perspective and orthographic projections alike.
pub fn ray_through(view_projection: Mat4, viewport: Vec2, pixel: Vec2) -> Option<Ray> {
    let ndc = Vec2::new(
        2.0 * pixel.x / viewport.x - 1.0,
        1.0 - 2.0 * pixel.y / viewport.y,
    );
    let inverse = view_projection.inverse();
    let near = inverse.project_point3(ndc.extend(0.0));
    let far = inverse.project_point3(ndc.extend(1.0));
    let direction = far - near;
    (near.is_finite() && direction.is_finite() && direction != Vec3::ZERO).then_some(Ray {
        origin: near,
        direction,
    })
}

/// The nearest mesh entity (one with a `Handle<Mesh>` and a [`GlobalTransform`]) that `ray`
/// hits, testing each mesh's bounding box before its triangles. Meshes with a degenerate
/// transform or missing from `meshes` are skipped.
pub fn pick_entity(world: &World, meshes: &Assets<Mesh>, ray: Ray) -> Option<PickHit> {
    let mut nearest: Option<(Entity, f32)> = None;
    for (entity, handle, transform) in world
        .query::<(Entity, &Handle<Mesh>, &GlobalTransform)>()
        .iter()
    {
        let Some(mesh) = meshes.get(handle) else {
            continue;
        };
        if transform.0.matrix3.determinant().abs() < 1e-12 {
            continue;
        }
        // In mesh space the ray keeps its parameter t, so hits of different meshes compare.
        let to_local = transform.0.inverse();
        let local = Ray {
            origin: to_local.transform_point3(ray.origin),
            direction: to_local.transform_vector3(ray.direction),
        };
        let limit = nearest.map_or(f32::INFINITY, |(_, t)| t);
        if let Some(t) = nearest_triangle_hit(mesh, local, limit) {
            nearest = Some((entity, t));
        }
    }
    nearest.map(|(entity, t)| {
        let point = ray.origin + ray.direction * t;
        PickHit {
            entity,
            point,
            distance: (point - ray.origin).length(),
        }
    })
}

/// [`pick_entity`] for the pixel `pixel` of a viewport of `viewport` pixels, seen by the
/// active camera, with the meshes of `resources`.
pub fn pick_at(
    world: &World,
    resources: &Resources,
    viewport: Vec2,
    pixel: Vec2,
) -> Option<PickHit> {
    let ray = camera_ray(world, viewport, pixel)?;
    pick_entity(world, resources.get::<Assets<Mesh>>()?, ray)
}

/// The smallest ray parameter below `limit` at which `ray` hits one of `mesh`'s triangles.
fn nearest_triangle_hit(mesh: &Mesh, ray: Ray, limit: f32) -> Option<f32> {
    let (low, high) = bounds(&mesh.positions)?;
    if slab_entry(ray, low, high).is_none_or(|t| t >= limit) {
        return None;
    }
    let vertex = |index: u32| mesh.positions.get(index as usize).map(|p| Vec3::from(*p));
    let mut nearest = limit;
    let mut found = false;
    for triangle in mesh.indices.chunks_exact(3) {
        let (Some(a), Some(b), Some(c)) = (
            vertex(triangle[0]),
            vertex(triangle[1]),
            vertex(triangle[2]),
        ) else {
            continue;
        };
        if let Some(t) = triangle_hit(ray, a, b, c)
            && t < nearest
        {
            nearest = t;
            found = true;
        }
    }
    found.then_some(nearest)
}

fn bounds(positions: &[[f32; 3]]) -> Option<(Vec3, Vec3)> {
    let mut points = positions.iter().map(|p| Vec3::from(*p));
    let first = points.next()?;
    Some(points.fold((first, first), |(low, high), p| (low.min(p), high.max(p))))
}

/// Where the ray enters the box (0 when it starts inside), or `None` if it misses it.
fn slab_entry(ray: Ray, low: Vec3, high: Vec3) -> Option<f32> {
    let inverse = ray.direction.recip();
    let (t0, t1) = ((low - ray.origin) * inverse, (high - ray.origin) * inverse);
    // NaN (a zero direction component with the origin on a slab's plane) counts as inside.
    let near = t0.min(t1).max_element().max(0.0);
    let far = t0.max(t1).min_element();
    (near <= far || far.is_nan()).then_some(near)
}

/// Möller–Trumbore: the ray parameter of the hit with triangle abc, either side facing.
fn triangle_hit(ray: Ray, a: Vec3, b: Vec3, c: Vec3) -> Option<f32> {
    let (edge1, edge2) = (b - a, c - a);
    let p = ray.direction.cross(edge2);
    let determinant = edge1.dot(p);
    if determinant.abs() < f32::EPSILON * ray.direction.length() * edge1.length() * edge2.length() {
        return None;
    }
    let to_origin = ray.origin - a;
    let u = to_origin.dot(p) / determinant;
    if !(0.0..=1.0).contains(&u) {
        return None;
    }
    let q = to_origin.cross(edge1);
    let v = ray.direction.dot(q) / determinant;
    if v < 0.0 || u + v > 1.0 {
        return None;
    }
    let t = edge2.dot(q) / determinant;
    (t >= 0.0).then_some(t)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Camera, Transform, propagate_transforms};

    /// Two unit cubes on the camera's axis, the near one at z = 0 and the far one at z = −5,
    /// plus one off to the side; the camera at z = 5 looks down −Z.
    fn scene() -> (World, Resources, [Entity; 3]) {
        let mut world = World::new();
        let mut resources = Resources::default();
        let cube = resources
            .get_or_default::<Assets<Mesh>>()
            .add(Mesh::cube(1.0));
        world.spawn((
            Camera::perspective(60.0),
            Transform::from_xyz(0.0, 0.0, 5.0),
        ));
        let near = world.spawn((cube.clone(), Transform::IDENTITY));
        let far = world.spawn((cube.clone(), Transform::from_xyz(0.0, 0.0, -5.0)));
        let side = world.spawn((cube, Transform::from_xyz(3.0, 0.0, 0.0)));
        propagate_transforms(&mut world, &mut resources);
        (world, resources, [near, far, side])
    }

    const VIEWPORT: Vec2 = Vec2::new(200.0, 100.0);

    #[test]
    fn the_centre_pixel_picks_the_nearest_of_two_cubes_on_the_axis() {
        let (world, resources, [near, ..]) = scene();
        let hit = pick_at(&world, &resources, VIEWPORT, VIEWPORT / 2.0).unwrap();
        assert_eq!(hit.entity, near);
        // The near cube's front face is at z = 0.5, 4.5 from the camera.
        assert!((hit.point.z - 0.5).abs() < 1e-3, "{hit:?}");
        assert!((hit.distance - (4.5 - 0.05)).abs() < 1e-2, "{hit:?}");
    }

    #[test]
    fn a_pixel_towards_the_side_cube_picks_it_and_a_corner_picks_nothing() {
        let (world, resources, [_, _, side]) = scene();
        let view_projection = Camera::perspective(60.0).projection.matrix(2.0)
            * Transform::from_xyz(0.0, 0.0, 5.0).to_affine().inverse();
        let clip = view_projection.project_point3(Vec3::new(3.0, 0.0, 0.5));
        let pixel = Vec2::new(
            (clip.x + 1.0) * 0.5 * VIEWPORT.x,
            (1.0 - clip.y) * 0.5 * VIEWPORT.y,
        );
        assert_eq!(
            pick_at(&world, &resources, VIEWPORT, pixel).unwrap().entity,
            side
        );
        assert_eq!(
            pick_at(&world, &resources, VIEWPORT, Vec2::new(1.0, 1.0)),
            None
        );
    }

    #[test]
    fn hidden_cubes_are_reached_once_the_near_one_moves_away() {
        let (mut world, mut resources, [near, far, _]) = scene();
        *world.get::<&mut Transform>(near).unwrap() = Transform::from_xyz(0.0, 10.0, 0.0);
        propagate_transforms(&mut world, &mut resources);
        let hit = pick_at(&world, &resources, VIEWPORT, VIEWPORT / 2.0).unwrap();
        assert_eq!(hit.entity, far);
    }

    #[test]
    fn degenerate_inputs_pick_nothing() {
        let (mut world, mut resources, [near, far, side]) = scene();
        assert_eq!(pick_at(&world, &resources, Vec2::ZERO, Vec2::ZERO), None);
        for entity in [near, far, side] {
            *world.get::<&mut Transform>(entity).unwrap() = Transform::from_scale(Vec3::ZERO);
        }
        propagate_transforms(&mut world, &mut resources);
        assert_eq!(pick_at(&world, &resources, VIEWPORT, VIEWPORT / 2.0), None);
        let mut no_camera = World::new();
        no_camera.spawn((Transform::IDENTITY,));
        assert_eq!(
            pick_at(&no_camera, &resources, VIEWPORT, VIEWPORT / 2.0),
            None
        );
    }

    #[test]
    fn an_orthographic_ray_is_parallel_to_the_view_axis() {
        let view_projection = Camera::orthographic(4.0).projection.matrix(1.0);
        let ray = ray_through(view_projection, Vec2::splat(100.0), Vec2::new(0.0, 50.0)).unwrap();
        assert!(ray.direction.normalize().abs_diff_eq(Vec3::NEG_Z, 1e-5));
        assert!((ray.origin.x + 2.0).abs() < 1e-4, "{ray:?}");
    }
}
