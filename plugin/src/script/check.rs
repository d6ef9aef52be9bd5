//! Checking a script's names and files before anything runs, with line and column.

use std::path::Path;

use super::ScriptError;
use super::format::{MaterialDesc, Script, Statistic, Step};

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

/// Checks every name and file the script refers to before anything runs.
pub(super) fn check(
    script: &Script,
    text: &str,
    path: &Path,
    dir: &Path,
) -> Result<(), ScriptError> {
    let missing = |needle: &str, after: &str, reason: String| {
        let (line, column) = locate(text, &format!("\"{needle}\""), after);
        ScriptError::Reference {
            path: path.to_owned(),
            line,
            column,
            reason,
        }
    };
    if let Some(ev100) = script.camera.exposure
        && !crate::Exposure::RANGE.contains(&ev100)
    {
        let (line, column) = locate(text, "exposure", "camera");
        return Err(ScriptError::Parse {
            path: path.to_owned(),
            line,
            column,
            reason: format!(
                "camera exposure {ev100} EV100 is outside {}..={}",
                crate::Exposure::RANGE.start(),
                crate::Exposure::RANGE.end()
            ),
        });
    }
    let lights_with_shadows = script
        .lights
        .iter()
        .enumerate()
        .filter_map(|(index, light)| light.shadows().map(|shadows| (index, shadows)));
    for (nth, (index, shadows)) in lights_with_shadows.enumerate() {
        if let Some((field, problem)) = shadows.problem() {
            let (line, column) = locate_light_shadows(text, nth, field);
            return Err(ScriptError::Parse {
                path: path.to_owned(),
                line,
                column,
                reason: format!("light {index} shadows: {problem}"),
            });
        }
    }
    let mut names = Vec::new();
    for entity in &script.entities {
        if names.contains(&entity.name) {
            return Err(missing(
                &entity.name,
                "entities",
                format!("entity {:?} is named twice", entity.name),
            ));
        }
        names.push(entity.name.clone());
        match (&entity.shape, &entity.gltf, &entity.material) {
            (Some(_), None, _) => {}
            (None, Some(file), None) => {
                if !dir.join(file).is_file() {
                    return Err(missing(
                        file,
                        "entities",
                        format!("glTF file {file:?} does not exist"),
                    ));
                }
            }
            (None, Some(_), Some(_)) => {
                return Err(missing(
                    &entity.name,
                    "entities",
                    format!(
                        "entity {:?}: a glTF file brings its own materials",
                        entity.name
                    ),
                ));
            }
            _ => {
                return Err(missing(
                    &entity.name,
                    "entities",
                    format!(
                        "entity {:?} needs exactly one of shape and gltf",
                        entity.name
                    ),
                ));
            }
        }
        if let Some(MaterialDesc::Pom { maps, preset, .. }) = &entity.material {
            for file in ["albedo.png", "normal.png", "height.png"] {
                if !dir.join(maps).join(file).is_file() {
                    return Err(missing(
                        maps,
                        "entities",
                        format!("{maps}/{file} does not exist"),
                    ));
                }
            }
            if let Some(preset) = preset
                && !dir.join(preset).is_file()
            {
                return Err(missing(
                    preset,
                    "entities",
                    format!("preset file {preset:?} does not exist"),
                ));
            }
        }
    }
    let mut captures: Vec<&str> = Vec::new();
    for step in &script.steps {
        match step {
            Step::Set { entity, .. } | Step::Spin { entity, .. } if !names.contains(entity) => {
                return Err(missing(
                    entity,
                    "steps",
                    format!("no entity is named {entity:?}"),
                ));
            }
            Step::MoveLight { light, .. } if *light >= script.lights.len() => {
                let (line, column) = locate(text, "MoveLight", "steps");
                return Err(ScriptError::Reference {
                    path: path.to_owned(),
                    line,
                    column,
                    reason: format!(
                        "light {light} does not exist (the script has {})",
                        script.lights.len()
                    ),
                });
            }
            Step::Capture { name, .. } => captures.push(name),
            Step::ExpectMatch { capture, .. } | Step::ExpectStat { capture, .. }
                if !captures.contains(&capture.as_str()) =>
            {
                return Err(missing(
                    capture,
                    "steps",
                    format!("no capture named {capture:?} is taken before this step"),
                ));
            }
            Step::ExpectMonotonic { captures: list, .. } => {
                if let Some(capture) = list.iter().find(|c| !captures.contains(&c.as_str())) {
                    return Err(missing(
                        capture,
                        "steps",
                        format!("no capture named {capture:?} is taken before this step"),
                    ));
                }
            }
            _ => {}
        }
        let baseline = match step {
            Step::ExpectStat {
                stat: Statistic::UvShift { baseline },
                ..
            }
            | Step::ExpectMonotonic {
                stat: Statistic::UvShift { baseline },
                ..
            } => Some(baseline),
            _ => None,
        };
        if let Some(baseline) = baseline
            && !captures.contains(&baseline.as_str())
        {
            return Err(missing(
                baseline,
                "steps",
                format!("no capture named {baseline:?} is taken before this step"),
            ));
        }
    }
    Ok(())
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
