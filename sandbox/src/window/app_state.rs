//! The sandbox's side of the `pom::App`: loading the scene with names for its entities, the
//! list of parallax materials, the tuned values saved between runs, and spinning an object.

use std::path::Path;

use glam::{Quat, Vec3};
use pom::hecs::{Entity, World};
use pom::preview::{default_lighting, three_quarter_view};
use pom::{App, GltfScene, Name, ParallaxOcclusionMaterial, Transform};

use super::autosave::TunedState;
use crate::cli_types::CameraArg;
use crate::demo_scene::STREET_CORNER;

/// Name of the embedded scene in the state file and the UI.
pub const EMBEDDED_SCENE: &str = "street_corner.glb (embedded)";
/// Radians per second of "spin selected object".
const SPIN_SPEED: f32 = 0.8;
/// Aspect the auto camera frames for; the real viewport's aspect is applied when drawing.
const FRAMING_ASPECT: f32 = 16.0 / 9.0;

/// What was loaded at start.
#[derive(Debug)]
pub struct LoadedScene {
    /// The scene's name (keys its tuned values in the state file).
    pub label: String,
    /// Why the requested scene could not be opened (the embedded one was opened instead), and
    /// the loader's warnings.
    pub messages: Vec<String>,
    /// Distance from the camera to the scene's centre, where orbiting pivots.
    pub focus_distance: f32,
}

/// Loads `path` (or the embedded street corner, also when `path` fails) into `app`, names its
/// entities (the loader's `pom::Name` components) and adds a camera and a light when it has none.
pub fn load_scene(app: &mut App, path: Option<&Path>, camera: Option<CameraArg>) -> LoadedScene {
    let mut messages = Vec::new();
    if let Some(path) = path {
        match pom::load_gltf(app, path) {
            Ok(scene) => {
                let label = path.display().to_string();
                return finish_loading(app, &scene, label, messages, camera);
            }
            Err(error) => {
                messages.push(format!(
                    "could not open the scene: {error}; showing the street corner"
                ));
                // A load that failed half-way may have spawned some nodes: start clean.
                app.world.clear();
            }
        }
    }
    match pom::load_gltf_bytes(app, STREET_CORNER, EMBEDDED_SCENE) {
        Ok(scene) => finish_loading(app, &scene, EMBEDDED_SCENE.into(), messages, camera),
        Err(error) => {
            messages.push(format!("could not load the embedded scene: {error}"));
            let label = EMBEDDED_SCENE.into();
            finish_loading(app, &GltfScene::default(), label, messages, camera)
        }
    }
}

/// Adds a camera and a light when `scene` has none, names its entities and finds where to
/// orbit: the end of every load.
pub fn finish_loading(
    app: &mut App,
    scene: &GltfScene,
    label: String,
    mut messages: Vec<String>,
    camera: Option<CameraArg>,
) -> LoadedScene {
    messages.extend(
        scene
            .warnings
            .iter()
            .map(|warning| format!("{label}: {warning}")),
    );
    let bounds = scene
        .framing_bounds
        .unwrap_or((Vec3::splat(-0.5), Vec3::splat(0.5)));
    // The file's first camera (the loader's rule), unless --camera says otherwise.
    let framed = match camera {
        Some(CameraArg::Auto) => {
            scene.activate_camera(&mut app.world, None);
            true
        }
        Some(CameraArg::Index(index)) => {
            if !scene.activate_camera(&mut app.world, Some(index)) {
                messages.push(format!(
                    "--camera {index}, but {label} has {} camera(s): opened on the first",
                    scene.cameras.len()
                ));
            }
            scene.cameras.is_empty()
        }
        None => scene.cameras.is_empty(),
    };
    if framed {
        app.world.spawn(three_quarter_view(bounds, FRAMING_ASPECT));
    }
    if scene.lights.is_empty() {
        let (sun, transform, ambient) = default_lighting();
        app.world.spawn((sun, transform));
        app.resources.insert(ambient);
    }
    // Scene shadows on, as in `render` and `snapshot`, wherever the light has no setting yet;
    // the light panel switches them per light.
    for light in crate::cli_types::light_entities(&app.world) {
        if !app.world.satisfies::<&pom::LightShadows>(light) {
            let _ = app.world.insert_one(light, pom::LightShadows::default());
        }
    }
    let centre = (bounds.0 + bounds.1) * 0.5;
    let focus_distance =
        super::camera_control::active_camera_transform(&app.world).map_or(5.0, |camera| {
            (centre - camera.translation)
                .dot(camera.rotation * Vec3::NEG_Z)
                .max(0.5)
        });
    LoadedScene {
        label,
        messages,
        focus_distance,
    }
}

/// Every entity with a parallax material and its display name, in a stable order.
pub fn material_entities(app: &App) -> Vec<(Entity, String)> {
    let mut entities: Vec<Entity> = app
        .world
        .query::<(Entity, &ParallaxOcclusionMaterial)>()
        .iter()
        .map(|(entity, _)| entity)
        .collect();
    entities.sort();
    entities
        .into_iter()
        .map(|entity| {
            let name = app
                .world
                .get::<&Name>(entity)
                .map_or_else(|_| format!("entity {}", entity.id()), |name| name.0.clone());
            (entity, name)
        })
        .collect()
}

/// The current parameters of every material of `app` and the shadows of its named lights,
/// stored under `scene` in `state`, and the camera's display controls.
pub fn record_tuned(app: &App, scene: &str, state: &mut TunedState) {
    if let Some(display) = super::display_control::active_display(&app.world) {
        state.display = Some(display);
    }
    let light_shadows = super::light_control::named_light_shadows(&app.world);
    if !light_shadows.is_empty() {
        state.light_shadows.insert(scene.to_owned(), light_shadows);
    }
    let materials = state.scenes.entry(scene.to_owned()).or_default();
    for (entity, name) in material_entities(app) {
        if let Ok(material) = app.world.get::<&ParallaxOcclusionMaterial>(entity) {
            materials.insert(name, material.preset());
        }
    }
}

/// Applies the values `state` holds for `scene` to the materials and lights of the same
/// names, and the saved display controls to the camera.
pub fn restore_tuned(app: &mut App, scene: &str, state: &TunedState) {
    if let Some(display) = state.display {
        super::display_control::apply_display(&mut app.world, display);
    }
    if let Some(light_shadows) = state.light_shadows.get(scene) {
        super::light_control::restore_light_shadows(&mut app.world, light_shadows);
    }
    let Some(saved) = state.scenes.get(scene) else {
        return;
    };
    for (entity, name) in material_entities(app) {
        if let (Some(preset), Ok(mut material)) = (
            saved.get(&name),
            app.world.get::<&mut ParallaxOcclusionMaterial>(entity),
        ) {
            material.apply_preset(preset);
        }
    }
}

/// Turns `entity` about the vertical by `dt` seconds' worth of spin.
pub fn spin(world: &mut World, entity: Entity, dt: f32) {
    if let Ok(mut transform) = world.get::<&mut Transform>(entity) {
        transform.rotation = Quat::from_rotation_y(SPIN_SPEED * dt) * transform.rotation;
    }
}

#[cfg(test)]
mod tests {
    use pom::{DirectionalLight, LightShadows, PointLight};

    use super::*;

    #[test]
    fn named_lights_keep_their_shadows_through_the_state_file() {
        let mut app = App::new();
        let tuned = LightShadows {
            map_size: 1024,
            softness: 3.0,
            ..LightShadows::off()
        };
        app.world
            .spawn((DirectionalLight::default(), Name::new("sun"), tuned));
        // Unnamed: nothing to find it by at the next start.
        app.world
            .spawn((PointLight::default(), LightShadows::off()));
        let mut state = TunedState::default();
        record_tuned(&app, "scene", &mut state);
        assert_eq!(state.light_shadows["scene"].len(), 1);
        let text = ron::to_string(&state).unwrap();
        let reloaded: TunedState = ron::from_str(&text).unwrap();
        assert_eq!(reloaded, state);
        let mut next_start = App::new();
        let sun = next_start
            .world
            .spawn((DirectionalLight::default(), Name::new("sun")));
        restore_tuned(&mut next_start, "scene", &reloaded);
        assert_eq!(*next_start.world.get::<&LightShadows>(sun).unwrap(), tuned);
        // A state file written before shadows were kept still loads.
        let older: TunedState = ron::from_str("(scenes: {}, display: None)").unwrap();
        assert!(older.light_shadows.is_empty());
    }

    #[test]
    fn the_street_corner_lists_its_materials_by_node_name() {
        let mut app = App::new();
        let loaded = load_scene(&mut app, None, None);
        assert_eq!(loaded.label, EMBEDDED_SCENE);
        assert!(loaded.messages.is_empty(), "{:?}", loaded.messages);
        let names: Vec<String> = material_entities(&app)
            .into_iter()
            .map(|(_, name)| name)
            .collect();
        assert_eq!(names, ["floor", "wall", "sign", "doormat", "crate"]);
    }
}
