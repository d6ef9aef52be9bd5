//! The material preview scene: one square plane under one directional light, framed by a camera
//! placed by angles. The `render` command and the material tests use it.

use glam::Vec3;

use crate::{
    App, AppError, Assets, Camera, Color, DirectionalLight, Mesh, ParallaxOcclusionMaterial,
    Projection, Transform,
};

/// The largest view angle, in degrees; larger ones are clamped to it.
pub const MAX_VIEW_ANGLE: f32 = 89.99;

/// Side of the preview plane in world units.
pub const PLANE_SIZE: f32 = 1.0;

/// How the preview camera projects.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum PreviewProjection {
    /// Parallel rays: every pixel sees the plane at the same angle. The plane fills the image at
    /// the default distance.
    #[default]
    Orthographic,
    /// A 45° vertical field of view.
    Perspective,
}

/// What the preview shows the material on. Each is [`PLANE_SIZE`] across, centred on the
/// origin, and `tiling` repeats its texture coordinates.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum PreviewShape {
    /// A square in the XZ plane facing +Y, u along +X and v along +Z; it fills the image
    /// (cropped where the view tilts it).
    #[default]
    Plane,
    /// A cube with the whole texture on each face ([`Mesh::cube`]); the top faces +Y like the
    /// plane. It and the other solids are framed whole.
    Cube,
    /// A sphere wrapped once around (u) and from pole to pole (v) ([`Mesh::uv_sphere`]).
    Sphere,
    /// A closed cylinder about +Y, its side wrapped once around (u) and once along the axis (v),
    /// each cap with the unit square over its disc ([`Mesh::cylinder`]).
    Cylinder,
}

impl PreviewShape {
    /// The shape's mesh with its texture repeated `tiling` times (values that are not positive
    /// and finite mean 1).
    pub fn mesh(self, tiling: f32) -> Mesh {
        let tiling = if tiling.is_finite() && tiling > 0.0 {
            tiling
        } else {
            1.0
        };
        let mut mesh = match self {
            PreviewShape::Plane => return Mesh::plane_tiled(PLANE_SIZE, tiling),
            PreviewShape::Cube => Mesh::cube(PLANE_SIZE),
            PreviewShape::Sphere => Mesh::uv_sphere(PLANE_SIZE * 0.5, 64, 32),
            PreviewShape::Cylinder => Mesh::cylinder(PLANE_SIZE * 0.5, PLANE_SIZE, 64),
        };
        for uv in &mut mesh.uvs {
            *uv = uv.map(|coordinate| coordinate * tiling);
        }
        mesh
    }

    /// Half the extent of the shape's bounding box along each axis.
    fn half_extent(self) -> Vec3 {
        match self {
            PreviewShape::Plane => Vec3::new(0.5, 0.0, 0.5) * PLANE_SIZE,
            _ => Vec3::splat(0.5 * PLANE_SIZE),
        }
    }
}

/// Where the camera and the light are, relative to the plane.
///
/// Angles are in degrees. The view angle is between the view direction and the plane's normal
/// (0 = looking straight down). Azimuth 0 puts the camera on the −u side with its view ray's
/// in-plane component along +u, so +u runs up the image and +v to the right; the azimuth turns
/// that towards +v. The light uses the same frame: light angle 0 is straight above, 90 is the
/// horizon, more is below it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PreviewView {
    /// Degrees between the view direction and the plane normal, 0..<90.
    pub view_angle: f32,
    /// Degrees around the normal, from +u towards +v.
    pub view_azimuth: f32,
    /// Degrees between the direction to the light and the plane normal.
    pub light_angle: f32,
    /// Degrees around the normal, from +u towards +v.
    pub light_azimuth: f32,
    /// The projection.
    pub projection: PreviewProjection,
    /// Camera distance as a multiple of the default (which frames the plane); < 1 zooms in.
    pub distance: f32,
    /// UV repeats across the plane.
    pub tiling: f32,
    /// What the material is shown on.
    pub shape: PreviewShape,
}

impl Default for PreviewView {
    fn default() -> Self {
        Self {
            view_angle: 0.0,
            view_azimuth: 0.0,
            light_angle: 45.0,
            light_azimuth: 0.0,
            projection: PreviewProjection::Orthographic,
            distance: 1.0,
            tiling: 1.0,
            shape: PreviewShape::Plane,
        }
    }
}

/// Unit vector in the plane at `azimuth` degrees: +u (world +X) at 0, +v (world +Z) at 90.
fn in_plane(azimuth: f32) -> Vec3 {
    let radians = azimuth.to_radians();
    Vec3::new(radians.cos(), 0.0, radians.sin())
}

/// Unit vector from the plane towards something at `angle` degrees from the normal and
/// `azimuth` degrees around it, on the −azimuth side (as the camera at azimuth 0 is on −u).
fn towards(angle: f32, azimuth: f32) -> Vec3 {
    let angle = angle.to_radians();
    -in_plane(azimuth) * angle.sin() + Vec3::Y * angle.cos()
}

impl PreviewView {
    /// The camera component and its transform for an image of `aspect` = width / height.
    pub fn camera(&self, aspect: f32) -> (Camera, Transform) {
        let angle = self.view_angle.clamp(0.0, MAX_VIEW_ANGLE);
        let distance_scale = if self.distance.is_finite() && self.distance > 0.0 {
            self.distance
        } else {
            1.0
        };
        let forward_in_plane = in_plane(self.view_azimuth);
        let to_camera = towards(angle, self.view_azimuth);
        // Perpendicular to the view direction, pointing up the image: +u at azimuth 0.
        let radians = angle.to_radians();
        let up = forward_in_plane * radians.cos() + Vec3::Y * radians.sin();
        let aspect = if aspect.is_finite() && aspect > 0.0 {
            aspect
        } else {
            1.0
        };
        let right = up.cross(-to_camera).normalize_or(Vec3::Z);
        let (projection, distance) = match self.projection {
            PreviewProjection::Orthographic => {
                let fit = if self.shape == PreviewShape::Plane {
                    // The plane appears cos(angle) as tall as it is wide; it fills the image.
                    (PLANE_SIZE * radians.cos()).min(PLANE_SIZE / aspect)
                } else {
                    // A solid is framed whole: its box's corners fit, with a margin.
                    let extent = self.shape.half_extent();
                    let (mut tall, mut wide) = (0.0_f32, 0.0_f32);
                    for corner in box_corners(extent) {
                        tall = tall.max(corner.dot(up).abs());
                        wide = wide.max(corner.dot(right).abs());
                    }
                    2.2 * tall.max(wide / aspect)
                }
                .max(1e-3);
                (
                    Projection::Orthographic {
                        height: fit * distance_scale,
                        near: 0.0,
                        far: 20.0,
                    },
                    5.0,
                )
            }
            PreviewProjection::Perspective => {
                let fov_y = 45_f32.to_radians();
                (
                    Projection::Perspective {
                        fov_y,
                        near: 0.01,
                        far: 100.0,
                    },
                    if self.shape == PreviewShape::Plane {
                        PLANE_SIZE * 0.5 / (fov_y * 0.5).tan() * distance_scale
                    } else {
                        // The bounding sphere fits the narrower field, with a margin.
                        let half_fov = (fov_y * 0.5).min(((fov_y * 0.5).tan() * aspect).atan());
                        1.1 * self.shape.half_extent().length() / half_fov.sin() * distance_scale
                    },
                )
            }
        };
        let camera = Camera {
            projection,
            clear_color: Color::linear_rgb(0.0, 0.0, 0.0),
            active: true,
        };
        let transform =
            Transform::from_translation(to_camera * distance).looking_at(Vec3::ZERO, up);
        (camera, transform)
    }

    /// The light's transform (its −Z axis points from the light towards the plane).
    pub fn light_transform(&self) -> Transform {
        let to_light = towards(self.light_angle, self.light_azimuth);
        // Any up that is not parallel to the light direction.
        let up = if to_light.y.abs() > 0.99 {
            Vec3::X
        } else {
            Vec3::Y
        };
        Transform::from_translation(to_light).looking_at(Vec3::ZERO, up)
    }
}

/// The eight corners of the box of half extent `extent` about the origin.
fn box_corners(extent: Vec3) -> impl Iterator<Item = Vec3> {
    (0..8).map(move |bits| {
        let sign = |bit: u32| if bits & bit == 0 { -1.0 } else { 1.0 };
        extent * Vec3::new(sign(1), sign(2), sign(4))
    })
}

/// Spawns the preview shape with `material`, the camera and the light. Finishes the app's
/// plugins first (the render plugin's target gives the aspect ratio).
pub fn spawn_preview(
    app: &mut App,
    material: ParallaxOcclusionMaterial,
    view: &PreviewView,
) -> Result<(), AppError> {
    spawn_preview_mesh(app, view.shape.mesh(view.tiling), material, view)
}

/// Like [`spawn_preview`] with `surface` in place of the flat plane: a mesh of about the
/// plane's size and place, such as [`Mesh::displaced_grid`] of side [`PLANE_SIZE`].
pub fn spawn_preview_mesh(
    app: &mut App,
    surface: Mesh,
    material: ParallaxOcclusionMaterial,
    view: &PreviewView,
) -> Result<(), AppError> {
    app.finish()?;
    let aspect = app
        .resources
        .require::<crate::render::RenderTarget>()?
        .aspect();
    let surface = app.resources.require_mut::<Assets<Mesh>>()?.add(surface);
    app.world.spawn(view.camera(aspect));
    app.world.spawn((
        DirectionalLight {
            color: Color::WHITE,
            intensity: 100_000.0,
        },
        view.light_transform(),
    ));
    app.world.spawn((surface, material, Transform::IDENTITY));
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::GlobalTransform;

    #[test]
    fn azimuth_zero_puts_the_camera_on_minus_u_with_u_up_and_v_right() {
        let view = PreviewView {
            view_angle: 30.0,
            ..PreviewView::default()
        };
        let (_, transform) = view.camera(1.0);
        assert!(transform.translation.x < 0.0 && transform.translation.y > 0.0);
        assert!(transform.translation.z.abs() < 1e-5);
        let global = GlobalTransform(transform.to_affine());
        let right = Vec3::from(global.0.matrix3.x_axis);
        let up = Vec3::from(global.0.matrix3.y_axis);
        assert!((right - Vec3::Z).length() < 1e-5, "right is +v: {right}");
        assert!(up.x > 0.5, "up the image is towards +u: {up}");
    }

    #[test]
    fn the_light_angle_is_measured_from_the_normal() {
        let view = PreviewView {
            light_angle: 90.0,
            light_azimuth: 90.0,
            ..PreviewView::default()
        };
        let forward = GlobalTransform(view.light_transform().to_affine()).forward();
        // On the −v side at the horizon, shining towards +v.
        assert!((forward - Vec3::Z).length() < 1e-5, "{forward}");
    }
}

/// Where a camera framing a box looks from. Angles are in degrees.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FramingView {
    /// Between the view direction and straight down (0 = from above, 90 = level).
    pub view_angle: f32,
    /// Around the vertical: 0 looks from +Z (the front), 90 from +X (the right).
    pub view_azimuth: f32,
    /// Distance as a multiple of the one at which the box just fits; < 1 zooms in.
    pub distance: f32,
}

/// The three-quarter view's direction: from the front right, 35° above.
const THREE_QUARTER: Vec3 = Vec3::new(0.6, 0.55, 0.8);

impl Default for FramingView {
    /// The three-quarter view: from the front right (36.9° around), 28.8° above the horizon.
    fn default() -> Self {
        let direction = THREE_QUARTER.normalize();
        Self {
            view_angle: direction.y.acos().to_degrees(),
            view_azimuth: direction.x.atan2(direction.z).to_degrees(),
            distance: 1.0,
        }
    }
}

impl FramingView {
    /// Unit vector from the box's centre towards the camera.
    fn direction(&self) -> Vec3 {
        if *self == Self::default() {
            // Exactly the historical vector, so reference images framed with it stay put.
            return THREE_QUARTER.normalize();
        }
        let angle = self.view_angle.clamp(0.0, 179.0).to_radians();
        let azimuth = self.view_azimuth.to_radians();
        Vec3::new(
            angle.sin() * azimuth.sin(),
            angle.cos(),
            angle.sin() * azimuth.cos(),
        )
        .normalize_or(Vec3::Y)
    }
}

/// A perspective camera looking at the box `(min, max)` from a three-quarter view (from the
/// front right, 35° above), far enough that the whole box fits the view for an image of
/// `aspect` = width / height.
pub fn three_quarter_view(bounds: (Vec3, Vec3), aspect: f32) -> (Camera, Transform) {
    framing_camera(bounds, aspect, FramingView::default())
}

/// A perspective camera looking at the box `(min, max)` from `view`, at `view.distance` times
/// the distance at which the whole box fits an image of `aspect` = width / height.
pub fn framing_camera(bounds: (Vec3, Vec3), aspect: f32, view: FramingView) -> (Camera, Transform) {
    let (min, max) = bounds;
    let centre = (min + max) * 0.5;
    let radius = ((max - min).length() * 0.5).max(1e-3);
    let fov_y = 45_f32.to_radians();
    let aspect = if aspect.is_finite() && aspect > 0.0 {
        aspect
    } else {
        1.0
    };
    // The bounding sphere fits when its angular radius is under half of the narrower field.
    let half_fov = (fov_y * 0.5).min(((fov_y * 0.5).tan() * aspect).atan());
    let factor = if view.distance.is_finite() && view.distance > 0.0 {
        view.distance
    } else {
        1.0
    };
    let distance = radius / half_fov.sin() * factor;
    let direction = view.direction();
    let camera = Camera {
        projection: Projection::Perspective {
            fov_y,
            near: (distance - radius).max(distance * 1e-3),
            far: distance + radius * 2.0,
        },
        ..Camera::default()
    };
    // Straight down (or up) needs another up vector than the view direction.
    let up = if direction.y.abs() > 0.999 {
        Vec3::NEG_Z
    } else {
        Vec3::Y
    };
    (
        camera,
        Transform::from_translation(centre + direction * distance).looking_at(centre, up),
    )
}

/// A 160,000 lux sun 50° above the horizon from the front left, and a 15,000 lux bluish sky:
/// the lighting a scene without lights of its own gets.
pub fn default_lighting() -> (DirectionalLight, Transform, crate::AmbientLight) {
    (
        DirectionalLight {
            color: Color::linear_rgb(1.0, 0.97, 0.92),
            intensity: 160_000.0,
        },
        Transform::IDENTITY.looking_at(Vec3::new(0.5, -1.2, -0.7), Vec3::Y),
        crate::AmbientLight {
            color: Color::linear_rgb(0.6, 0.7, 1.0),
            intensity: 15_000.0,
        },
    )
}

#[cfg(test)]
mod framing_tests {
    use super::*;
    use crate::GlobalTransform;

    #[test]
    fn the_three_quarter_view_sees_every_corner_of_the_box() {
        let bounds = (Vec3::new(-3.0, 0.0, -1.0), Vec3::new(5.0, 2.0, 1.0));
        for aspect in [0.5, 1.0, 2.0] {
            let (camera, transform) = three_quarter_view(bounds, aspect);
            let view_projection = camera.projection.matrix(aspect)
                * GlobalTransform(transform.to_affine()).to_mat4().inverse();
            for x in [bounds.0.x, bounds.1.x] {
                for y in [bounds.0.y, bounds.1.y] {
                    for z in [bounds.0.z, bounds.1.z] {
                        let clip = view_projection * Vec3::new(x, y, z).extend(1.0);
                        let ndc = clip.truncate() / clip.w;
                        assert!(ndc.x.abs() <= 1.0 && ndc.y.abs() <= 1.0, "{aspect}: {ndc}");
                        assert!((0.0..=1.0).contains(&ndc.z), "{aspect}: depth {}", ndc.z);
                    }
                }
            }
        }
    }
}
