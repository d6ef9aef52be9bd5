//! Where each shadow map looks from: a directional light's cascades fitted to slices of the
//! camera's view, a spot light's perspective map, a point light's six cube faces. Pure math,
//! done in the Extract stage.

use glam::camera::rh::proj::directx::{orthographic, perspective, perspective_infinite};
use glam::camera::rh::view::look_to_mat4;
use glam::{Mat4, Vec3};

use crate::render::{ShadowViewGpu, ShadowViewPlan};
use crate::{DIRECTIONAL_CASCADES, LightShadows, Projection};

/// How far the near plane of a spot's or cube face's map lies from the light.
const PERSPECTIVE_NEAR: f32 = 0.05;

/// The camera whose view the cascades cover.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CascadeCamera {
    /// Its position.
    pub position: Vec3,
    /// Unit vectors: where it looks, its right and its up.
    pub forward: Vec3,
    /// Its right.
    pub right: Vec3,
    /// Its up.
    pub up: Vec3,
    /// Its projection.
    pub projection: Projection,
    /// Image width / height.
    pub aspect: f32,
}

/// Any vector not parallel to `forward`, to orient a light's view.
fn up_for(forward: Vec3) -> Vec3 {
    if forward.y.abs() < 0.99 {
        Vec3::Y
    } else {
        Vec3::X
    }
}

/// Widens a half-extent (a half-angle's tangent, a cascade's radius) so that the filter and the
/// receiver offsets near the map's edge still read inside it: `margin_texels` more on each side
/// of a `map_size` map.
fn widened_tan(tan_half_angle: f32, margin_texels: f32, map_size: u32) -> f32 {
    tan_half_angle * (1.0 + 2.0 * margin_texels / map_size as f32)
}

/// The filter's reach plus the receivers' largest offsets (shadows.wgsl), in texels.
fn margin_texels(settings: &LightShadows) -> f32 {
    2.0 * settings.softness + 4.0
}

fn perspective_view(
    eye: Vec3,
    forward: Vec3,
    tan_half_angle: f32,
    range: f32,
    settings: &LightShadows,
) -> ShadowViewPlan {
    let tan_half = widened_tan(tan_half_angle, margin_texels(settings), settings.map_size);
    let fov = 2.0 * tan_half.atan();
    let projection = if range.is_finite() && range > PERSPECTIVE_NEAR * 2.0 {
        perspective(fov, 1.0, PERSPECTIVE_NEAR, range)
    } else {
        perspective_infinite(fov, 1.0, PERSPECTIVE_NEAR)
    };
    let view = look_to_mat4(eye, forward, up_for(forward));
    ShadowViewPlan {
        gpu: ShadowViewGpu {
            view_projection: (projection * view).to_cols_array_2d(),
            uv_scale: 1.0,
            far_view_depth: f32::INFINITY,
            texel_world_size: 2.0 * tan_half / settings.map_size as f32,
            perspective: 1,
            softness: settings.softness,
            layer: 0,
            _padding: [0; 2],
        },
        eye,
        forward,
        orthographic: false,
        map_size: settings.map_size,
    }
}

/// A spot light's map: a perspective view down its axis covering its outer cone.
pub fn spot_view(
    position: Vec3,
    forward: Vec3,
    outer_angle: f32,
    range: f32,
    settings: &LightShadows,
) -> ShadowViewPlan {
    let tan_half = outer_angle.min(1.5).tan();
    perspective_view(position, forward, tan_half, range, settings)
}

/// The directions of a point light's cube faces, in the order the shaders pick them.
pub const CUBE_FACES: [Vec3; 6] = [
    Vec3::X,
    Vec3::NEG_X,
    Vec3::Y,
    Vec3::NEG_Y,
    Vec3::Z,
    Vec3::NEG_Z,
];

/// A point light's six maps: 90° (slightly widened) views along ±X, ±Y, ±Z.
pub fn point_views(position: Vec3, range: f32, settings: &LightShadows) -> [ShadowViewPlan; 6] {
    CUBE_FACES.map(|face| perspective_view(position, face, 1.0, range, settings))
}

/// The view distances at which the cascades end, nearest first: the practical split scheme
/// (half logarithmic, half uniform), between the camera's near plane and `distance`.
pub fn cascade_ends(near: f32, distance: f32) -> [f32; DIRECTIONAL_CASCADES] {
    let near = near.max(1e-3);
    let far = distance.max(near * 1.01);
    std::array::from_fn(|i| {
        let t = (i + 1) as f32 / DIRECTIONAL_CASCADES as f32;
        let logarithmic = near * (far / near).powf(t);
        let uniform = near + (far - near) * t;
        0.5 * (logarithmic + uniform)
    })
}

/// The corners of the camera's view between distances `near` and `far` along its view.
fn slice_corners(camera: &CascadeCamera, near: f32, far: f32) -> [Vec3; 8] {
    let extent = |depth: f32| match camera.projection {
        Projection::Perspective { fov_y, .. } => {
            let half_height = depth * (fov_y * 0.5).tan();
            (half_height * camera.aspect, half_height)
        }
        Projection::Orthographic { height, .. } => {
            let half_height = height * 0.5;
            (half_height * camera.aspect, half_height)
        }
    };
    let mut corners = [Vec3::ZERO; 8];
    for (i, depth) in [near, far].into_iter().enumerate() {
        let (half_width, half_height) = extent(depth);
        let centre = camera.position + camera.forward * depth;
        for (j, (sx, sy)) in [(-1.0, -1.0), (1.0, -1.0), (-1.0, 1.0), (1.0, 1.0)]
            .into_iter()
            .enumerate()
        {
            corners[i * 4 + j] =
                centre + camera.right * (sx * half_width) + camera.up * (sy * half_height);
        }
    }
    corners
}

/// A directional light's cascades: each an orthographic view around the bounding sphere of its
/// slice of the camera's view (stable as the camera turns), its centre snapped to whole texels
/// (stable as the camera moves), reaching `settings.distance` further towards the light for
/// casters outside the slice.
pub fn directional_views(
    camera: &CascadeCamera,
    light_forward: Vec3,
    settings: &LightShadows,
) -> [ShadowViewPlan; DIRECTIONAL_CASCADES] {
    let slices = cascade_slices(camera, settings);
    let up = up_for(light_forward);
    let rotation = look_to_mat4(Vec3::ZERO, light_forward, up);
    let map_size = settings.map_size as f32;
    std::array::from_fn(|i| {
        let (start, end) = slices[i];
        let corners = slice_corners(camera, start, end);
        let centre = corners.iter().copied().sum::<Vec3>() / 8.0;
        let radius = corners
            .iter()
            .map(|corner| corner.distance(centre))
            .fold(0.0_f32, f32::max);
        // Room for the filter and the receivers' offsets at the rim (as spot and cube maps have),
        // in whole 1/16 units, so the texel size only changes in steps as the view changes.
        let radius = widened_tan(radius, margin_texels(settings), settings.map_size);
        let radius = ((radius * 16.0).ceil() / 16.0).max(1.0 / 16.0);
        let texel = 2.0 * radius / map_size;
        let centre_in_light = rotation.transform_point3(centre);
        let snapped = Vec3::new(
            (centre_in_light.x / texel).floor() * texel,
            (centre_in_light.y / texel).floor() * texel,
            centre_in_light.z,
        );
        let centre = rotation.inverse().transform_point3(snapped);
        let reach = radius + settings.distance;
        let eye = centre - light_forward * reach;
        let view = look_to_mat4(eye, light_forward, up);
        let projection = orthographic(-radius, radius, -radius, radius, 0.0, reach + radius);
        ShadowViewPlan {
            gpu: ShadowViewGpu {
                view_projection: (projection * view).to_cols_array_2d(),
                uv_scale: 1.0,
                far_view_depth: end,
                texel_world_size: texel,
                perspective: 0,
                softness: settings.softness,
                layer: 0,
                _padding: [0; 2],
            },
            eye,
            forward: light_forward,
            orthographic: true,
            map_size: settings.map_size,
        }
    })
}

/// The view distances each cascade covers, nearest first: from the camera's near plane to
/// `settings.distance` (or its far plane).
fn cascade_slices(
    camera: &CascadeCamera,
    settings: &LightShadows,
) -> [(f32, f32); DIRECTIONAL_CASCADES] {
    let (near, far) = match camera.projection {
        Projection::Perspective { near, far, .. } | Projection::Orthographic { near, far, .. } => {
            (near, far)
        }
    };
    let ends = cascade_ends(near.max(0.0), settings.distance.min(far.max(near + 1e-3)));
    std::array::from_fn(|i| (if i == 0 { near.max(0.0) } else { ends[i - 1] }, ends[i]))
}

/// Whether cascade `index`, kept as `kept`, still serves its slice of `camera`'s view: every
/// corner of the slice inside the map, clear of the filter's and the receivers' margin (less
/// the texels a freshly fitted cascade's snapped centre may take of it), and the casters
/// `settings.distance` towards the light still inside its depth range. A freshly fitted
/// cascade does.
pub fn cascade_covers(
    camera: &CascadeCamera,
    settings: &LightShadows,
    index: usize,
    kept: &ShadowViewPlan,
) -> bool {
    let Some(&(start, end)) = cascade_slices(camera, settings).get(index) else {
        return false;
    };
    let map_size = kept.map_size as f32;
    let matrix = Mat4::from_cols_array_2d(&kept.gpu.view_projection);
    let edge = 1.0 - 2.0 * (margin_texels(settings) - SNAP_TEXELS) / map_size;
    // The orthographic depth range: the cascade's diameter and the casters' reach before it.
    let radius = kept.gpu.texel_world_size * map_size / 2.0;
    let nearest = settings.distance / (2.0 * radius + settings.distance);
    slice_corners(camera, start, end).iter().all(|corner| {
        let ndc = matrix.project_point3(*corner);
        ndc.x.abs() <= edge && ndc.y.abs() <= edge && (nearest..=1.0).contains(&ndc.z)
    })
}

/// Texels by which snapping a cascade's centre to whole texels may move its slice towards
/// the map's edge (one along each axis), with room for rounding.
const SNAP_TEXELS: f32 = 2.0;

#[cfg(test)]
pub(super) mod tests {
    use super::*;

    /// A camera above and in front of the origin, looking along −Z.
    pub(in crate::render::shadows) fn camera() -> CascadeCamera {
        CascadeCamera {
            position: Vec3::new(0.0, 2.0, 5.0),
            forward: Vec3::NEG_Z,
            right: Vec3::X,
            up: Vec3::Y,
            projection: Projection::Perspective {
                fov_y: 1.0,
                near: 0.1,
                far: 200.0,
            },
            aspect: 1.5,
        }
    }

    #[test]
    fn cascades_grow_outwards_and_end_at_the_shadow_distance() {
        let ends = cascade_ends(0.1, 50.0);
        assert!(ends.windows(2).all(|pair| pair[0] < pair[1]), "{ends:?}");
        assert!((ends[DIRECTIONAL_CASCADES - 1] - 50.0).abs() < 1e-3);
    }

    #[test]
    fn every_cascade_sees_its_slice_of_the_view() {
        let camera = camera();
        let settings = LightShadows::default();
        let light = Vec3::new(0.3, -1.0, 0.2).normalize();
        let views = directional_views(&camera, light, &settings);
        let ends = cascade_ends(0.1, settings.distance);
        for (i, view) in views.iter().enumerate() {
            let start = if i == 0 { 0.1 } else { ends[i - 1] };
            let matrix = Mat4::from_cols_array_2d(&view.gpu.view_projection);
            for corner in slice_corners(&camera, start, ends[i]) {
                let ndc = matrix.project_point3(corner);
                assert!(
                    ndc.x.abs() <= 1.0 && ndc.y.abs() <= 1.0,
                    "cascade {i}: {ndc}"
                );
                assert!((0.0..=1.0).contains(&ndc.z), "cascade {i}: {ndc}");
            }
        }
    }

    #[test]
    fn a_freshly_fitted_cascade_covers_its_slice_and_a_far_moved_camera_leaves_it() {
        let settings = LightShadows::default();
        for step in 0..64 {
            let turn = glam::Quat::from_rotation_y(step as f32 * 0.37);
            let camera = CascadeCamera {
                position: Vec3::new(step as f32 * 1.3, 2.0 + step as f32 * 0.05, -(step as f32)),
                forward: turn * Vec3::NEG_Z,
                right: turn * Vec3::X,
                ..camera()
            };
            let light = Vec3::new(0.3, -1.0, 0.2 + step as f32 * 0.01).normalize();
            for (index, view) in directional_views(&camera, light, &settings)
                .iter()
                .enumerate()
            {
                assert!(
                    cascade_covers(&camera, &settings, index, view),
                    "{step}, {index}"
                );
                let away = CascadeCamera {
                    position: camera.position + camera.right * settings.distance,
                    ..camera
                };
                assert!(
                    !cascade_covers(&away, &settings, index, view),
                    "{step}, {index}"
                );
            }
        }
    }

    #[test]
    fn a_point_light_face_sees_what_its_axis_points_at() {
        let views = point_views(Vec3::ONE, 20.0, &LightShadows::default());
        for (face, view) in CUBE_FACES.iter().zip(&views) {
            let matrix = Mat4::from_cols_array_2d(&view.gpu.view_projection);
            let ndc = matrix
                .project_point3(Vec3::ONE + *face * 5.0 + face.any_orthonormal_vector() * 4.9);
            assert!(ndc.x.abs() <= 1.0 && ndc.y.abs() <= 1.0, "{face}: {ndc}");
            assert!((0.0..=1.0).contains(&ndc.z), "{face}: {ndc}");
        }
    }
}
