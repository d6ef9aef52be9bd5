//! The street-corner scene: a cobblestone floor, a brick wall with a shop sign, a furry doormat,
//! a studded crate and a low-poly ball resting on the stones. One camera, one sun.

use glam::{Quat, Vec3};
use serde_json::{Value, json};

use super::EncodedMaterial;
use super::glb::GlbBuilder;

/// File name of the scene under assets/.
pub const STREET_CORNER_FILE: &str = "street_corner.glb";

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

/// The `.glb` bytes of the scene, textures embedded.
pub fn build(materials: &[EncodedMaterial]) -> Vec<u8> {
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

    let camera = builder.camera(0.75);
    let eye = Vec3::new(3.6, 2.3, 4.0);
    let camera_rotation = pom::Transform::from_translation(eye)
        .looking_at(Vec3::new(-0.3, 0.9, -1.3), Vec3::Y)
        .rotation;
    builder.node(json!({"name": "camera", "camera": camera, "translation": eye.to_array(), "rotation": camera_rotation.to_array()}));
    let sun = builder.sun([1.0, 0.96, 0.88], 180_000.0);
    let sun_rotation = pom::Transform::IDENTITY
        .looking_at(Vec3::new(-0.55, -0.75, -0.45), Vec3::Y)
        .rotation;
    builder.node(json!({"name": "sun", "rotation": sun_rotation.to_array(), "extensions": {"KHR_lights_punctual": {"light": sun}}}));
    builder.finish()
}
