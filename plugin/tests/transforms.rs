//! Transform propagation: hierarchies, re-parenting, despawned parents.

use glam::{Quat, Vec3};
use hecs::World;
use pom::{GlobalTransform, Parent, Resources, Transform, despawn_recursive, propagate_transforms};

fn propagate(world: &mut World) {
    propagate_transforms(world, &mut Resources::default());
}

fn global_translation(world: &World, entity: hecs::Entity) -> Vec3 {
    world.get::<&GlobalTransform>(entity).unwrap().translation()
}

#[test]
fn child_composes_with_parent_rotation_and_scale() {
    let mut world = World::new();
    let parent = world.spawn((Transform {
        translation: Vec3::new(1.0, 0.0, 0.0),
        rotation: Quat::from_rotation_y(std::f32::consts::FRAC_PI_2),
        scale: Vec3::splat(2.0),
    },));
    let child = world.spawn((Transform::from_xyz(1.0, 0.0, 0.0), Parent(parent)));
    propagate(&mut world);
    // Scaled by 2, then +X rotated a quarter turn about Y to −Z, then moved by +1 X.
    assert!((global_translation(&world, child) - Vec3::new(1.0, 0.0, -2.0)).length() < 1e-5);
}

#[test]
fn a_deep_hierarchy_propagates_without_recursion() {
    let mut world = World::new();
    let mut parent = world.spawn((Transform::IDENTITY,));
    let depth = 20_000;
    for _ in 0..depth {
        parent = world.spawn((Transform::from_xyz(0.0, 1.0, 0.0), Parent(parent)));
    }
    propagate(&mut world);
    assert_eq!(
        global_translation(&world, parent),
        Vec3::new(0.0, depth as f32, 0.0)
    );
}

#[test]
fn reparenting_moves_the_child_with_its_new_parent() {
    let mut world = World::new();
    let left = world.spawn((Transform::from_xyz(-5.0, 0.0, 0.0),));
    let right = world.spawn((Transform::from_xyz(5.0, 0.0, 0.0),));
    let child = world.spawn((Transform::from_xyz(0.0, 1.0, 0.0), Parent(left)));
    propagate(&mut world);
    assert_eq!(global_translation(&world, child), Vec3::new(-5.0, 1.0, 0.0));
    world.insert_one(child, Parent(right)).unwrap();
    propagate(&mut world);
    assert_eq!(global_translation(&world, child), Vec3::new(5.0, 1.0, 0.0));
    world.remove_one::<Parent>(child).unwrap();
    propagate(&mut world);
    assert_eq!(global_translation(&world, child), Vec3::new(0.0, 1.0, 0.0));
}

#[test]
fn a_child_of_a_despawned_parent_becomes_a_root() {
    let mut world = World::new();
    let parent = world.spawn((Transform::from_xyz(3.0, 0.0, 0.0),));
    let child = world.spawn((Transform::from_xyz(0.0, 2.0, 0.0), Parent(parent)));
    propagate(&mut world);
    world.despawn(parent).unwrap();
    propagate(&mut world);
    assert_eq!(global_translation(&world, child), Vec3::new(0.0, 2.0, 0.0));
}

#[test]
fn despawn_recursive_removes_the_whole_subtree() {
    let mut world = World::new();
    let root = world.spawn((Transform::IDENTITY,));
    let child = world.spawn((Transform::IDENTITY, Parent(root)));
    let grandchild = world.spawn((Transform::IDENTITY, Parent(child)));
    let bystander = world.spawn((Transform::IDENTITY,));
    despawn_recursive(&mut world, root);
    for gone in [root, child, grandchild] {
        assert!(!world.contains(gone));
    }
    assert!(world.contains(bystander));
}

#[test]
fn a_parent_cycle_does_not_hang_and_leaves_others_correct() {
    let mut world = World::new();
    let a = world.spawn((Transform::IDENTITY,));
    let b = world.spawn((Transform::IDENTITY, Parent(a)));
    world.insert_one(a, Parent(b)).unwrap();
    let free = world.spawn((Transform::from_xyz(1.0, 2.0, 3.0),));
    propagate(&mut world);
    assert_eq!(global_translation(&world, free), Vec3::new(1.0, 2.0, 3.0));
    assert!(
        world.get::<&GlobalTransform>(a).is_err(),
        "cycle members are unreachable"
    );
}

#[test]
fn looking_at_points_minus_z_at_the_target() {
    let transform =
        Transform::from_xyz(0.0, 0.0, 5.0).looking_at(Vec3::new(0.0, 0.0, -1.0), Vec3::Y);
    let forward = GlobalTransform(transform.to_affine()).forward();
    assert!((forward - Vec3::NEG_Z).length() < 1e-6);
    // Degenerate input leaves the rotation alone instead of producing NaN.
    let same_point = Transform::IDENTITY.looking_at(Vec3::ZERO, Vec3::Y);
    assert_eq!(same_point.rotation, Quat::IDENTITY);
    let parallel_up = Transform::IDENTITY.looking_at(Vec3::Y, Vec3::Y);
    assert_eq!(parallel_up.rotation, Quat::IDENTITY);
}

#[test]
fn a_child_of_a_parent_without_a_transform_is_a_root() {
    let mut world = World::new();
    let untransformed = world.spawn(());
    let child = world.spawn((Transform::from_xyz(5.0, 0.0, 0.0), Parent(untransformed)));
    propagate(&mut world);
    assert_eq!(global_translation(&world, child), Vec3::new(5.0, 0.0, 0.0));
}

#[test]
fn roots_with_and_without_a_global_transform_carry_their_children() {
    let mut world = World::new();
    let fresh = world.spawn((Transform::from_xyz(1.0, 0.0, 0.0),));
    let kept = world.spawn((
        Transform::from_xyz(2.0, 0.0, 0.0),
        GlobalTransform::default(),
    ));
    let under_fresh = world.spawn((Transform::from_xyz(0.0, 1.0, 0.0), Parent(fresh)));
    let under_kept = world.spawn((Transform::from_xyz(0.0, 0.0, 1.0), Parent(kept)));
    propagate(&mut world);
    assert_eq!(global_translation(&world, fresh), Vec3::new(1.0, 0.0, 0.0));
    assert_eq!(global_translation(&world, kept), Vec3::new(2.0, 0.0, 0.0));
    assert_eq!(
        global_translation(&world, under_fresh),
        Vec3::new(1.0, 1.0, 0.0)
    );
    assert_eq!(
        global_translation(&world, under_kept),
        Vec3::new(2.0, 0.0, 1.0)
    );
}

#[test]
fn a_parent_cycle_keeps_its_last_global_transforms() {
    let mut world = World::new();
    let first = world.spawn((Transform::from_xyz(1.0, 0.0, 0.0),));
    let second = world.spawn((Transform::from_xyz(0.0, 1.0, 0.0), Parent(first)));
    propagate(&mut world);
    world.insert_one(first, Parent(second)).unwrap();
    propagate(&mut world);
    assert_eq!(global_translation(&world, first), Vec3::new(1.0, 0.0, 0.0));
    assert_eq!(global_translation(&world, second), Vec3::new(1.0, 1.0, 0.0));
}
