//! Checking a script's names and files before anything runs, with line and column.

mod expectations;
mod materials;
mod values;

use std::path::Path;

use crate::files::{FileAccess, FileError, check_regular, resolve_inside};
use crate::parameters::DeclaredSettings;

use super::ScriptError;
use super::format::{EntityDesc, MAX_ADVANCE_FRAMES, MaterialDesc, Script, Statistic, Step};

/// Line and column (1-based) of the first `needle` in `text` after `after` (or anywhere).
fn locate(text: &str, needle: &str, after: &str) -> (usize, usize) {
    let start = text.find(after).unwrap_or(0);
    let offset = text[start..]
        .find(needle)
        .map_or(start, |found| start + found);
    line_and_column(text, offset)
}

/// Line and column (1-based) of byte `offset` of `text`.
fn line_and_column(text: &str, offset: usize) -> (usize, usize) {
    let before = &text[..offset];
    let line = before.matches('\n').count() + 1;
    let column = before.len() - before.rfind('\n').map_or(0, |newline| newline + 1) + 1;
    (line, column)
}

/// Byte offsets of `needle` in `text` from `start` on, leaving out `//` comments.
fn uncommented(text: &str, needle: &str, start: usize) -> impl Iterator<Item = usize> {
    text[start..]
        .match_indices(needle)
        .map(move |(found, _)| start + found)
        .filter(|&offset| {
            let line_start = text[..offset].rfind('\n').map_or(0, |newline| newline + 1);
            !text[line_start..offset].contains("//")
        })
}

/// Line and column of `field` inside the `nth` (0-based) `shadows` setting of the script's
/// lights, or of that setting itself: the lights' shadows are found in the order written.
fn locate_light_shadows(text: &str, nth: usize, field: &str) -> (usize, usize) {
    let lights = uncommented(text, "lights", 0).next().unwrap_or(0);
    let Some(setting) = uncommented(text, "shadows", lights).nth(nth) else {
        return line_and_column(text, lights);
    };
    // The field's own line when it is written inside this setting (before its closing bracket).
    let end = text[setting..]
        .find(')')
        .map_or(text.len(), |close| setting + close);
    let offset = text[setting..end]
        .find(field)
        .map_or(setting, |found| setting + found);
    line_and_column(text, offset)
}

/// The script's text and file, which every error found in it names with a line and column.
struct ScriptText<'a> {
    text: &'a str,
    path: &'a Path,
    /// Which files the script may name.
    access: FileAccess,
}

impl ScriptText<'_> {
    /// A text that is not a valid script (a value out of range) at `line` and `column`.
    fn invalid(&self, (line, column): (usize, usize), reason: String) -> ScriptError {
        ScriptError::Parse {
            path: self.path.to_owned(),
            line,
            column,
            reason,
        }
    }

    /// A reference to something missing at `line` and `column`.
    fn reference(&self, (line, column): (usize, usize), reason: String) -> ScriptError {
        ScriptError::Reference {
            path: self.path.to_owned(),
            line,
            column,
            reason,
        }
    }

    /// A reference to something missing, placed at the first `"needle"` after `after`.
    fn missing(&self, needle: &str, after: &str, reason: String) -> ScriptError {
        self.reference(locate(self.text, &format!("\"{needle}\""), after), reason)
    }

    /// A step that reads capture `capture` before any step takes it.
    fn no_capture(&self, capture: &str) -> ScriptError {
        self.missing(
            capture,
            "steps",
            format!("no capture named {capture:?} is taken before this step"),
        )
    }
}

/// Checks every name and file the script refers to before anything runs.
pub(super) fn check(
    script: &Script,
    text: &str,
    path: &Path,
    dir: &Path,
    access: FileAccess,
) -> Result<(), ScriptError> {
    let source = ScriptText { text, path, access };
    check_exposure(script, &source)?;
    check_anti_aliasing(script, &source)?;
    check_environment(script, &source, dir)?;
    check_light_shadows(script, &source)?;
    check_advances(script, &source)?;
    values::check_values(script, &source)?;
    let names = check_entities(script, &source, dir)?;
    check_steps(script, &names, &source)?;
    materials::check_materials(script, &source, dir)?;
    expectations::check_expectations(script, &source)
}

/// The camera's exposure, if given, is within [`crate::Exposure::RANGE`].
fn check_exposure(script: &Script, source: &ScriptText<'_>) -> Result<(), ScriptError> {
    if let Some(ev100) = script.camera.exposure
        && !crate::Exposure::RANGE.contains(&ev100)
    {
        return Err(source.invalid(
            locate(source.text, "exposure", "camera"),
            format!(
                "camera exposure {ev100} EV100 is outside {}..={}",
                crate::Exposure::RANGE.start(),
                crate::Exposure::RANGE.end()
            ),
        ));
    }
    Ok(())
}

/// The environment, if given, names a source that parses (a file: one inside the folder
/// `access` allows) and parameters within their limits.
fn check_environment(
    script: &Script,
    source: &ScriptText<'_>,
    dir: &Path,
) -> Result<(), ScriptError> {
    let Some(environment) = &script.environment else {
        return Ok(());
    };
    let at = || locate(source.text, "source", "environment");
    let choice: crate::EnvironmentChoice = environment
        .source
        .parse()
        .map_err(|error: crate::EnvironmentError| source.invalid(at(), error.to_string()))?;
    if let crate::EnvironmentChoice::File(file) = &choice
        && let Some(problem) = file_problem(dir, file, source.access)
    {
        return Err(source.invalid(at(), format!("environment file {file:?} {problem}")));
    }
    match environment.settings.problems().into_iter().next() {
        Some(problem) => Err(source.invalid(
            locate(source.text, "settings", "environment"),
            format!("environment settings.{problem}"),
        )),
        None => Ok(()),
    }
}

/// The parameters of TAA and FXAA, if given, are within their limits.
fn check_anti_aliasing(script: &Script, source: &ScriptText<'_>) -> Result<(), ScriptError> {
    check_settings(script.camera.taa, "taa", source)?;
    check_settings(script.camera.fxaa, "fxaa", source)
}

/// The camera's settings under `key`, if given, are within their declared limits; the error
/// names the first parameter that is not.
fn check_settings<S: DeclaredSettings>(
    settings: Option<S>,
    key: &str,
    source: &ScriptText<'_>,
) -> Result<(), ScriptError> {
    match settings.and_then(|settings| settings.problems().into_iter().next()) {
        Some(problem) => Err(source.invalid(
            locate(source.text, key, "camera"),
            format!("camera {key}.{problem}"),
        )),
        None => Ok(()),
    }
}

/// No `Advance` step runs more than [`MAX_ADVANCE_FRAMES`] frames.
fn check_advances(script: &Script, source: &ScriptText<'_>) -> Result<(), ScriptError> {
    let advances = script
        .steps
        .iter()
        .enumerate()
        .filter_map(|(index, step)| match step {
            Step::Advance { frames } => Some((index, *frames)),
            _ => None,
        });
    for (nth, (index, frames)) in advances.enumerate() {
        if frames > MAX_ADVANCE_FRAMES {
            // The steps' `Advance`s are found in the order written.
            let steps = uncommented(source.text, "steps", 0).next().unwrap_or(0);
            let offset = uncommented(source.text, "Advance", steps)
                .nth(nth)
                .unwrap_or(steps);
            return Err(source.invalid(
                line_and_column(source.text, offset),
                format!(
                    "step {}: Advance of {frames} frames is more than the {MAX_ADVANCE_FRAMES} \
                     one step may run",
                    index + 1
                ),
            ));
        }
    }
    Ok(())
}

/// Every light's shadow settings, where given, are usable.
fn check_light_shadows(script: &Script, source: &ScriptText<'_>) -> Result<(), ScriptError> {
    let lights_with_shadows = script
        .lights
        .iter()
        .enumerate()
        .filter_map(|(index, light)| light.shadows().map(|shadows| (index, shadows)));
    for (nth, (index, shadows)) in lights_with_shadows.enumerate() {
        if let Some((field, problem)) = shadows.problem() {
            return Err(source.invalid(
                locate_light_shadows(source.text, nth, field),
                format!("light {index} shadows: {problem}"),
            ));
        }
    }
    Ok(())
}

/// Every entity has a name of its own, exactly one of a shape and a glTF file, and files that
/// exist. Returns the names, in order.
fn check_entities(
    script: &Script,
    source: &ScriptText<'_>,
    dir: &Path,
) -> Result<Vec<String>, ScriptError> {
    let mut names = Vec::new();
    for entity in &script.entities {
        if names.contains(&entity.name) {
            return Err(source.missing(
                &entity.name,
                "entities",
                format!("entity {:?} is named twice", entity.name),
            ));
        }
        names.push(entity.name.clone());
        check_shape_or_gltf(entity, source, dir)?;
        if let Some(MaterialDesc::Pom { maps, preset, .. }) = &entity.material {
            check_pom_files(maps, preset.as_deref(), source, dir)?;
        }
    }
    Ok(names)
}

/// An entity is a shape (with any material) or a glTF file that exists (with none).
fn check_shape_or_gltf(
    entity: &EntityDesc,
    source: &ScriptText<'_>,
    dir: &Path,
) -> Result<(), ScriptError> {
    let name = &entity.name;
    match (&entity.shape, &entity.gltf, &entity.material) {
        (Some(_), None, _) => Ok(()),
        (None, Some(file), None) => match file_problem(dir, Path::new(file), source.access) {
            None => Ok(()),
            Some(problem) => {
                Err(source.missing(file, "entities", format!("glTF file {file:?} {problem}")))
            }
        },
        (None, Some(_), Some(_)) => Err(source.missing(
            name,
            "entities",
            format!("entity {name:?}: a glTF file brings its own materials"),
        )),
        _ => Err(source.missing(
            name,
            "entities",
            format!("entity {name:?} needs exactly one of shape and gltf"),
        )),
    }
}

/// A parallax material's three maps in folder `maps`, and its preset file, exist.
fn check_pom_files(
    maps: &str,
    preset: Option<&str>,
    source: &ScriptText<'_>,
    dir: &Path,
) -> Result<(), ScriptError> {
    for file in ["albedo.png", "normal.png", "height.png"] {
        if let Some(problem) = file_problem(dir, &Path::new(maps).join(file), source.access) {
            return Err(source.missing(maps, "entities", format!("{maps}/{file} {problem}")));
        }
    }
    if let Some(preset) = preset
        && let Some(problem) = file_problem(dir, Path::new(preset), source.access)
    {
        return Err(source.missing(
            preset,
            "entities",
            format!("preset file {preset:?} {problem}"),
        ));
    }
    Ok(())
}

/// Why file `name` (relative to the script's folder `dir`) cannot be read: it leads outside the
/// folder `access` allows, does not exist, or is not a regular file; `None` when it can.
fn file_problem(dir: &Path, name: &Path, access: FileAccess) -> Option<String> {
    let path = match resolve_inside(dir, name, access) {
        Ok(path) => path,
        Err(error) => return Some(format!("is refused: {error}")),
    };
    match check_regular(&path, u64::MAX) {
        Ok(_) => None,
        Err(FileError::Io { .. }) => Some("does not exist".into()),
        Err(error) => Some(format!("cannot be read: {error}")),
    }
}

/// Every step refers to entities, lights and earlier captures that exist.
fn check_steps(
    script: &Script,
    names: &[String],
    source: &ScriptText<'_>,
) -> Result<(), ScriptError> {
    let mut captures: Vec<&str> = Vec::new();
    for step in &script.steps {
        check_step(step, script, names, &captures, source)?;
        if let Step::Capture { name, .. } = step {
            captures.push(name);
        }
    }
    Ok(())
}

/// One step's references, `captures` being those taken by the steps before it.
fn check_step(
    step: &Step,
    script: &Script,
    names: &[String],
    captures: &[&str],
    source: &ScriptText<'_>,
) -> Result<(), ScriptError> {
    let taken = |capture: &String| captures.contains(&capture.as_str());
    match step {
        Step::Set { entity, .. } | Step::Spin { entity, .. } if !names.contains(entity) => {
            return Err(source.missing(entity, "steps", format!("no entity is named {entity:?}")));
        }
        Step::MoveLight { light, .. } if *light >= script.lights.len() => {
            return Err(source.reference(
                locate(source.text, "MoveLight", "steps"),
                format!(
                    "light {light} does not exist (the script has {})",
                    script.lights.len()
                ),
            ));
        }
        Step::ExpectMatch { capture, .. } | Step::ExpectStat { capture, .. } if !taken(capture) => {
            return Err(source.no_capture(capture));
        }
        Step::ExpectMonotonic { captures: list, .. } => {
            if let Some(capture) = list.iter().find(|capture| !taken(capture)) {
                return Err(source.no_capture(capture));
            }
        }
        _ => {}
    }
    match uv_shift_baseline(step) {
        Some(baseline) if !taken(baseline) => Err(source.no_capture(baseline)),
        _ => Ok(()),
    }
}

/// The baseline capture a `UvShift` statistic of an expectation measures from.
fn uv_shift_baseline(step: &Step) -> Option<&String> {
    match step {
        Step::ExpectStat {
            stat: Statistic::UvShift { baseline },
            ..
        }
        | Step::ExpectMonotonic {
            stat: Statistic::UvShift { baseline },
            ..
        } => Some(baseline),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::{locate, locate_light_shadows};

    #[test]
    fn light_shadows_are_located_at_their_field_in_the_order_written() {
        let text = "// lights with shadows\n(\n  lights: [\n    Point(position: (0, 1, 0), shadows: (softness: 2.0)),\n    Spot(position: (0, 1, 0), direction: (0, -1, 0),\n         shadows: (enabled: true,\n                   map_size: 9000)),\n  ],\n)";
        assert_eq!(locate_light_shadows(text, 1, "map_size"), (7, 20));
        // A field the setting does not write: the setting itself.
        assert_eq!(locate_light_shadows(text, 0, "map_size"), (4, 32));
    }

    #[test]
    fn locate_reports_one_based_line_and_column() {
        let text = "(\n  steps: [\n    Set(entity: \"ghost\"),\n  ],\n)";
        assert_eq!(locate(text, "\"ghost\"", "steps"), (3, 17));
    }
}
