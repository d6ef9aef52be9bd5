//! The scene the sandbox opens with: a brick floor, a cube and a sphere under two lights.

use anyhow::{Context, Result};
use glam::{Quat, Vec3};
use pom::{
    App, Assets, Camera, Color, DirectionalLight, Image, LitMaterial, Mesh, PointLight,
    TextureKind, Transform,
};

const BRICK_TEXELS: u32 = 256;
/// Bricks per texture, across and down.
const BRICKS_U: f32 = 4.0;
const BRICKS_V: f32 = 8.0;
const MORTAR: f32 = 0.06;

/// Height of a running-bond brick wall at (u, v) in 0..1: 1 on a brick, falling to 0 in mortar.
fn brick_height(u: f32, v: f32) -> f32 {
    let row = (v * BRICKS_V).floor();
    let offset = if row as i64 % 2 == 0 { 0.0 } else { 0.5 };
    let across = (u * BRICKS_U + offset).fract();
    let down = (v * BRICKS_V).fract();
    // Distance to the nearest mortar line, in brick-size units, softened into a bevel.
    let edge = across
        .min(1.0 - across)
        .min((down.min(1.0 - down)) * BRICKS_U / BRICKS_V * 2.0);
    (edge / MORTAR).clamp(0.0, 1.0)
}

fn brick_textures() -> Result<(Image, Image)> {
    let size = BRICK_TEXELS;
    let texel = 1.0 / size as f32;
    let mut heights = Vec::with_capacity((size * size) as usize);
    let mut albedo = Vec::with_capacity((size * size * 4) as usize);
    for y in 0..size {
        for x in 0..size {
            let (u, v) = ((x as f32 + 0.5) * texel, (y as f32 + 0.5) * texel);
            let h = brick_height(u, v);
            heights.push(h);
            // Mortar is pale grey; bricks vary in tone by row and column.
            let row = (v * BRICKS_V).floor();
            let tone =
                0.85 + 0.15 * ((row * 12.9898 + (u * BRICKS_U).floor() * 78.233).sin() * 0.5 + 0.5);
            let brick = [170.0 * tone, 80.0 * tone, 60.0 * tone];
            let mortar = [185.0, 180.0, 170.0];
            let mix = |a: f32, b: f32| (b + (a - b) * h).round() as u8;
            albedo.extend([
                mix(brick[0], mortar[0]),
                mix(brick[1], mortar[1]),
                mix(brick[2], mortar[2]),
                255,
            ]);
        }
    }
    let normal = pom::normal_map_from_heights(&heights, size, size, 0.02)?;
    let albedo = Image::from_rgba8(size, size, albedo, TextureKind::Color)?;
    Ok((albedo, normal))
}

/// Adds the demo scene's meshes, textures, camera and lights to `app`.
pub fn spawn(app: &mut App) -> Result<()> {
    let (albedo, normal) = brick_textures().context("generating the brick textures")?;
    let images = app
        .resources
        .get_mut::<Assets<Image>>()
        .context("the render plugin must be added first")?;
    let brick_material = LitMaterial {
        base_color_texture: Some(images.add(albedo)),
        normal_map: Some(images.add(normal)),
        specular_strength: 0.15,
        shininess: 24.0,
        ..LitMaterial::default()
    };
    let meshes = app
        .resources
        .get_mut::<Assets<Mesh>>()
        .context("the render plugin must be added first")?;
    let floor = meshes.add(Mesh::plane_tiled(8.0, 4.0));
    let cube = meshes.add(Mesh::cube(1.0));
    let sphere = meshes.add(Mesh::uv_sphere(0.55, 48, 24));

    app.world.spawn((
        Camera::perspective(45.0),
        Transform::from_xyz(-2.6, 2.2, 3.6).looking_at(Vec3::new(0.0, 0.4, 0.0), Vec3::Y),
    ));
    app.world.spawn((
        DirectionalLight {
            color: Color::linear_rgb(1.0, 0.95, 0.85),
            intensity: 1.5,
        },
        Transform::IDENTITY.looking_at(Vec3::new(-0.6, -1.0, -0.4), Vec3::Y),
    ));
    app.world.spawn((
        PointLight {
            color: Color::linear_rgb(0.3, 0.5, 1.0),
            intensity: 3.0,
            range: 6.0,
        },
        Transform::from_xyz(-1.2, 1.0, 1.4),
    ));
    app.world
        .spawn((floor, brick_material.clone(), Transform::IDENTITY));
    app.world.spawn((
        cube,
        brick_material,
        Transform {
            translation: Vec3::new(0.7, 0.5, -0.3),
            rotation: Quat::from_rotation_y(0.6),
            scale: Vec3::ONE,
        },
    ));
    app.world.spawn((
        sphere,
        LitMaterial {
            specular_strength: 0.6,
            shininess: 64.0,
            ..LitMaterial::from_color(Color::srgb(0.55, 0.58, 0.62))
        },
        Transform::from_xyz(-0.8, 0.55, 0.5),
    ));
    Ok(())
}
