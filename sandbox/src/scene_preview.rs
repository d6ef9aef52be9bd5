//! `sandbox render --scene`: a glTF file loaded by the plugin (`pom::load_gltf`), seen through
//! one camera, lit, and with the debug view on every parallax material. What the command has to
//! say about the file goes to stderr as one `warning:` line each; a file it cannot load, or a
//! camera it does not have, is an error.

use std::path::Path;

use anyhow::{Result, anyhow, bail};
use glam::Vec3;
use pom::hecs::World;
use pom::preview::{FramingView, default_lighting, framing_camera};
use pom::{App, DebugView, GltfScene, ParallaxOcclusionMaterial};

use crate::cli_types::CameraArg;

/// What the auto camera frames when the scene has no meshes: a unit box at the origin.
const EMPTY_SCENE_BOUNDS: (Vec3, Vec3) = (Vec3::splat(-0.5), Vec3::splat(0.5));

/// A scene file and how to look at it.
#[derive(Clone, Copy, Debug)]
pub struct ScenePreview<'a> {
    /// The `.gltf` or `.glb` file.
    pub path: &'a Path,
    /// `--camera`; `None` lets the file decide (its first camera, or auto when it has none).
    pub camera: Option<CameraArg>,
    /// `--view-angle`, `--view-azimuth`, `--distance` for the automatic camera, if any was given.
    pub framing: Option<FramingView>,
    /// Width / height of the image.
    pub aspect: f32,
    /// Set on every parallax material.
    pub debug_view: DebugView,
}

/// The camera the picture is taken with.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Viewpoint {
    /// The file's camera with this index.
    File(usize),
    /// A three-quarter view framing the scene's meshes.
    Framing,
}

/// Loads the scene into `app` and sets up its camera, lights and debug view, printing the
/// loader's warnings and the command's own. Needs the render plugin; does not start the GPU.
pub fn spawn(app: &mut App, preview: &ScenePreview<'_>) -> Result<()> {
    let path = preview.path;
    // The loader's errors name the file and the problem.
    let scene = pom::load_gltf(app, path).map_err(|error| anyhow!(one_line(&error.to_string())))?;
    // Checked before any warning is printed, so that a bad index is the only line on stderr.
    let viewpoint = choose_viewpoint(
        preview.camera,
        preview.framing.is_some(),
        scene.cameras.len(),
        path,
    )?;
    for warning in &scene.warnings {
        warn(&format!("{}: {warning}", path.display()));
    }
    match viewpoint {
        Viewpoint::File(index) => {
            scene.activate_camera(&mut app.world, Some(index));
        }
        Viewpoint::Framing => frame_scene(app, &scene, preview),
    }
    if scene.lights.is_empty() {
        add_default_lighting(app);
        warn(&format!(
            "{} has no lights: added a default light (a sun and a soft ambient light)",
            path.display()
        ));
    }
    apply_debug_view(&mut app.world, preview.debug_view);
    Ok(())
}

/// `--camera` against the file's cameras: an index it has, auto, or by default its first
/// camera (auto when it has none, or when the automatic camera's options were given).
fn choose_viewpoint(
    requested: Option<CameraArg>,
    framing_options: bool,
    cameras: usize,
    path: &Path,
) -> Result<Viewpoint> {
    match requested {
        Some(CameraArg::Auto) => Ok(Viewpoint::Framing),
        Some(CameraArg::Index(index)) if framing_options => bail!(
            "--view-angle, --view-azimuth and --distance move the automatic camera, not --camera {index}"
        ),
        Some(CameraArg::Index(index)) if index < cameras => Ok(Viewpoint::File(index)),
        Some(CameraArg::Index(index)) => bail!(
            "--camera {index}, but {} has {}",
            path.display(),
            count(cameras, "camera", "cameras")
        ),
        None if cameras == 0 || framing_options => Ok(Viewpoint::Framing),
        None => Ok(Viewpoint::File(0)),
    }
}

/// Turns the file's cameras off and spawns a camera framing what the scene is about
/// (`GltfScene::framing_bounds`; a unit box at the origin, with a warning, without meshes).
fn frame_scene(app: &mut App, scene: &GltfScene, preview: &ScenePreview<'_>) {
    scene.activate_camera(&mut app.world, None);
    let bounds = scene.framing_bounds.unwrap_or_else(|| {
        warn(&format!(
            "{} has no meshes: framing a unit box at the origin",
            preview.path.display()
        ));
        EMPTY_SCENE_BOUNDS
    });
    let view = preview.framing.unwrap_or_default();
    app.world
        .spawn(framing_camera(bounds, preview.aspect, view));
}

/// The plugin's default lighting: a sun, and the ambient light resource.
fn add_default_lighting(app: &mut App) {
    let (sun, transform, ambient) = default_lighting();
    app.world.spawn((sun, transform));
    app.resources.insert(ambient);
}

/// Sets `view` on every parallax material in the world.
fn apply_debug_view(world: &mut World, view: DebugView) {
    for material in world.query_mut::<&mut ParallaxOcclusionMaterial>() {
        material.debug_view = view;
    }
}

/// Prints one `warning:` line on stderr.
fn warn(message: &str) {
    eprintln!("warning: {}", one_line(message));
}

/// `text` with its lines joined by spaces, so that every message is one line.
fn one_line(text: &str) -> String {
    text.lines()
        .map(str::trim)
        .filter(|line| !line.is_empty())
        .collect::<Vec<_>>()
        .join(" ")
}

/// "1 camera", "2 cameras", "0 cameras".
fn count(n: usize, one: &str, many: &str) -> String {
    format!("{n} {}", if n == 1 { one } else { many })
}

#[cfg(test)]
mod tests {
    use super::*;
    use pom::hecs::Entity;

    #[test]
    fn the_default_camera_is_the_files_first_or_auto_without_one() {
        let path = Path::new("scene.gltf");
        assert_eq!(
            choose_viewpoint(None, false, 2, path).unwrap(),
            Viewpoint::File(0)
        );
        assert_eq!(
            choose_viewpoint(None, false, 0, path).unwrap(),
            Viewpoint::Framing
        );
        let auto = Some(CameraArg::Auto);
        assert_eq!(
            choose_viewpoint(auto, false, 2, path).unwrap(),
            Viewpoint::Framing
        );
        let second = Some(CameraArg::Index(1));
        assert_eq!(
            choose_viewpoint(second, false, 2, path).unwrap(),
            Viewpoint::File(1)
        );
        // The automatic camera's options imply it, and contradict a file camera.
        assert_eq!(
            choose_viewpoint(None, true, 2, path).unwrap(),
            Viewpoint::Framing
        );
        assert!(choose_viewpoint(second, true, 2, path).is_err());
    }

    #[test]
    fn a_camera_past_the_files_names_the_count() {
        let path = Path::new("scene.gltf");
        let error = choose_viewpoint(Some(CameraArg::Index(3)), false, 2, path).unwrap_err();
        assert_eq!(
            error.to_string(),
            "--camera 3, but scene.gltf has 2 cameras"
        );
        let error = choose_viewpoint(Some(CameraArg::Index(1)), false, 1, path).unwrap_err();
        assert_eq!(error.to_string(), "--camera 1, but scene.gltf has 1 camera");
        let error = choose_viewpoint(Some(CameraArg::Index(0)), false, 0, path).unwrap_err();
        assert_eq!(
            error.to_string(),
            "--camera 0, but scene.gltf has 0 cameras"
        );
    }

    #[test]
    fn the_debug_view_reaches_every_parallax_material() {
        let mut world = World::new();
        let materials: Vec<Entity> = (0..2)
            .map(|_| world.spawn((ParallaxOcclusionMaterial::default(),)))
            .collect();
        apply_debug_view(&mut world, DebugView::Uv);
        for entity in materials {
            let material = world.get::<&ParallaxOcclusionMaterial>(entity).unwrap();
            assert_eq!(material.debug_view, DebugView::Uv);
        }
    }

    #[test]
    fn messages_are_one_line() {
        assert_eq!(one_line("a\n  b\n\nc "), "a b c");
        assert_eq!(count(1, "camera", "cameras"), "1 camera");
        assert_eq!(count(2, "camera", "cameras"), "2 cameras");
    }
}
