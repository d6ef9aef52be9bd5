//! Reference-image tests of the forward renderer on the software Vulkan driver.
//! Each reference under tests/golden/ was looked at before it was blessed.

use glam::{Quat, Vec3};
use pom::{
    App, Assets, Camera, Color, DirectionalLight, Handle, Image, LitMaterial, Mesh, PointLight,
    Transform,
};
use pom_tests::{FlipTolerance, check_golden, fixtures, headless_app, render_both_paths};

fn add_mesh(app: &mut App, mesh: Mesh) -> Handle<Mesh> {
    app.resources.get_mut::<Assets<Mesh>>().unwrap().add(mesh)
}

fn add_image(app: &mut App, image: Image) -> Handle<Image> {
    app.resources.get_mut::<Assets<Image>>().unwrap().add(image)
}

fn bumpy_material(app: &mut App, albedo: Image) -> LitMaterial {
    LitMaterial {
        base_color_texture: Some(add_image(app, albedo)),
        normal_map: Some(add_image(app, fixtures::bump_normal_map(128, 4.0, 0.04))),
        specular_strength: 0.4,
        shininess: 48.0,
        ..LitMaterial::default()
    }
}

fn sun(direction: Vec3, intensity: f32) -> (DirectionalLight, Transform) {
    (
        DirectionalLight {
            color: Color::WHITE,
            intensity,
        },
        Transform::IDENTITY.looking_at(direction, Vec3::Y),
    )
}

#[test]
fn normal_mapped_cube_under_one_directional_light() {
    let mut app = headless_app(256, 256).unwrap();
    let cube = add_mesh(&mut app, Mesh::cube(1.0));
    let material = bumpy_material(
        &mut app,
        fixtures::checker_albedo(128, 4, [200, 80, 60], [230, 200, 170]),
    );
    app.world.spawn((
        Camera::perspective(40.0),
        Transform::from_xyz(1.6, 1.3, 2.2).looking_at(Vec3::ZERO, Vec3::Y),
    ));
    app.world.spawn(sun(Vec3::new(-0.5, -1.0, -0.8), 250_000.0));
    app.world.spawn((cube, material, Transform::IDENTITY));
    let image = render_both_paths(&mut app, "cube_directional").unwrap();
    check_golden("cube_directional", &image, FlipTolerance::default()).unwrap();
}

#[test]
fn directional_and_point_light_together() {
    let mut app = headless_app(256, 256).unwrap();
    let floor = add_mesh(&mut app, Mesh::plane_tiled(6.0, 3.0));
    let sphere = add_mesh(&mut app, Mesh::uv_sphere(0.6, 32, 16));
    let floor_material = bumpy_material(
        &mut app,
        fixtures::checker_albedo(128, 4, [150, 150, 150], [90, 90, 100]),
    );
    app.world.spawn((
        Camera::perspective(50.0),
        Transform::from_xyz(0.0, 2.2, 4.0).looking_at(Vec3::new(0.0, 0.3, 0.0), Vec3::Y),
    ));
    // A dim blue sky light from the left and a warm point light to the right of the sphere.
    app.world.spawn((
        DirectionalLight {
            color: Color::linear_rgb(0.4, 0.5, 1.0),
            intensity: 80_000.0,
        },
        Transform::IDENTITY.looking_at(Vec3::new(1.0, -1.0, -0.3), Vec3::Y),
    ));
    app.world.spawn((
        PointLight {
            color: Color::linear_rgb(1.0, 0.6, 0.25),
            intensity: 250_000.0,
            range: 8.0,
        },
        Transform::from_xyz(1.3, 0.9, 0.6),
    ));
    app.world
        .spawn((floor, floor_material, Transform::IDENTITY));
    app.world.spawn((
        sphere,
        LitMaterial::from_color(Color::srgb(0.8, 0.8, 0.8)),
        Transform::from_xyz(-0.2, 0.6, 0.0),
    ));
    let image = render_both_paths(&mut app, "two_lights").unwrap();
    check_golden("two_lights", &image, FlipTolerance::default()).unwrap();
}

/// A row of cubes receding from the camera: perspective shrinks the far ones, orthographic
/// keeps them the same size. 250×180 also checks readback of a width that is no multiple of 64.
fn receding_cubes(camera: Camera) -> image::RgbaImage {
    let mut app = headless_app(250, 180).unwrap();
    let cube = add_mesh(&mut app, Mesh::cube(0.8));
    let floor = add_mesh(&mut app, Mesh::plane_tiled(12.0, 6.0));
    let checker = add_image(
        &mut app,
        fixtures::checker_albedo(64, 2, [180, 180, 180], [110, 110, 110]),
    );
    app.world.spawn((
        camera,
        Transform::from_xyz(3.0, 2.5, 4.0).looking_at(Vec3::new(0.0, 0.0, -1.5), Vec3::Y),
    ));
    app.world.spawn(sun(Vec3::new(-0.3, -1.0, -0.5), 200_000.0));
    app.world.spawn((
        floor,
        LitMaterial {
            base_color_texture: Some(checker),
            specular_strength: 0.0,
            ..LitMaterial::default()
        },
        Transform::IDENTITY,
    ));
    for i in 0..4 {
        let hue = [
            Color::srgb(0.8, 0.3, 0.3),
            Color::srgb(0.3, 0.7, 0.3),
            Color::srgb(0.3, 0.4, 0.8),
            Color::srgb(0.8, 0.7, 0.2),
        ][i];
        app.world.spawn((
            cube.clone(),
            LitMaterial::from_color(hue),
            Transform {
                translation: Vec3::new(0.0, 0.4, 1.0 - 1.6 * i as f32),
                rotation: Quat::from_rotation_y(0.3 * i as f32),
                scale: Vec3::ONE,
            },
        ));
    }
    render_both_paths(&mut app, "receding_cubes").unwrap()
}

#[test]
fn perspective_camera() {
    let image = receding_cubes(Camera::perspective(45.0));
    check_golden("projection_perspective", &image, FlipTolerance::default()).unwrap();
}

#[test]
fn orthographic_camera() {
    let image = receding_cubes(Camera::orthographic(5.0));
    check_golden("projection_orthographic", &image, FlipTolerance::default()).unwrap();
}
