//! The anti-aliasing tests' scenes and settling: a camera's anti-aliasing, its settled image,
//! and the turned square whose straight edges every kind must smooth.

use std::path::Path;

use glam::{Quat, Vec3};
use image::RgbaImage;
use pom::{
    AntiAliasing, App, Assets, Camera, Color, DirectionalLight, GlobalTransform, LitMaterial, Mesh,
    RenderPlugin, Transform,
};

use crate::{render_and_capture, run_frames};

/// Frames a still TAA image is rendered for: one whole cycle of the default jitter, after
/// which the history is the plain mean of its sixteen sub-pixel positions.
pub const SETTLE: usize = 16;

/// Gives every camera of `app` the anti-aliasing `mode`.
pub fn set_anti_aliasing(app: &mut App, mode: AntiAliasing) {
    let cameras: Vec<_> = app
        .world
        .query::<(pom::hecs::Entity, &Camera)>()
        .iter()
        .map(|(entity, _)| entity)
        .collect();
    for camera in cameras {
        app.world.insert_one(camera, mode).unwrap();
    }
}

/// The image `app` shows with `mode`, settled: TAA after [`SETTLE`] frames, the others after one.
pub fn settled(app: &mut App, mode: AntiAliasing) -> RgbaImage {
    set_anti_aliasing(app, mode);
    if mode == AntiAliasing::Taa {
        run_frames(app, SETTLE - 1).unwrap();
    }
    render_and_capture(app).unwrap()
}

/// Writes `image` under target/anti-aliasing/ for a person to look at.
pub fn save_for_looking(name: &str, image: &RgbaImage) {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../target/anti-aliasing");
    let _ = std::fs::create_dir_all(&dir);
    let _ = image.save(dir.join(format!("{name}.png")));
}

/// A white square turned 30° about the view axis on a dark ground, lit from the camera's side:
/// edges at 30° and 120°.
pub fn turned_square(width: u32, height: u32) -> App {
    turned_square_with(RenderPlugin::new(width, height))
}

/// The turned square rendered by `render` (its size, format or post-processing path).
pub fn turned_square_with(render: RenderPlugin) -> App {
    let mut app = App::new();
    app.add_plugin(render).add_plugin(pom::LitPlugin);
    app.finish().unwrap();
    let mesh = app
        .resources
        .get_mut::<Assets<Mesh>>()
        .unwrap()
        .add(Mesh::plane(1.0));
    let transform = Transform {
        rotation: Quat::from_rotation_y(30_f32.to_radians()),
        ..Transform::IDENTITY
    };
    app.world.spawn((
        mesh,
        LitMaterial {
            base_color: Color::linear_rgb(0.9, 0.9, 0.9),
            specular_strength: 0.0,
            ..LitMaterial::default()
        },
        transform,
        GlobalTransform(transform.to_affine()),
    ));
    app.world.spawn((
        Camera {
            clear_color: Color::linear_rgb(0.02, 0.02, 0.03),
            ..Camera::orthographic(1.6)
        },
        Transform::from_xyz(0.0, 3.0, 0.0).looking_at(Vec3::ZERO, Vec3::NEG_Z),
    ));
    app.world.spawn((
        DirectionalLight::default(),
        Transform::from_xyz(0.0, 3.0, 0.5).looking_at(Vec3::ZERO, Vec3::Y),
    ));
    app
}
