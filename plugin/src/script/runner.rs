//! Checking a script against itself and the file system, building its scene, running its steps.

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use glam::{EulerRot, Quat, Vec3};
use hecs::Entity;
use image::RgbaImage;

use super::check::check;
use super::format::{CameraDesc, MaterialDesc, Script, ShapeDesc, Statistic, Step};
use super::lights::{light_towards, spawn_light};
use super::stats::{measure, required_view};
use super::{CapturePath, Outcome, Report, RunOptions, ScriptError, StepReport};
use crate::{
    AmbientLight, App, Assets, Camera, Color, DebugView, DirectionalLight, Exposure, GpuContext,
    HeightSource, Image, LitMaterial, Mesh, ParallaxOcclusionMaterial, PointLight, PomPlugin,
    PomPreset, Projection, RenderPlugin, TextureKind, Transform, flip_compare, load_gltf,
    render::Renderer,
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
    let text = std::fs::read_to_string(path).map_err(|error| ScriptError::Io {
        path: path.to_owned(),
        reason: error.to_string(),
    })?;
    let script = parse_script(&text, path)?;
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
    check(&script, text, path, dir)?;
    Ok(script)
}

struct Capture {
    image: RgbaImage,
    view: Option<DebugView>,
    path: CapturePath,
}

struct Runner<'a> {
    app: App,
    path: &'a Path,
    dir: &'a Path,
    options: &'a RunOptions,
    entities: HashMap<String, Vec<Entity>>,
    lights: Vec<Entity>,
    camera: Entity,
    target: Vec3,
    spins: HashMap<String, f32>,
    captures: HashMap<String, Capture>,
}

fn vec3(v: [f32; 3]) -> Vec3 {
    Vec3::from(v)
}

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

fn look(position: Vec3, target: Vec3) -> Transform {
    let up = if (target - position).normalize_or_zero().y.abs() > 0.99 {
        Vec3::Z
    } else {
        Vec3::Y
    };
    Transform::from_translation(position).looking_at(target, up)
}

impl<'a> Runner<'a> {
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
            RenderPlugin::headless(width.clamp(1, 8192), height.clamp(1, 8192))
                .with_path(options.path),
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

    fn spawn(&mut self, desc: &super::format::EntityDesc) -> Result<Vec<Entity>, String> {
        let rotation = Quat::from_euler(
            EulerRot::XYZ,
            desc.transform.rotation_degrees[0].to_radians(),
            desc.transform.rotation_degrees[1].to_radians(),
            desc.transform.rotation_degrees[2].to_radians(),
        );
        let transform = Transform {
            translation: vec3(desc.transform.translation),
            rotation,
            scale: vec3(desc.transform.scale.unwrap_or([1.0; 3])),
        };
        if let Some(file) = &desc.gltf {
            let scene =
                load_gltf(&mut self.app, self.dir.join(file)).map_err(|error| error.to_string())?;
            // Place the whole file by moving its root nodes.
            for entity in &scene.entities {
                if self.app.world.get::<&crate::Parent>(*entity).is_err()
                    && let Ok(mut root) = self.app.world.get::<&mut Transform>(*entity)
                {
                    *root = Transform::from_affine(transform.to_affine() * root.to_affine());
                }
            }
            // A script's own camera and lights replace the file's.
            for camera in &scene.cameras {
                let _ = self.app.world.remove_one::<Camera>(*camera);
            }
            if !self.lights.is_empty() {
                for light in &scene.lights {
                    let _ = self.app.world.remove_one::<DirectionalLight>(*light);
                    let _ = self.app.world.remove_one::<PointLight>(*light);
                }
            }
            return Ok(scene.entities);
        }
        let mesh = match desc.shape.as_ref().ok_or("no shape")? {
            ShapeDesc::Plane { size, tiling } => Mesh::plane_tiled(*size, *tiling),
            ShapeDesc::Cube { size } => Mesh::cube(*size),
            ShapeDesc::Sphere { radius } => Mesh::uv_sphere(*radius, 32, 16),
        };
        let mesh = self
            .app
            .resources
            .get_mut::<Assets<Mesh>>()
            .ok_or("no mesh store")?
            .add(mesh);
        let entity = self.app.world.spawn((mesh, transform));
        match &desc.material {
            None => {}
            Some(MaterialDesc::Lit { color }) => {
                let _ = self.app.world.insert_one(
                    entity,
                    LitMaterial::from_color(Color::linear_rgb(color[0], color[1], color[2])),
                );
            }
            Some(MaterialDesc::Pom { maps, preset, set }) => {
                let folder = self.dir.join(maps);
                let load = |file: &str, kind| {
                    Image::load(folder.join(file), kind).map_err(|error| error.to_string())
                };
                let (albedo, normal, height) = (
                    load("albedo.png", TextureKind::Color)?,
                    load("normal.png", TextureKind::Normal)?,
                    load("height.png", TextureKind::Height)?,
                );
                let images = self
                    .app
                    .resources
                    .get_mut::<Assets<Image>>()
                    .ok_or("no image store")?;
                let mut material = ParallaxOcclusionMaterial {
                    base_color_texture: Some(images.add(albedo)),
                    normal_map: Some(images.add(normal)),
                    height_map: Some(HeightSource::Texture(images.add(height))),
                    ..ParallaxOcclusionMaterial::default()
                };
                if let Some(preset) = preset {
                    let preset = PomPreset::load(self.dir.join(preset))
                        .map_err(|error| error.to_string())?;
                    material.apply_preset(&preset);
                }
                set.apply(&mut material);
                let _ = self.app.world.insert_one(entity, material);
            }
        }
        Ok(vec![entity])
    }

    fn step_error(&self, number: usize, reason: String, report: &Report) -> ScriptError {
        ScriptError::Step {
            path: self.path.to_owned(),
            step: number,
            reason,
            report: report.clone(),
        }
    }

    /// One update, with spins applied first; fails on any GPU error the frame raised.
    fn frame(&mut self) -> Result<(), String> {
        for (name, degrees) in &self.spins {
            for entity in self.entities.get(name).into_iter().flatten() {
                if let Ok(mut transform) = self.app.world.get::<&mut Transform>(*entity) {
                    transform.rotation =
                        Quat::from_rotation_y(degrees.to_radians()) * transform.rotation;
                }
            }
        }
        self.app.update().map_err(|error| error.to_string())?;
        let errors = self
            .app
            .resources
            .get::<GpuContext>()
            .map(GpuContext::take_uncaptured_errors)
            .unwrap_or_default();
        match errors.first() {
            Some(error) => Err(format!("GPU error: {error}")),
            None => Ok(()),
        }
    }

    fn materials_of(&mut self, name: &str) -> Vec<Entity> {
        self.entities
            .get(name)
            .into_iter()
            .flatten()
            .copied()
            .filter(|entity| {
                self.app
                    .world
                    .satisfies::<&ParallaxOcclusionMaterial>(*entity)
            })
            .collect()
    }

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

    fn execute(&mut self, step: &Step) -> Result<(String, Outcome), String> {
        match step {
            Step::Advance { frames } => {
                for _ in 0..*frames {
                    self.frame()?;
                }
                Ok((format!("Advance {frames}"), Outcome::Done))
            }
            Step::Set { entity, material } => {
                let targets = self.materials_of(entity);
                if targets.is_empty() {
                    return Err(format!("entity {entity:?} has no parallax material"));
                }
                for target in targets {
                    if let Ok(mut component) =
                        self.app.world.get::<&mut ParallaxOcclusionMaterial>(target)
                    {
                        material.apply(&mut component);
                    }
                }
                Ok((format!("Set {entity:?}"), Outcome::Done))
            }
            Step::Camera { position, target } => {
                self.target = vec3(*target);
                if let Ok(mut transform) = self.app.world.get::<&mut Transform>(self.camera) {
                    *transform = look(vec3(*position), self.target);
                }
                Ok(("Camera".into(), Outcome::Done))
            }
            Step::OrbitCamera { degrees } => {
                let target = self.target;
                if let Ok(mut transform) = self.app.world.get::<&mut Transform>(self.camera) {
                    let offset = Quat::from_rotation_y(degrees.to_radians())
                        * (transform.translation - target);
                    *transform = look(target + offset, target);
                }
                Ok((format!("OrbitCamera {degrees}°"), Outcome::Done))
            }
            Step::MoveLight {
                light,
                direction,
                position,
            } => {
                let entity = self.lights[*light];
                if let Ok(mut transform) = self.app.world.get::<&mut Transform>(entity) {
                    if let Some(direction) = direction {
                        // Turned in place: a spot keeps its position.
                        let translation = transform.translation;
                        *transform = light_towards(vec3(*direction));
                        transform.translation = translation;
                    }
                    if let Some(position) = position {
                        transform.translation = vec3(*position);
                    }
                }
                Ok((format!("MoveLight {light}"), Outcome::Done))
            }
            Step::Spin {
                entity,
                degrees_per_frame,
            } => {
                self.spins.insert(entity.clone(), *degrees_per_frame);
                Ok((
                    format!("Spin {entity:?} {degrees_per_frame}°/frame"),
                    Outcome::Done,
                ))
            }
            Step::Capture { name, debug_view } => {
                let image = self.capture(*debug_view)?;
                let path = self.last_frame_path()?;
                self.captures.insert(
                    name.clone(),
                    Capture {
                        image,
                        view: *debug_view,
                        path,
                    },
                );
                Ok((format!("Capture {name:?}"), Outcome::Done))
            }
            Step::ExpectMatch {
                capture,
                reference,
                tolerance,
            } => {
                let outcome = self.expect_match(capture, reference, tolerance)?;
                Ok((format!("ExpectMatch {capture:?}"), outcome))
            }
            Step::ExpectStat {
                capture,
                stat,
                rect,
                min,
                max,
            } => {
                let value = self.statistic(capture, stat, *rect)?;
                let low = min.unwrap_or(f32::NEG_INFINITY);
                let high = max.unwrap_or(f32::INFINITY);
                let detail = format!("{} = {value:.4}, bounds {low}..={high}", stat_name(stat));
                let outcome = if (low..=high).contains(&value) {
                    Outcome::Passed(detail)
                } else {
                    Outcome::Failed(detail)
                };
                Ok((format!("ExpectStat {capture:?}"), outcome))
            }
            Step::ExpectMonotonic {
                captures,
                stat,
                increasing,
            } => {
                let values = captures
                    .iter()
                    .map(|capture| self.statistic(capture, stat, None))
                    .collect::<Result<Vec<f32>, String>>()?;
                let ordered = values.windows(2).all(|pair| {
                    if *increasing {
                        pair[1] > pair[0]
                    } else {
                        pair[1] < pair[0]
                    }
                });
                let list: Vec<String> = values.iter().map(|v| format!("{v:.4}")).collect();
                let detail = format!(
                    "{} = [{}], {}",
                    stat_name(stat),
                    list.join(", "),
                    if *increasing {
                        "must grow"
                    } else {
                        "must shrink"
                    }
                );
                let outcome = if ordered {
                    Outcome::Passed(detail)
                } else {
                    Outcome::Failed(detail)
                };
                Ok(("ExpectMonotonic".into(), outcome))
            }
        }
    }

    fn capture(&mut self, view: Option<DebugView>) -> Result<RgbaImage, String> {
        let mut saved = Vec::new();
        if let Some(view) = view {
            for (entity, material) in self
                .app
                .world
                .query_mut::<(Entity, &mut ParallaxOcclusionMaterial)>()
            {
                saved.push((entity, material.debug_view));
                material.debug_view = view;
            }
        }
        let result = self
            .frame()
            .and_then(|()| crate::capture(&self.app).map_err(|error| error.to_string()));
        for (entity, view) in saved {
            if let Ok(mut material) = self.app.world.get::<&mut ParallaxOcclusionMaterial>(entity) {
                material.debug_view = view;
            }
        }
        result
    }

    /// The path the renderer ran the last frame on (a deferred request can fall back to
    /// forward, which the images alone would not show).
    fn last_frame_path(&self) -> Result<CapturePath, String> {
        let renderer = self
            .app
            .resources
            .get::<Renderer>()
            .ok_or("the app has no renderer")?;
        Ok(
            match (renderer.runs_deferred(), renderer.deferred_unavailable()) {
                (true, _) => CapturePath::Deferred,
                (false, Some(reason)) => CapturePath::FellBackToForward(reason),
                (false, None) => CapturePath::Forward,
            },
        )
    }

    fn statistic(
        &self,
        capture: &str,
        stat: &Statistic,
        rect: Option<super::format::Rect>,
    ) -> Result<f32, String> {
        let taken = &self.captures[capture];
        if let Some(view) = required_view(stat)
            && taken.view != Some(view)
        {
            return Err(format!(
                "{} needs capture {capture:?} taken with debug_view: {view:?}",
                stat_name(stat)
            ));
        }
        let baseline = match stat {
            Statistic::UvShift { baseline } => Some(&self.captures[baseline].image),
            _ => None,
        };
        Ok(measure(stat, &taken.image, rect, baseline))
    }

    fn expect_match(
        &self,
        capture: &str,
        reference: &str,
        tolerance: &crate::FlipTolerance,
    ) -> Result<Outcome, String> {
        let actual = &self.captures[capture].image;
        let reference_path = self.dir.join(reference);
        let save = |image: &RgbaImage, path: &Path| -> Result<(), String> {
            if let Some(parent) = path.parent() {
                std::fs::create_dir_all(parent)
                    .map_err(|e| format!("{}: {e}", parent.display()))?;
            }
            image
                .save(path)
                .map_err(|error| format!("{}: {error}", path.display()))
        };
        let stem = Path::new(reference)
            .file_stem()
            .map(|stem| stem.to_string_lossy().into_owned())
            .unwrap_or_else(|| capture.to_owned());
        let out_dir: PathBuf = self
            .options
            .out_dir
            .clone()
            .unwrap_or_else(|| reference_path.parent().unwrap_or(self.dir).to_owned());
        let actual_path = out_dir.join(format!("{stem}-actual.png"));
        let difference_path = out_dir.join(format!("{stem}-difference.png"));
        let expected = match image::open(&reference_path) {
            Ok(expected) => expected.to_rgba8(),
            Err(_) if self.options.bless => {
                save(actual, &reference_path)?;
                return Ok(Outcome::Blessed(format!(
                    "wrote {}",
                    reference_path.display()
                )));
            }
            Err(error) => {
                save(actual, &actual_path)?;
                return Ok(Outcome::Failed(format!(
                    "reference {} is missing ({error}); look at {} and run with --bless",
                    reference_path.display(),
                    actual_path.display()
                )));
            }
        };
        let Some(comparison) = flip_compare(&expected, actual, tolerance.percentile) else {
            if self.options.bless {
                save(actual, &reference_path)?;
                return Ok(Outcome::Blessed(format!(
                    "rewrote {} at the new size",
                    reference_path.display()
                )));
            }
            save(actual, &actual_path)?;
            return Ok(Outcome::Failed(format!(
                "size {:?} differs from the reference's {:?}",
                actual.dimensions(),
                expected.dimensions()
            )));
        };
        let detail = format!(
            "FLIP mean {:.4} (max {}), p{} {:.4} (max {})",
            comparison.mean,
            tolerance.mean,
            tolerance.percentile * 100.0,
            comparison.at_percentile,
            tolerance.percentile_max
        );
        if comparison.within(tolerance) {
            return Ok(Outcome::Passed(detail));
        }
        if self.options.bless {
            save(actual, &reference_path)?;
            return Ok(Outcome::Blessed(format!(
                "{detail}; rewrote {}",
                reference_path.display()
            )));
        }
        save(actual, &actual_path)?;
        save(&comparison.error_map, &difference_path)?;
        Ok(Outcome::Failed(format!(
            "{detail}; see {} and {}",
            actual_path.display(),
            difference_path.display()
        )))
    }
}

fn stat_name(stat: &Statistic) -> String {
    match stat {
        Statistic::MeanLuminance => "mean luminance".into(),
        Statistic::LodBandFraction => "LOD band fraction".into(),
        Statistic::NormalMappingFraction => "normal-mapping fraction".into(),
        Statistic::ShadowedFraction => "shadowed fraction".into(),
        Statistic::UvShift { baseline } => format!("UV shift from {baseline:?}"),
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
