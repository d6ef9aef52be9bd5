//! Checking a script against itself and the file system, building its scene, running its steps.

mod expect;
mod spawn;
mod steps;

use std::collections::HashMap;
use std::path::Path;

use glam::Vec3;
use hecs::Entity;
use image::RgbaImage;

use super::check::check;
use super::format::{CameraDesc, Script, Step};
use super::lights::spawn_light;
use super::stats::SurfaceMask;
use super::{CapturePath, Report, RunOptions, ScriptError, StepReport};
use crate::files::{FileAccess, MAX_TEXT_FILE_BYTES, read_text_bounded};
use crate::{
    AmbientLight, App, Camera, Color, Exposure, PomPlugin, Projection, RenderPlugin, Transform,
};

/// The time between two frames of a scene script ([`crate::Time`] advances by it).
pub const SCRIPT_FRAME_TIME: std::time::Duration = std::time::Duration::from_nanos(16_666_667);

/// Runs the script at `path` with default options (no blessing, failure images next to the
/// references).
pub fn run_script(path: impl AsRef<Path>) -> Result<Report, ScriptError> {
    run_script_with(path, &RunOptions::default())
}

/// Runs the script at `path`. `Ok` holds a report whose expectations may have failed (see
/// [`Report::passed`]); `Err` means the script could not be read, checked or carried out.
pub fn run_script_with(
    path: impl AsRef<Path>,
    options: &RunOptions,
) -> Result<Report, ScriptError> {
    let path = path.as_ref();
    let text = read_text_bounded(path, MAX_TEXT_FILE_BYTES).map_err(|error| ScriptError::Io {
        path: path.to_owned(),
        reason: error.to_string(),
    })?;
    let script = parse_script_with(&text, path, options.file_access)?;
    let dir = path.parent().unwrap_or(Path::new(".")).to_owned();
    Runner::new(&script, path, &dir, options)?.run(&script)
}

/// Parses script `text` and checks every name and file it refers to (files relative to `path`'s
/// folder) without running it; `path` names the script in errors.
///
/// # Example
/// ```
/// let error = pom::script::parse_script("(steps: [])", "scene.ron".as_ref()).unwrap_err();
/// assert!(error.to_string().starts_with("scene.ron:1:"), "{error}");
/// ```
pub fn parse_script(text: &str, path: &Path) -> Result<Script, ScriptError> {
    parse_script_with(text, path, FileAccess::InsideFolder)
}

/// [`parse_script`], letting the script name the files `access` allows.
pub fn parse_script_with(
    text: &str,
    path: &Path,
    access: FileAccess,
) -> Result<Script, ScriptError> {
    // Optional fields may be written as plain values (`min: 0.5`) as well as `Some(0.5)`.
    let parser =
        ron::Options::default().with_default_extension(ron::extensions::Extensions::IMPLICIT_SOME);
    let script: Script = parser.from_str(text).map_err(|error| ScriptError::Parse {
        path: path.to_owned(),
        line: error.span.start.line,
        column: error.span.start.col,
        reason: error.code.to_string(),
    })?;
    let dir = path.parent().unwrap_or(Path::new("."));
    check(&script, text, path, dir, access)?;
    Ok(script)
}

/// A frame a `Capture` step kept, with the debug view it was drawn with, the pixels of its
/// parallax surfaces (debug views only: the statistics that read them count nothing else) and
/// the path it ran on.
struct Capture {
    image: RgbaImage,
    surface: Option<SurfaceMask>,
    path: CapturePath,
}

/// A script's scene while its steps run: the app, what the script named, and the captures.
struct Runner<'a> {
    app: App,
    path: &'a Path,
    dir: &'a Path,
    options: &'a RunOptions,
    /// What each script entity spawned (a glTF file: every entity of its scene).
    entities: HashMap<String, Vec<Entity>>,
    /// The script's lights, in its order.
    lights: Vec<Entity>,
    camera: Entity,
    /// The point the camera looks at, which `OrbitCamera` turns about.
    target: Vec3,
    /// Degrees per frame about Y, by entity name.
    spins: HashMap<String, f32>,
    captures: HashMap<String, Capture>,
}

fn vec3(v: [f32; 3]) -> Vec3 {
    Vec3::from(v)
}

/// The script camera's projection (perspective unless an orthographic height is given).
fn camera_component(desc: &CameraDesc) -> Camera {
    let projection = match (desc.orthographic_height, desc.fov_degrees) {
        (Some(height), _) => Projection::Orthographic {
            height,
            near: 0.0,
            far: 200.0,
        },
        (None, fov) => Projection::Perspective {
            fov_y: fov.unwrap_or(45.0).to_radians(),
            near: 0.05,
            far: 200.0,
        },
    };
    Camera {
        projection,
        clear_color: Color::linear_rgb(0.02, 0.02, 0.025),
        active: true,
    }
}

/// A transform at `position` looking at `target`, with an up axis that is not along the view.
fn look(position: Vec3, target: Vec3) -> Transform {
    let up = if (target - position).normalize_or_zero().y.abs() > 0.99 {
        Vec3::Z
    } else {
        Vec3::Y
    };
    Transform::from_translation(position).looking_at(target, up)
}

/// The script's environment, its file (checked before the run) resolved in the script's folder.
fn environment_light(
    environment: &super::format::EnvironmentDesc,
    dir: &Path,
    access: FileAccess,
) -> Result<crate::EnvironmentLight, String> {
    let choice = match environment.source.parse() {
        Ok(crate::EnvironmentChoice::File(file)) => crate::EnvironmentChoice::File(
            crate::files::resolve_inside(dir, &file, access).map_err(|error| error.to_string())?,
        ),
        Ok(choice) => choice,
        Err(error) => return Err(error.to_string()),
    };
    Ok(crate::EnvironmentLight {
        source: choice.load().map_err(|error| error.to_string())?,
        settings: environment.settings,
    })
}

impl<'a> Runner<'a> {
    /// Builds the script's app and scene: camera, lights, ambient light, then its entities.
    fn new(
        script: &Script,
        path: &'a Path,
        dir: &'a Path,
        options: &'a RunOptions,
    ) -> Result<Self, ScriptError> {
        let setup = |reason: String| ScriptError::Setup {
            path: path.to_owned(),
            reason,
        };
        let (width, height) = script.size;
        let mut app = App::new();
        app.add_plugin(
            RenderPlugin::new(width.clamp(1, 8192), height.clamp(1, 8192)).with_path(options.path),
        )
        .add_plugin(PomPlugin);
        // Scripts run with the fixed frame time their steps count in, so a run repeats exactly.
        app.insert_resource(crate::Time::fixed(SCRIPT_FRAME_TIME));
        app.finish().map_err(|error| setup(error.to_string()))?;
        let camera = app.world.spawn((
            camera_component(&script.camera),
            look(vec3(script.camera.position), vec3(script.camera.target)),
            script
                .camera
                .exposure
                .map_or_else(Exposure::default, |ev100| Exposure { ev100 }),
            script.camera.tonemap.unwrap_or_default(),
            script.camera.aa.unwrap_or_default(),
            script.camera.taa.unwrap_or_default(),
            script.camera.fxaa.unwrap_or_default(),
        ));
        let lights = script
            .lights
            .iter()
            .map(|light| spawn_light(&mut app.world, light))
            .collect();
        if let Some((color, intensity)) = script.ambient {
            app.insert_resource(AmbientLight {
                color: Color::linear_rgb(color[0], color[1], color[2]),
                intensity,
            });
        }
        if let Some(environment) = &script.environment {
            let light = environment_light(environment, dir, options.file_access).map_err(setup)?;
            app.insert_resource(light);
        }
        let mut runner = Self {
            app,
            path,
            dir,
            options,
            entities: HashMap::new(),
            lights,
            camera,
            target: vec3(script.camera.target),
            spins: HashMap::new(),
            captures: HashMap::new(),
        };
        for entity in &script.entities {
            let spawned = runner
                .spawn(entity)
                .map_err(|reason| setup(format!("entity {:?}: {reason}", entity.name)))?;
            runner.entities.insert(entity.name.clone(), spawned);
        }
        Ok(runner)
    }

    /// A step that could not be carried out, with the report of the steps before it.
    fn step_error(&self, number: usize, reason: String, report: &Report) -> ScriptError {
        ScriptError::Step {
            path: self.path.to_owned(),
            step: number,
            reason,
            report: report.clone(),
        }
    }

    /// Runs every step in order, one report line each.
    fn run(mut self, script: &Script) -> Result<Report, ScriptError> {
        let mut report = Report {
            script: self.path.to_owned(),
            steps: Vec::new(),
        };
        for (index, step) in script.steps.iter().enumerate() {
            let number = index + 1;
            let (description, outcome) = self
                .execute(step)
                .map_err(|reason| self.step_error(number, reason, &report))?;
            let path = match step {
                Step::Capture { name, .. } => Some(self.captures[name].path),
                _ => None,
            };
            report.steps.push(StepReport {
                number,
                description,
                outcome,
                path,
            });
        }
        Ok(report)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{LightShadows, SpotLight};

    #[test]
    fn a_lights_shadow_settings_reach_its_component() {
        let script = parse_script(
            "(
                camera: (position: (0.0, 1.0, 1.0), target: (0.0, 0.0, 0.0)),
                lights: [
                    Directional(direction: (0.0, -1.0, 0.0),
                        shadows: Some((enabled: true, map_size: 1024, softness: 2.0, distance: 30.0))),
                    Point(position: (0.0, 1.0, 0.0), shadows: (enabled: false)),
                    Spot(position: (0.0, 1.0, 0.0), direction: (0.0, -1.0, 0.0)),
                ],
                steps: [],
            )",
            Path::new("shadows.ron"),
        )
        .unwrap();
        let mut world = hecs::World::new();
        let lights: Vec<Entity> = script
            .lights
            .iter()
            .map(|light| spawn_light(&mut world, light))
            .collect();
        let shadows_of = |light: Entity| world.get::<&LightShadows>(light).map(|s| *s).ok();
        assert_eq!(
            shadows_of(lights[0]),
            Some(LightShadows {
                enabled: true,
                map_size: 1024,
                softness: 2.0,
                distance: 30.0,
            })
        );
        assert_eq!(shadows_of(lights[1]), Some(LightShadows::off()));
        assert_eq!(shadows_of(lights[2]), None, "absent: the default");
        assert!(world.satisfies::<&SpotLight>(lights[2]));
    }
}
