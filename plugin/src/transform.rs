//! Local and global transforms, and parent→child propagation.

use std::collections::HashMap;

use glam::{Affine3A, Mat3, Mat4, Quat, Vec3};
use hecs::{Entity, World};

use crate::Resources;

/// An entity's position, rotation and scale relative to its [`Parent`] (or the world).
///
/// Cameras and lights look along their local −Z axis, as in Bevy and glTF.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Transform {
    /// Position.
    pub translation: Vec3,
    /// Orientation.
    pub rotation: Quat,
    /// Scale along each local axis.
    pub scale: Vec3,
}

impl Default for Transform {
    fn default() -> Self {
        Self::IDENTITY
    }
}

impl Transform {
    /// No translation, rotation or scale.
    pub const IDENTITY: Self = Self {
        translation: Vec3::ZERO,
        rotation: Quat::IDENTITY,
        scale: Vec3::ONE,
    };

    /// A transform at `(x, y, z)`.
    pub fn from_xyz(x: f32, y: f32, z: f32) -> Self {
        Self::from_translation(Vec3::new(x, y, z))
    }

    /// A transform at `translation`.
    pub fn from_translation(translation: Vec3) -> Self {
        Self {
            translation,
            ..Self::IDENTITY
        }
    }

    /// A transform with only a rotation.
    pub fn from_rotation(rotation: Quat) -> Self {
        Self {
            rotation,
            ..Self::IDENTITY
        }
    }

    /// A transform with only a scale.
    pub fn from_scale(scale: Vec3) -> Self {
        Self {
            scale,
            ..Self::IDENTITY
        }
    }

    /// Rotates this transform so its −Z axis points at `target` and its +Y axis is as close to
    /// `up` as possible. Leaves the rotation unchanged when `target` is at the translation or
    /// `up` is parallel to the view direction.
    pub fn looking_at(mut self, target: Vec3, up: Vec3) -> Self {
        let forward = (target - self.translation).normalize_or_zero();
        let right = forward.cross(up).normalize_or_zero();
        if forward == Vec3::ZERO || right == Vec3::ZERO {
            return self;
        }
        let true_up = right.cross(forward);
        self.rotation = Quat::from_mat3(&Mat3::from_cols(right, true_up, -forward));
        self
    }

    /// The transform of an affine matrix (its shear, if any, is lost).
    pub fn from_affine(affine: Affine3A) -> Self {
        let (scale, rotation, translation) = affine.to_scale_rotation_translation();
        Self {
            translation,
            rotation,
            scale,
        }
    }

    /// The affine matrix of this transform.
    pub fn to_affine(&self) -> Affine3A {
        Affine3A::from_scale_rotation_translation(self.scale, self.rotation, self.translation)
    }
}

/// An entity's transform in world space, written by [`propagate_transforms`].
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct GlobalTransform(pub Affine3A);

impl GlobalTransform {
    /// The world-space position.
    pub fn translation(&self) -> Vec3 {
        self.0.translation.into()
    }

    /// The world-space direction of the local −Z axis (where cameras and lights point).
    pub fn forward(&self) -> Vec3 {
        (-Vec3::from(self.0.matrix3.z_axis)).normalize_or_zero()
    }

    /// The 4×4 matrix.
    pub fn to_mat4(&self) -> Mat4 {
        Mat4::from(self.0)
    }
}

/// Makes an entity's [`Transform`] relative to another entity's [`GlobalTransform`].
///
/// Re-parenting is changing this component. An entity whose parent has been despawned (or has no
/// `Transform`) is treated as a root. Entities in a parent cycle are not reachable from a root and
/// keep their last global transform.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Parent(pub Entity);

/// Computes every entity's [`GlobalTransform`] from its [`Transform`] and its ancestors'.
///
/// Runs in [`crate::Stage::PostUpdate`]. Works iteratively, so hierarchies of any depth are fine.
/// Entities without a [`Parent`] (most of a scene) are written in one pass over their
/// components as they lie in memory; only children are looked up one by one.
pub fn propagate_transforms(world: &mut World, _: &mut Resources) {
    let mut children: HashMap<Entity, Vec<Entity>> = HashMap::new();
    // Children whose parent is gone (or has no Transform) are roots.
    let mut stack: Vec<(Entity, Affine3A)> = Vec::new();
    for (entity, _, Parent(parent)) in world.query::<(Entity, &Transform, &Parent)>().iter() {
        if world.satisfies::<&Transform>(*parent) {
            children.entry(*parent).or_default().push(entity);
        } else {
            stack.push((entity, Affine3A::IDENTITY));
        }
    }

    let mut without_global = Vec::new();
    for (entity, transform, global) in world
        .query_mut::<(Entity, &Transform, Option<&mut GlobalTransform>)>()
        .without::<&Parent>()
    {
        let affine = transform.to_affine();
        match global {
            Some(global) => global.0 = affine,
            None => without_global.push((entity, affine)),
        }
        if !children.is_empty()
            && let Some(kids) = children.remove(&entity)
        {
            stack.extend(kids.into_iter().map(|kid| (kid, affine)));
        }
    }
    for (entity, affine) in without_global {
        write_global(world, entity, affine);
    }

    while let Some((entity, parent_global)) = stack.pop() {
        let Ok(local) = world.get::<&Transform>(entity).map(|t| t.to_affine()) else {
            continue;
        };
        let global = parent_global * local;
        write_global(world, entity, global);
        if let Some(kids) = children.remove(&entity) {
            stack.extend(kids.into_iter().map(|kid| (kid, global)));
        }
    }
}

fn write_global(world: &mut World, entity: Entity, global: Affine3A) {
    if let Ok(mut existing) = world.get::<&mut GlobalTransform>(entity) {
        existing.0 = global;
        return;
    }
    // The entity was just yielded by a query, so it exists; insert cannot fail.
    let _ = world.insert_one(entity, GlobalTransform(global));
}

/// Despawns `entity` and all of its descendants (entities whose [`Parent`] chain leads to it).
pub fn despawn_recursive(world: &mut World, entity: Entity) {
    let mut children: HashMap<Entity, Vec<Entity>> = HashMap::new();
    for (child, Parent(parent)) in world.query::<(Entity, &Parent)>().iter() {
        children.entry(*parent).or_default().push(child);
    }
    let mut stack = vec![entity];
    while let Some(next) = stack.pop() {
        if let Some(kids) = children.remove(&next) {
            stack.extend(kids);
        }
        let _ = world.despawn(next);
    }
}

/// Adds [`propagate_transforms`] to [`crate::Stage::PostUpdate`].
#[derive(Clone, Copy, Debug, Default)]
pub struct TransformPlugin;

impl crate::Plugin for TransformPlugin {
    fn build(&self, app: &mut crate::App) {
        app.add_system(crate::Stage::PostUpdate, propagate_transforms);
    }
}
