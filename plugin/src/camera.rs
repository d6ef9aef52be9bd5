//! Cameras: what part of the world the renderer draws, and how it is projected.

use glam::Mat4;
// WebGPU clip space is the DirectX one: depth 0..1, y up.
use glam::camera::rh::proj::directx::{orthographic, perspective};

use crate::{Color, GlobalTransform};

/// How a camera projects the view volume onto the image.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub enum Projection {
    /// Perspective: distant things look smaller.
    Perspective {
        /// Vertical field of view, in radians.
        fov_y: f32,
        /// Distance of the near clipping plane (> 0).
        near: f32,
        /// Distance of the far clipping plane (> near).
        far: f32,
    },
    /// Orthographic: parallel view rays, no foreshortening.
    Orthographic {
        /// Height of the view volume in world units; the width follows the image's aspect ratio.
        height: f32,
        /// Distance of the near clipping plane.
        near: f32,
        /// Distance of the far clipping plane (> near).
        far: f32,
    },
}

impl Projection {
    /// The projection matrix for an image of the given width / height, with depth 0 (near) to
    /// 1 (far) as wgpu expects. Degenerate values are clamped so the matrix stays finite.
    pub fn matrix(&self, aspect: f32) -> Mat4 {
        let aspect = if aspect.is_finite() && aspect > 0.0 {
            aspect
        } else {
            1.0
        };
        match *self {
            Projection::Perspective { fov_y, near, far } => {
                let fov_y = fov_y.clamp(1e-4, std::f32::consts::PI - 1e-4);
                let near = near.max(1e-5);
                let far = far.max(near * 1.0001);
                perspective(fov_y, aspect, near, far)
            }
            Projection::Orthographic { height, near, far } => {
                let half_height = (height * 0.5).max(1e-6);
                let half_width = half_height * aspect;
                let far = far.max(near + 1e-4);
                orthographic(
                    -half_width,
                    half_width,
                    -half_height,
                    half_height,
                    near,
                    far,
                )
            }
        }
    }
}

/// A camera component; the entity's [`crate::GlobalTransform`] places it, looking along −Z.
///
/// The renderer draws from the first camera it finds with `active` set.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    /// The projection.
    pub projection: Projection,
    /// The colour the image is cleared to: a display colour, shown as set (neither exposed nor tonemapped).
    pub clear_color: Color,
    /// Whether this camera renders.
    pub active: bool,
}

/// The camera the renderer draws from: the first with `active` set, with its world transform.
pub fn active_camera(world: &hecs::World) -> Option<(Camera, GlobalTransform)> {
    world
        .query::<(&Camera, &GlobalTransform)>()
        .iter()
        .find(|(camera, _)| camera.active)
        .map(|(camera, transform)| (*camera, *transform))
}

/// Every camera entity with `active` set: what the camera settings a tool applies (exposure,
/// tonemapping, anti-aliasing) go on.
pub fn active_cameras(world: &hecs::World) -> Vec<hecs::Entity> {
    world
        .query::<(hecs::Entity, &Camera)>()
        .iter()
        .filter(|(_, camera)| camera.active)
        .map(|(entity, _)| entity)
        .collect()
}

impl Camera {
    /// A perspective camera with a vertical field of view in degrees.
    pub fn perspective(fov_y_degrees: f32) -> Self {
        Self {
            projection: Projection::Perspective {
                fov_y: fov_y_degrees.to_radians(),
                near: 0.05,
                far: 200.0,
            },
            ..Self::default()
        }
    }

    /// An orthographic camera showing `height` world units vertically.
    pub fn orthographic(height: f32) -> Self {
        Self {
            projection: Projection::Orthographic {
                height,
                near: 0.0,
                far: 200.0,
            },
            ..Self::default()
        }
    }
}

impl Default for Camera {
    fn default() -> Self {
        Self {
            projection: Projection::Perspective {
                fov_y: 45_f32.to_radians(),
                near: 0.05,
                far: 200.0,
            },
            clear_color: Color::linear_rgb(0.02, 0.02, 0.025),
            active: true,
        }
    }
}
