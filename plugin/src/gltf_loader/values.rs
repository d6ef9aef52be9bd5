//! The numbers a glTF scene's nodes carry (transforms, cameras, lights), checked before they
//! are used: each is fixed with a warning or refused with an error, never drawn silently wrong.

use glam::{Affine3A, Mat4, Quat, Vec3};

use crate::light::{clamped_light_output, light_output_problem};
use crate::{Camera, Projection, Transform};

/// Far plane of a perspective camera that gives none (glTF's infinite projection), as a
/// multiple of its near plane, at least 1000 units.
const FAR_PER_NEAR: f32 = 1000.0;

/// A node's local transform, or why it cannot place anything (not finite, or flattening
/// space: a zero scale, a singular matrix). A rotation of zero length or not finite is
/// replaced by none, with a warning in `warnings`.
pub(super) fn node_transform(
    node: &gltf::Node<'_>,
    node_name: &str,
    warnings: &mut Vec<String>,
) -> Result<Transform, String> {
    let (translation, rotation, scale) = match node.transform() {
        gltf::scene::Transform::Matrix { matrix } => {
            let matrix = Mat4::from_cols_array_2d(&matrix);
            let determinant = glam::Mat3::from_mat4(matrix).determinant();
            if !matrix.is_finite() {
                return Err(format!("matrix {matrix:?} is not finite"));
            }
            if !(determinant.is_finite() && determinant != 0.0) {
                return Err(format!(
                    "matrix {:?} has determinant {determinant}: it is singular or overflows",
                    matrix.to_cols_array()
                ));
            }
            let (scale, rotation, translation) = matrix.to_scale_rotation_translation();
            (translation, rotation, scale)
        }
        gltf::scene::Transform::Decomposed {
            translation,
            rotation,
            scale,
        } => {
            let rotation = Quat::from_array(rotation);
            let length = rotation.length();
            let rotation = if length.is_finite() && length > 0.0 {
                rotation / length
            } else {
                warnings.push(format!(
                    "node {node_name}: rotation {:?} is not a usable quaternion; none used",
                    rotation.to_array()
                ));
                Quat::IDENTITY
            };
            (Vec3::from(translation), rotation, Vec3::from(scale))
        }
    };
    if !translation.is_finite() {
        return Err(format!("translation {translation} is not finite"));
    }
    if !scale.is_finite() || scale.cmpeq(Vec3::ZERO).any() {
        return Err(format!("scale {scale} is not finite and non-zero"));
    }
    Ok(Transform {
        translation,
        rotation,
        scale,
    })
}

/// Why `world`, a node's place in the world, cannot place anything: its products overflowed,
/// or it flattens space.
pub(super) fn world_problem(world: Affine3A) -> Option<String> {
    let determinant = world.matrix3.determinant();
    (!(world.is_finite() && determinant.is_finite() && determinant != 0.0)).then(|| {
        format!(
            "its world transform (its ancestors' times its own) has determinant {determinant}: it is singular or overflows"
        )
    })
}

/// The camera a glTF camera describes, or which of its fields is unusable and why.
pub(super) fn camera_of(camera: &gltf::Camera<'_>) -> Result<Camera, String> {
    let projection = match camera.projection() {
        gltf::camera::Projection::Perspective(perspective) => {
            let (fov_y, near) = (perspective.yfov(), perspective.znear());
            if !(fov_y > 0.0 && fov_y < std::f32::consts::PI) {
                return Err(format!(
                    "perspective.yfov {fov_y} is outside 0 < yfov < π radians"
                ));
            }
            if !(near.is_finite() && near > 0.0) {
                return Err(format!("perspective.znear {near} is not finite and > 0"));
            }
            let far = perspective
                .zfar()
                .unwrap_or((near * FAR_PER_NEAR).max(1000.0));
            if !(far.is_finite() && far > near) {
                return Err(format!(
                    "perspective.zfar {far} is not finite and greater than znear {near}"
                ));
            }
            Projection::Perspective { fov_y, near, far }
        }
        gltf::camera::Projection::Orthographic(orthographic) => {
            let (ymag, near, far) = (
                orthographic.ymag(),
                orthographic.znear(),
                orthographic.zfar(),
            );
            if !(ymag.is_finite() && ymag > 0.0) {
                return Err(format!("orthographic.ymag {ymag} is not finite and > 0"));
            }
            if !(near.is_finite() && near >= 0.0) {
                return Err(format!("orthographic.znear {near} is not finite and ≥ 0"));
            }
            if !(far.is_finite() && far > near) {
                return Err(format!(
                    "orthographic.zfar {far} is not finite and greater than znear {near}"
                ));
            }
            Projection::Orthographic {
                height: ymag * 2.0,
                near,
                far,
            }
        }
    };
    Ok(Camera {
        projection,
        ..Camera::default()
    })
}

/// The value at `pom.KEY` of an element's raw `extras` JSON: `None` without one, or why the
/// JSON is unreadable.
fn pom_extra(
    raw: Option<&serde_json::value::RawValue>,
    key: &str,
) -> Result<Option<serde_json::Value>, String> {
    let Some(raw) = raw else {
        return Ok(None);
    };
    let mut value: serde_json::Value =
        serde_json::from_str(raw.get()).map_err(|e| e.to_string())?;
    Ok(value
        .get_mut("pom")
        .and_then(|pom| pom.get_mut(key))
        .map(serde_json::Value::take))
}

/// The exposure a glTF camera asks for in `extras.pom.exposure` (EV100, as `--exposure`):
/// `None` without one, or why it is unusable. A scene lit at night carries its own.
pub(super) fn camera_exposure(
    camera: &gltf::Camera<'_>,
) -> Result<Option<crate::Exposure>, String> {
    let Some(exposure) = pom_extra(camera.extras().as_deref(), "exposure")? else {
        return Ok(None);
    };
    let range = crate::Exposure::RANGE;
    match exposure.as_f64().map(|ev100| ev100 as f32) {
        Some(ev100) if range.contains(&ev100) => Ok(Some(crate::Exposure { ev100 })),
        _ => Err(format!(
            "extras.pom.exposure {exposure} is not an EV100 in {}..={}",
            range.start(),
            range.end()
        )),
    }
}

/// The ambient light a glTF scene asks for in `extras.pom.ambient` (`{"color": [r, g, b],
/// "intensity": lux}`, linear colour, as [`crate::AmbientLight`]): `None` without one, or why
/// it is unusable. A scene lit at night carries its own (the default is a day's).
pub(super) fn scene_ambient(
    scene: &gltf::Scene<'_>,
) -> Result<Option<crate::AmbientLight>, String> {
    let Some(ambient) = pom_extra(scene.extras().as_deref(), "ambient")? else {
        return Ok(None);
    };
    let intensity = ambient["intensity"].as_f64().map(|lux| lux as f32);
    let color: Option<Vec<f32>> = ambient["color"]
        .as_array()
        .and_then(|rgb| rgb.iter().map(|c| c.as_f64().map(|c| c as f32)).collect());
    match (intensity, color.as_deref()) {
        (Some(lux), Some(&[r, g, b]))
            if lux.is_finite()
                && lux >= 0.0
                && [r, g, b].iter().all(|c| (0.0..=1.0).contains(c)) =>
        {
            Ok(Some(crate::AmbientLight {
                color: crate::Color::linear_rgb(r, g, b),
                intensity: lux,
            }))
        }
        _ => Err(format!(
            "extras.pom.ambient {ambient} is not {{\"color\": [r, g, b] in 0..=1, \"intensity\": lux ≥ 0}}"
        )),
    }
}

/// A light's colour and intensity within [`crate::MAX_LIGHT_OUTPUT`], with a warning in
/// `warnings` when they had to be changed.
pub(super) fn light_output(
    light: &gltf::khr_lights_punctual::Light<'_>,
    node_name: &str,
    warnings: &mut Vec<String>,
) -> ([f32; 3], f32) {
    let (color, intensity) = (light.color(), light.intensity());
    if let Some((_, problem)) = light_output_problem(color, intensity) {
        let (color, intensity) = clamped_light_output(color, intensity);
        warnings.push(format!(
            "node {node_name}: light {problem}; clamped to color {color:?}, intensity {intensity:?}"
        ));
        return (color, intensity);
    }
    (color, intensity)
}

/// A light's range: none (unbounded, as `KHR_lights_punctual` defines it) when it gives none,
/// or one that is not > 0, with a warning in `warnings` for the latter.
pub(super) fn light_range(
    light: &gltf::khr_lights_punctual::Light<'_>,
    node_name: &str,
    warnings: &mut Vec<String>,
) -> f32 {
    match light.range() {
        Some(range) if range > 0.0 => range,
        Some(range) => {
            warnings.push(format!(
                "node {node_name}: light range {range} is not > 0; unbounded"
            ));
            f32::INFINITY
        }
        None => f32::INFINITY,
    }
}
