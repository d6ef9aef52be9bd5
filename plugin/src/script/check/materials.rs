//! Checking the parallax parameters a script gives (an entity's preset file and `set`, every
//! `Set` step) before anything renders, with the one validation the command line's flags and
//! preset files go through too: [`ParallaxOcclusionMaterial::validate`].

use std::collections::HashMap;
use std::path::Path;

use super::values::{locate_step, step_kind};
use super::{ScriptText, locate};
use crate::files::resolve_inside;
use crate::material::LimitError;
use crate::parallax::PomMaterialError;
use crate::script::ScriptError;
use crate::script::format::{MaterialDesc, MaterialPatch, Script, Step};
use crate::{ParallaxOcclusionMaterial, PomPreset};

/// What the loader knows of an entity's parallax material.
enum Known {
    /// Built by the script (maps, preset, `set`): every parameter is known.
    Built(Box<ParallaxOcclusionMaterial>),
    /// A glTF file's materials: their values are the file's, known when it is loaded.
    FromFile,
    /// No parallax material: a `Set` step has nothing to change.
    None,
}

/// The field a material problem is about, as the script spells it.
fn problem_field(problem: &PomMaterialError) -> &'static str {
    match problem {
        PomMaterialError::Limit(
            LimitError::NotFinite { field, .. }
            | LimitError::TooSmall { field, .. }
            | LimitError::TooLarge { field, .. },
        ) => field,
        PomMaterialError::SamplesInverted { .. } => "min_samples",
        PomMaterialError::BoundsEmpty { .. } => "bounds_",
        PomMaterialError::Layers(_) => "layers",
        PomMaterialError::TriplanarLayers => "mapping",
    }
}

/// Checks every parallax material the script builds and every `Set` step against it.
pub(super) fn check_materials(
    script: &Script,
    source: &ScriptText<'_>,
    dir: &Path,
) -> Result<(), ScriptError> {
    let mut known = HashMap::new();
    for entity in &script.entities {
        let material = match (&entity.material, &entity.gltf) {
            (Some(MaterialDesc::Pom { preset, set, .. }), _) => {
                let entity_at = |field: &str, reason: String| {
                    source.invalid(
                        locate(source.text, field, &format!("\"{}\"", entity.name)),
                        format!("entity {:?}: {reason}", entity.name),
                    )
                };
                let material = built_material(preset.as_deref(), set, source, dir)
                    .map_err(|reason| entity_at("preset", reason))?;
                material
                    .validate()
                    .map_err(|problem| entity_at(problem_field(&problem), problem.to_string()))?;
                Known::Built(Box::new(material))
            }
            (None, Some(_)) => Known::FromFile,
            _ => Known::None,
        };
        known.insert(entity.name.as_str(), material);
    }
    for (index, step) in script.steps.iter().enumerate() {
        if let Step::Set { entity, material } = step
            && let Some(material_known) = known.get_mut(entity.as_str())
        {
            check_set(entity, material, material_known).map_err(|(field, reason)| {
                source.invalid(
                    locate_step(source.text, &script.steps, index, field),
                    format!("step {} ({}): {reason}", index + 1, step_kind(step)),
                )
            })?;
        }
    }
    Ok(())
}

/// The parameters of a script-built parallax material: the defaults, then the preset file (if
/// any, checked as it loads), then `set`.
fn built_material(
    preset: Option<&str>,
    set: &MaterialPatch,
    source: &ScriptText<'_>,
    dir: &Path,
) -> Result<ParallaxOcclusionMaterial, String> {
    let mut material = ParallaxOcclusionMaterial::default();
    if let Some(preset) = preset {
        let path = resolve_inside(dir, Path::new(preset), source.access)
            .map_err(|error| error.to_string())?;
        let preset = PomPreset::load(path).map_err(|error| format!("preset {error}"))?;
        material.apply_preset(&preset);
    }
    set.apply(&mut material);
    Ok(material)
}

/// A `Set` step on entity `name`: the material it leaves must be valid. A glTF file's values
/// are not known yet: each parameter set is checked against its own limits here, and the whole
/// material when the step runs.
fn check_set(
    name: &str,
    patch: &MaterialPatch,
    known: &mut Known,
) -> Result<(), (&'static str, String)> {
    let as_problem = |problem: PomMaterialError| {
        (
            problem_field(&problem),
            format!("entity {name:?}: {problem}"),
        )
    };
    match known {
        Known::Built(material) => {
            patch.apply(material);
            material.validate().map_err(as_problem)
        }
        Known::FromFile => {
            let mut alone = ParallaxOcclusionMaterial::default();
            patch.apply(&mut alone);
            match alone
                .problems()
                .into_iter()
                .find(|problem| matches!(problem, PomMaterialError::Limit(_)))
            {
                Some(problem) => Err(as_problem(problem)),
                None => Ok(()),
            }
        }
        Known::None => Err((
            "entity",
            format!("entity {name:?} has no parallax material to set"),
        )),
    }
}
