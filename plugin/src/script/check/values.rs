//! Checking every number a script gives (camera, lights, ambient light, entities, steps) before
//! anything renders: one that is not finite, or outside what it can mean, is an error naming
//! its line, the element and the field.

use super::{ScriptText, line_and_column, locate, uncommented};
use crate::light::light_output_problem;
use crate::script::ScriptError;
use crate::script::format::{LightDesc, MaterialDesc, Script, ShapeDesc, Step};

/// What is wrong with one field of one element: the field, as the script spells it, and why.
type Problem = (&'static str, String);

fn finite(values: &[f32]) -> bool {
    values.iter().all(|v| v.is_finite())
}

/// `values` (the field `field`) must be finite.
fn need_finite(field: &'static str, values: &[f32]) -> Result<(), Problem> {
    if finite(values) {
        Ok(())
    } else {
        Err((field, format!("{field} {values:?} is not finite")))
    }
}

/// `value` (the field `field`) must be finite and > 0.
fn need_positive(field: &'static str, value: f32) -> Result<(), Problem> {
    if value.is_finite() && value > 0.0 {
        Ok(())
    } else {
        Err((field, format!("{field} {value} is not finite and > 0")))
    }
}

/// A direction must be finite and have a length.
fn need_direction(field: &'static str, direction: [f32; 3]) -> Result<(), Problem> {
    need_finite(field, &direction)?;
    if direction == [0.0; 3] {
        return Err((field, format!("{field} {direction:?} has no length")));
    }
    Ok(())
}

/// Checks every number of `script`.
pub(super) fn check_values(script: &Script, source: &ScriptText<'_>) -> Result<(), ScriptError> {
    let camera_at = |(field, reason): Problem| {
        source.invalid(
            locate(source.text, field, "camera"),
            format!("camera {reason}"),
        )
    };
    check_camera(script).map_err(camera_at)?;
    for (index, light) in script.lights.iter().enumerate() {
        check_light(light).map_err(|(field, reason)| {
            source.invalid(
                locate_light(source.text, index, field),
                format!("light {index}: {reason}"),
            )
        })?;
    }
    if let Some((color, intensity)) = script.ambient
        && let Some((_, reason)) = light_output_problem(color, intensity)
    {
        return Err(source.invalid(
            locate(source.text, "ambient", ""),
            format!("ambient light {reason}"),
        ));
    }
    for entity in &script.entities {
        check_entity(entity).map_err(|(field, reason)| {
            source.invalid(
                locate(source.text, field, &format!("\"{}\"", entity.name)),
                format!("entity {:?}: {reason}", entity.name),
            )
        })?;
    }
    for (index, step) in script.steps.iter().enumerate() {
        check_step(step).map_err(|(field, reason)| {
            source.invalid(
                locate_step(source.text, &script.steps, index, field),
                format!("step {} ({}): {reason}", index + 1, step_kind(step)),
            )
        })?;
    }
    Ok(())
}

/// The camera's place and projection.
fn check_camera(script: &Script) -> Result<(), Problem> {
    let camera = &script.camera;
    need_finite("position", &camera.position)?;
    need_finite("target", &camera.target)?;
    if camera.position == camera.target {
        return Err((
            "target",
            format!(
                "target {:?} is its position: it looks nowhere",
                camera.target
            ),
        ));
    }
    if let Some(fov) = camera.fov_degrees
        && !(fov > 0.0 && fov < 180.0)
    {
        return Err((
            "fov_degrees",
            format!("fov_degrees {fov} is outside 0 < fov < 180"),
        ));
    }
    if let Some(height) = camera.orthographic_height {
        need_positive("orthographic_height", height)?;
    }
    Ok(())
}

/// A light's place, direction, output, range and cone.
fn check_light(light: &LightDesc) -> Result<(), Problem> {
    let (color, intensity) = match light {
        LightDesc::Directional {
            direction,
            color,
            intensity,
            ..
        } => {
            need_direction("direction", *direction)?;
            (color, intensity)
        }
        LightDesc::Point {
            position,
            color,
            intensity,
            range,
            ..
        } => {
            need_finite("position", position)?;
            need_range(*range)?;
            (color, intensity)
        }
        LightDesc::Spot {
            position,
            direction,
            color,
            intensity,
            range,
            inner_degrees,
            outer_degrees,
            ..
        } => {
            need_finite("position", position)?;
            need_direction("direction", *direction)?;
            need_range(*range)?;
            need_cone(*inner_degrees, *outer_degrees)?;
            (color, intensity)
        }
    };
    match light_output_problem(*color, *intensity) {
        Some(problem) => Err(problem),
        None => Ok(()),
    }
}

/// A range is > 0; infinite means none.
fn need_range(range: f32) -> Result<(), Problem> {
    if range > 0.0 {
        Ok(())
    } else {
        Err(("range", format!("range {range} is not > 0")))
    }
}

/// A spot's cone, as glTF's: 0 ≤ inner ≤ outer ≤ 90 degrees, outer > 0.
fn need_cone(inner: f32, outer: f32) -> Result<(), Problem> {
    if !(outer > 0.0 && outer <= 90.0) {
        return Err((
            "outer_degrees",
            format!("outer_degrees {outer} is outside 0 < outer ≤ 90"),
        ));
    }
    if !(inner >= 0.0 && inner <= outer) {
        return Err((
            "inner_degrees",
            format!("inner_degrees {inner} is outside 0 ≤ inner ≤ outer_degrees {outer}"),
        ));
    }
    Ok(())
}

/// An entity's placement, shape and colour.
fn check_entity(entity: &crate::script::EntityDesc) -> Result<(), Problem> {
    let transform = &entity.transform;
    need_finite("translation", &transform.translation)?;
    need_finite("rotation_degrees", &transform.rotation_degrees)?;
    if let Some(scale) = transform.scale {
        need_finite("scale", &scale)?;
        if scale.contains(&0.0) {
            return Err(("scale", format!("scale {scale:?} flattens it to nothing")));
        }
    }
    match &entity.shape {
        Some(ShapeDesc::Plane { size, tiling }) => {
            need_positive("size", *size)?;
            need_positive("tiling", *tiling)?;
        }
        Some(ShapeDesc::Cube { size }) => need_positive("size", *size)?,
        Some(ShapeDesc::Sphere { radius }) => need_positive("radius", *radius)?,
        Some(ShapeDesc::Cylinder { radius, height }) => {
            need_positive("radius", *radius)?;
            need_positive("height", *height)?;
        }
        None => {}
    }
    if let Some(MaterialDesc::Lit { color }) = &entity.material
        && !color.iter().all(|c| c.is_finite() && *c >= 0.0)
    {
        return Err(("color", format!("color {color:?} is not finite and ≥ 0")));
    }
    Ok(())
}

/// A step's numbers.
fn check_step(step: &Step) -> Result<(), Problem> {
    match step {
        Step::Camera { position, target } => {
            need_finite("position", position)?;
            need_finite("target", target)?;
            if position == target {
                return Err((
                    "target",
                    format!("target {target:?} is its position: it looks nowhere"),
                ));
            }
        }
        Step::OrbitCamera { degrees } => need_finite("degrees", &[*degrees])?,
        Step::MoveLight {
            direction,
            position,
            ..
        } => {
            if let Some(direction) = direction {
                need_direction("direction", *direction)?;
            }
            if let Some(position) = position {
                need_finite("position", position)?;
            }
        }
        Step::Spin {
            degrees_per_frame, ..
        } => need_finite("degrees_per_frame", &[*degrees_per_frame])?,
        _ => {}
    }
    Ok(())
}

/// The name a step is written with.
pub(super) fn step_kind(step: &Step) -> &'static str {
    match step {
        Step::Advance { .. } => "Advance",
        Step::Set { .. } => "Set",
        Step::Camera { .. } => "Camera",
        Step::OrbitCamera { .. } => "OrbitCamera",
        Step::MoveLight { .. } => "MoveLight",
        Step::Spin { .. } => "Spin",
        Step::Capture { .. } => "Capture",
        Step::ExpectMatch { .. } => "ExpectMatch",
        Step::ExpectStat { .. } => "ExpectStat",
        Step::ExpectMonotonic { .. } => "ExpectMonotonic",
    }
}

/// Byte offsets where elements written as `names` (`Name(`) start, after `section`, in order.
fn element_starts(text: &str, section: &str, names: &[&str]) -> Vec<usize> {
    let start = uncommented(text, section, 0).next().unwrap_or(0);
    let mut starts: Vec<usize> = names
        .iter()
        .flat_map(|name| {
            // `Camera(` is also the end of `OrbitCamera(`: only a whole word counts.
            uncommented(text, &format!("{name}("), start)
                .filter(|&offset| {
                    !text[..offset]
                        .chars()
                        .next_back()
                        .is_some_and(|c| c.is_alphanumeric() || c == '_')
                })
                .collect::<Vec<_>>()
        })
        .collect();
    starts.sort_unstable();
    starts
}

/// Line and column of `field` inside the element starting at `starts[nth]` (or of the element
/// itself, or of `section` when the element is not found).
fn locate_in_element(text: &str, starts: &[usize], nth: usize, field: &str) -> (usize, usize) {
    let Some(&start) = starts.get(nth) else {
        return line_and_column(text, 0);
    };
    let end = starts.get(nth + 1).copied().unwrap_or(text.len());
    let offset = text[start..end]
        .find(field)
        .map_or(start, |found| start + found);
    line_and_column(text, offset)
}

/// Line and column of `field` of light `nth` (0-based) as written.
fn locate_light(text: &str, nth: usize, field: &str) -> (usize, usize) {
    let starts = element_starts(text, "lights", &["Directional", "Point", "Spot"]);
    locate_in_element(text, &starts, nth, field)
}

/// Line and column of `field` of step `nth` (0-based) of `steps` as written: the step is the
/// how-manieth of its kind.
pub(super) fn locate_step(text: &str, steps: &[Step], nth: usize, field: &str) -> (usize, usize) {
    let Some(step) = steps.get(nth) else {
        return line_and_column(text, 0);
    };
    let kind = step_kind(step);
    let of_its_kind = steps[..nth]
        .iter()
        .filter(|earlier| step_kind(earlier) == kind)
        .count();
    let starts = element_starts(text, "steps", &[kind]);
    locate_in_element(text, &starts, of_its_kind, field)
}
