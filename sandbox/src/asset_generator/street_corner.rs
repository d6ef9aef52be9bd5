//! The street-corner scene: a cobblestone floor, a brick wall with a shop sign, a furry doormat,
//! a studded crate and a low-poly ball resting on the stones, seen by one camera: by day under
//! one sun, and at night lit by street lamps (spot lights), a lamp post and a string of bulbs
//! (point lights) with the camera's exposure for the night.

use glam::{Quat, Vec3};
use serde_json::{Value, json};

use super::EncodedMaterial;
use super::glb::GlbBuilder;

/// File name of the scene by day under assets/.
pub const STREET_CORNER_FILE: &str = "street_corner.glb";
/// File name of the scene at night under assets/.
pub const STREET_CORNER_NIGHT_FILE: &str = "street_corner_night.glb";

/// The light the scene is seen in.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TimeOfDay {
    /// One sun.
    Day,
    /// Street lamps, a lamp post and a string of bulbs; exposed for them.
    Night,
}

/// The night's exposure (EV100): a white surface 190 lux under the lamp post shows at about
/// one half before tonemapping.
const NIGHT_EXPOSURE: f32 = 6.5;
/// Bulbs along the string over the street.
const STRING_BULBS: usize = 24;

/// A `width` × `depth` quad in the XZ plane facing +Y, texture repeated `repeat` times on each
/// axis.
fn quad(width: f32, depth: f32, repeat: (f32, f32)) -> pom::Mesh {
    let mut mesh = pom::Mesh::plane(1.0);
    for position in &mut mesh.positions {
        position[0] *= width;
        position[2] *= depth;
    }
    for uv in &mut mesh.uvs {
        uv[0] *= repeat.0;
        uv[1] *= repeat.1;
    }
    mesh
}

fn node(name: &str, mesh: usize, translation: Vec3, rotation: Quat) -> Value {
    json!({"name": name, "mesh": mesh, "translation": translation.to_array(), "rotation": rotation.to_array()})
}

/// A material using one shipped set, with its POM parameters in `extras`.
fn pom_material(builder: &mut GlbBuilder, maps: &EncodedMaterial, pom: Value) -> usize {
    let albedo = builder.texture(&format!("{} albedo", maps.name), &maps.albedo);
    let normal = builder.texture(&format!("{} normal", maps.name), &maps.normal);
    let height = builder.texture(&format!("{} height", maps.name), &maps.height);
    let mut pom = pom;
    pom["height_texture"] = json!(height);
    pom["height_scale"] = json!(maps.height_scale);
    builder.material(json!({
        "name": maps.name,
        "pbrMetallicRoughness": {"baseColorTexture": {"index": albedo}, "metallicFactor": 0.0, "roughnessFactor": 0.75},
        "normalTexture": {"index": normal},
        "extras": {"pom": pom}
    }))
}

fn find<'a>(materials: &'a [EncodedMaterial], name: &str) -> &'a EncodedMaterial {
    // The generator always makes every set; a missing one is a bug in this file.
    materials
        .iter()
        .find(|m| m.name == name)
        .unwrap_or_else(|| panic!("the shipped set has no {name}"))
}

/// The `.glb` bytes of the scene at `time`, textures embedded.
pub fn build(materials: &[EncodedMaterial], time: TimeOfDay) -> Vec<u8> {
    let mut builder = GlbBuilder::default();
    let cobblestone = pom_material(
        &mut builder,
        find(materials, "cobblestone"),
        json!({"shadows": "soft"}),
    );
    let bricks = pom_material(
        &mut builder,
        find(materials, "bricks"),
        json!({"shadows": "soft"}),
    );
    let sign = pom_material(
        &mut builder,
        find(materials, "sign"),
        // The board and the crate's faces end where their texture does: their outlines show
        // the relief (`uv_bounds`).
        json!({"shadows": "soft", "max_samples": 64, "silhouette": "uv_bounds"}),
    );
    let fur = pom_material(
        &mut builder,
        find(materials, "fur"),
        json!({"method": "steep", "shadows": "off"}),
    );
    let cones = pom_material(
        &mut builder,
        find(materials, "cones"),
        json!({"shadows": "hard", "silhouette": "uv_bounds"}),
    );
    let ball = builder.material(json!({
        "name": "ball",
        "pbrMetallicRoughness": {"baseColorFactor": [0.55, 0.12, 0.1, 1.0], "metallicFactor": 0.0, "roughnessFactor": 0.35}
    }));

    let floor = builder.mesh("floor", &quad(6.0, 6.0, (4.0, 4.0)), cobblestone);
    let wall = builder.mesh("wall", &quad(6.0, 3.0, (3.0, 1.5)), bricks);
    let board = builder.mesh("sign", &quad(1.6, 1.6, (1.0, 1.0)), sign);
    let mat = builder.mesh("doormat", &quad(1.2, 0.8, (1.5, 1.0)), fur);
    let crate_mesh = builder.mesh("crate", &pom::Mesh::cube(0.8), cones);
    let ball_mesh = builder.mesh("ball", &pom::Mesh::uv_sphere(0.5, 12, 6), ball);

    // The plane faces +Y; a quarter turn about X makes it face +Z with v running down the wall.
    let upright = Quat::from_rotation_x(std::f32::consts::FRAC_PI_2);
    builder.node(node("floor", floor, Vec3::ZERO, Quat::IDENTITY));
    builder.node(node("wall", wall, Vec3::new(0.0, 1.5, -3.0), upright));
    builder.node(node("sign", board, Vec3::new(0.9, 1.8, -2.98), upright));
    builder.node(node(
        "doormat",
        mat,
        Vec3::new(-1.1, 0.01, -2.3),
        Quat::IDENTITY,
    ));
    builder.node(node(
        "crate",
        crate_mesh,
        Vec3::new(1.5, 0.4, 0.2),
        Quat::from_rotation_y(0.5),
    ));
    // Sunk a little into the stones, so depth offset has something to show.
    builder.node(node(
        "ball",
        ball_mesh,
        Vec3::new(-1.1, 0.47, -0.4),
        Quat::IDENTITY,
    ));

    let exposure = (time == TimeOfDay::Night).then_some(NIGHT_EXPOSURE);
    let camera = builder.camera(0.75, exposure);
    let eye = Vec3::new(3.6, 2.3, 4.0);
    let camera_rotation = pom::Transform::from_translation(eye)
        .looking_at(Vec3::new(-0.3, 0.9, -1.3), Vec3::Y)
        .rotation;
    builder.node(json!({"name": "camera", "camera": camera, "translation": eye.to_array(), "rotation": camera_rotation.to_array()}));
    match time {
        TimeOfDay::Day => {
            let color: [f32; 3] = [1.0, 0.96, 0.88];
            let intensity: f32 = 180_000.0;
            let sun = builder
                .light(json!({"type": "directional", "color": color, "intensity": intensity}));
            let towards = Vec3::new(-0.55, -0.75, -0.45);
            light_node(&mut builder, "sun", sun, Vec3::ZERO, towards);
        }
        TimeOfDay::Night => night_lights(&mut builder),
    }
    builder.finish()
}

/// A node holding light `light` at `position`, shining along `towards` (spots and the sun).
fn light_node(builder: &mut GlbBuilder, name: &str, light: usize, position: Vec3, towards: Vec3) {
    let rotation = pom::Transform::IDENTITY
        .looking_at(towards, Vec3::Y)
        .rotation;
    let mut node = json!({"name": name, "rotation": rotation.to_array(), "extensions": {"KHR_lights_punctual": {"light": light}}});
    if position != Vec3::ZERO {
        node["translation"] = json!(position.to_array());
    }
    builder.node(node);
}

/// The night's lights: two street lamps on the wall (sodium-orange spots, down and out), a lamp
/// over the sign, a lamp post by the crate, and a string of warm and amber bulbs hanging in a
/// curve from the wall over the street.
fn night_lights(builder: &mut GlbBuilder) {
    // The sun has set, 15° below the horizon: the sky that follows it is the night's, and it
    // lights nothing. What is left of the sky's light is a dim blue ambient.
    let set_sun =
        builder.light(json!({"type": "directional", "color": [1.0, 0.96, 0.88], "intensity": 0.0}));
    let below = Vec3::new(-0.6, -(15_f32.to_radians().sin()), -0.8).normalize();
    light_node(builder, "sun (set)", set_sun, Vec3::ZERO, -below);
    builder
        .scene_extras(json!({"pom": {"ambient": {"color": [0.35, 0.45, 0.8], "intensity": 3.0}}}));
    let sodium = [1.0, 0.62, 0.28];
    let street_lamp = builder.light(
        json!({"type": "spot", "color": sodium, "intensity": 2500.0, "range": 9.0,
        "spot": {"innerConeAngle": 0.45, "outerConeAngle": 0.85}}),
    );
    for (name, x) in [("street lamp left", -2.0), ("street lamp right", 2.3)] {
        light_node(
            builder,
            name,
            street_lamp,
            Vec3::new(x, 2.7, -2.7),
            Vec3::new(0.0, -1.0, 0.6),
        );
    }
    let sign_lamp = builder.light(
        json!({"type": "spot", "color": [1.0, 0.9, 0.75], "intensity": 400.0, "range": 3.0,
        "spot": {"innerConeAngle": 0.3, "outerConeAngle": 0.6}}),
    );
    light_node(
        builder,
        "sign lamp",
        sign_lamp,
        Vec3::new(0.9, 2.9, -2.4),
        Vec3::new(0.0, -1.0, -0.45),
    );
    let post = builder.light(
        json!({"type": "point", "color": [1.0, 0.85, 0.65], "intensity": 1500.0, "range": 10.0}),
    );
    light_node(
        builder,
        "lamp post",
        post,
        Vec3::new(2.6, 2.8, 1.9),
        Vec3::NEG_Y,
    );
    let warm = builder.light(
        json!({"type": "point", "color": [1.0, 0.78, 0.5], "intensity": 25.0, "range": 2.5}),
    );
    let amber = builder.light(
        json!({"type": "point", "color": [1.0, 0.5, 0.15], "intensity": 25.0, "range": 2.5}),
    );
    let (from, to) = (Vec3::new(-2.8, 2.6, -2.9), Vec3::new(2.6, 2.6, 1.9));
    for bulb in 0..STRING_BULBS {
        let t = (bulb as f32 + 0.5) / STRING_BULBS as f32;
        // A hanging string: lowest in the middle.
        let sag = 0.55 * 4.0 * t * (1.0 - t);
        let position = from.lerp(to, t) - Vec3::Y * sag;
        let light = if bulb % 2 == 0 { warm } else { amber };
        light_node(
            builder,
            &format!("bulb {bulb}"),
            light,
            position,
            Vec3::NEG_Y,
        );
    }
}
