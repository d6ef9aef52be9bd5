//! Opening another scene while the window runs: a glTF file, or a height map with optional
//! normal and albedo maps shown on a plane. A file that cannot be opened leaves the current
//! scene as it was and returns the reason.

use std::collections::HashSet;
use std::path::{Path, PathBuf};

use glam::Vec3;
use pom::hecs::Entity;
use pom::{
    App, Assets, GltfScene, HeightSource, Image, Mesh, Name, ParallaxOcclusionMaterial,
    TextureKind, Transform,
};

use super::app_state::{LoadedScene, finish_loading};

/// Side of the plane an image set is shown on, in world units.
const IMAGE_PLANE_SIZE: f32 = 2.0;
/// How often the image set repeats across the plane.
const IMAGE_PLANE_TILING: f32 = 2.0;

/// What to open.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum OpenRequest {
    /// A `.gltf` or `.glb` scene.
    Scene(PathBuf),
    /// A height map, with a normal map and an albedo when given.
    ImageSet(ImageSet),
}

/// The files of a parallax material.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct ImageSet {
    /// The height map (required).
    pub height: Option<PathBuf>,
    /// The tangent-space normal map.
    pub normal: Option<PathBuf>,
    /// The colour texture.
    pub albedo: Option<PathBuf>,
}

/// Whether `path` names a glTF scene.
pub fn is_scene_file(path: &Path) -> bool {
    has_extension(path, &["gltf", "glb"])
}

/// Whether `path` names an image the loaders read.
pub fn is_image_file(path: &Path) -> bool {
    has_extension(path, &["png", "jpg", "jpeg"])
}

fn has_extension(path: &Path, extensions: &[&str]) -> bool {
    path.extension()
        .and_then(|extension| extension.to_str())
        .is_some_and(|extension| extensions.contains(&extension.to_ascii_lowercase().as_str()))
}

/// What a set of dropped files asks for: one glTF scene, or images sorted into height, normal
/// and albedo by their names ("normal", "albedo"/"color"/"base"/"diffuse"; anything else is
/// the height map).
pub fn request_for_dropped(paths: &[PathBuf]) -> Result<OpenRequest, String> {
    if let Some(scene) = paths.iter().find(|path| is_scene_file(path)) {
        return Ok(OpenRequest::Scene(scene.clone()));
    }
    let mut set = ImageSet::default();
    for path in paths {
        if !is_image_file(path) {
            return Err(format!(
                "{}: not a glTF scene (.gltf, .glb) or an image (.png, .jpg)",
                path.display()
            ));
        }
        let name = path
            .file_stem()
            .map(|stem| stem.to_string_lossy().to_ascii_lowercase())
            .unwrap_or_default();
        let slot = if name.contains("normal") {
            &mut set.normal
        } else if ["albedo", "color", "colour", "base", "diffuse"]
            .iter()
            .any(|word| name.contains(word))
        {
            &mut set.albedo
        } else {
            &mut set.height
        };
        if let Some(previous) = slot.replace(path.clone()) {
            return Err(format!(
                "{} and {} both look like the same map: drop one set at a time",
                previous.display(),
                path.display()
            ));
        }
    }
    if set.height.is_none() {
        return Err(
            "no height map among the dropped images (name it anything but \
                    *normal* or *albedo*)"
                .into(),
        );
    }
    Ok(OpenRequest::ImageSet(set))
}

/// Replaces `app`'s scene with what `request` names. On failure the current scene stays and
/// the error says which file and why.
pub fn open_request(app: &mut App, request: &OpenRequest) -> Result<LoadedScene, String> {
    let before: HashSet<Entity> = app.world.iter().map(|entity| entity.entity()).collect();
    let opened = match request {
        OpenRequest::Scene(path) => open_scene(app, path),
        OpenRequest::ImageSet(set) => open_image_set(app, set),
    };
    let spawned: Vec<Entity> = app
        .world
        .iter()
        .map(|entity| entity.entity())
        .filter(|entity| !before.contains(entity))
        .collect();
    // Drop whichever scene is not wanted: the new one's leftovers on failure, else the old.
    let unwanted: Vec<Entity> = match &opened {
        Ok(_) => before.into_iter().collect(),
        Err(_) => spawned,
    };
    for entity in unwanted {
        let _ = app.world.despawn(entity);
    }
    let (scene, label) = opened?;
    Ok(finish_loading(app, &scene, label, Vec::new(), None))
}

/// The loaded scene and its label.
type Opened = (GltfScene, String);

fn open_scene(app: &mut App, path: &Path) -> Result<Opened, String> {
    let scene = pom::load_gltf(app, path).map_err(|error| error.to_string())?;
    Ok((scene, path.display().to_string()))
}

fn open_image_set(app: &mut App, set: &ImageSet) -> Result<Opened, String> {
    let height = set
        .height
        .as_ref()
        .ok_or("an image set needs a height map")?;
    let load = |path: &PathBuf, kind| Image::load(path, kind).map_err(|error| error.to_string());
    let height_image = load(height, TextureKind::Height)?;
    let normal_image = set
        .normal
        .as_ref()
        .map(|path| load(path, TextureKind::Normal))
        .transpose()?;
    let albedo_image = set
        .albedo
        .as_ref()
        .map(|path| load(path, TextureKind::Color))
        .transpose()?;
    let images = app.resources.get_or_default::<Assets<Image>>();
    let material = ParallaxOcclusionMaterial {
        height_map: Some(HeightSource::Texture(images.add(height_image))),
        normal_map: normal_image.map(|image| images.add(image)),
        base_color_texture: albedo_image.map(|image| images.add(image)),
        ..ParallaxOcclusionMaterial::default()
    };
    let plane = app
        .resources
        .get_or_default::<Assets<Mesh>>()
        .add(Mesh::plane_tiled(IMAGE_PLANE_SIZE, IMAGE_PLANE_TILING));
    let name = height.file_stem().map_or_else(
        || "image set".into(),
        |stem| stem.to_string_lossy().into_owned(),
    );
    let entity = app
        .world
        .spawn((plane, material, Transform::IDENTITY, Name::new(name)));
    let half = IMAGE_PLANE_SIZE * 0.5;
    let scene = GltfScene {
        entities: vec![entity],
        bounds: Some((Vec3::new(-half, 0.0, -half), Vec3::new(half, 0.0, half))),
        ..GltfScene::default()
    };
    Ok((scene, format!("image set {}", height.display())))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn paths(names: &[&str]) -> Vec<PathBuf> {
        names.iter().map(PathBuf::from).collect()
    }

    #[test]
    fn dropped_files_are_sorted_into_a_scene_or_an_image_set() {
        assert_eq!(
            request_for_dropped(&paths(&["a.png", "street.GLB"])),
            Ok(OpenRequest::Scene("street.GLB".into()))
        );
        assert_eq!(
            request_for_dropped(&paths(&[
                "bricks_albedo.png",
                "bricks_normal.png",
                "bricks.png"
            ])),
            Ok(OpenRequest::ImageSet(ImageSet {
                height: Some("bricks.png".into()),
                normal: Some("bricks_normal.png".into()),
                albedo: Some("bricks_albedo.png".into()),
            }))
        );
        assert!(request_for_dropped(&paths(&["notes.txt"])).is_err());
        assert!(request_for_dropped(&paths(&["a_normal.png"])).is_err());
        assert!(request_for_dropped(&paths(&["a.png", "b.png"])).is_err());
    }

    #[test]
    fn a_bad_file_keeps_the_current_scene() {
        let mut app = App::new();
        let kept = app.world.spawn((ParallaxOcclusionMaterial::default(),));
        let path = std::env::temp_dir().join(format!("sandbox-bad-{}.glb", std::process::id()));
        std::fs::write(&path, b"glTF but not really").unwrap();
        let error = open_request(&mut app, &OpenRequest::Scene(path.clone())).unwrap_err();
        assert!(error.contains(&path.display().to_string()), "{error}");
        assert!(app.world.contains(kept));
        assert_eq!(app.world.len(), 1);
        std::fs::remove_file(&path).unwrap();
    }
}
