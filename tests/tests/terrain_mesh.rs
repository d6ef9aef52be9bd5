//! `Mesh::terrain` on the GPU: a Gaussian hill seen from straight above under a low sun, lit
//! only by it, shows at every pixel the brightness Lambert's law gives its analytic normal
//! (relative to the flat ground around it), on both paths, with no NaN.

use glam::{Vec2, Vec3};
use pom::{
    AmbientLight, App, Assets, Camera, Color, DirectionalLight, HeightField, LitMaterial,
    LitPlugin, Mesh, RenderPath, RenderPlugin, TargetFormat, Transform,
};
use pom_tests::{in_error_scopes, set_path};

/// Side of the image in pixels.
const SIZE: u32 = 64;
/// The terrain's side in metres, and the hill's height.
const SIDE: f32 = 4.0;
const HILL_HEIGHT: f32 = 0.5;
/// The hill's width (standard deviation) in the field's 0..1 coordinates.
const SIGMA: f32 = 0.15;

fn hill(uv: Vec2) -> f32 {
    (-(uv - Vec2::splat(0.5)).length_squared() / (2.0 * SIGMA * SIGMA)).exp()
}

/// The hill's normal at a point of the ground (x, z), from the derivative of the Gaussian.
fn analytic_normal(x: f32, z: f32) -> Vec3 {
    let uv = Vec2::new(x / SIDE + 0.5, z / SIDE + 0.5);
    // d(height)/d(world) = HILL_HEIGHT · h · −(uv − ½)/σ² · d(uv)/d(world).
    let slope = HILL_HEIGHT * hill(uv) * -(uv - Vec2::splat(0.5)) / (SIGMA * SIGMA) / SIDE;
    Vec3::new(-slope.x, 1.0, -slope.y).normalize()
}

#[test]
fn a_hill_is_lit_as_its_slopes_face_the_sun_on_both_paths() {
    // The field's corner texels are the terrain's corners: texel i of 129 lies at i / 128.
    let values = (0..129 * 129)
        .map(|i| hill(Vec2::new((i % 129) as f32, (i / 129) as f32) / 128.0))
        .collect();
    let field = HeightField::new(129, 129, values).expect("field");
    let terrain = Mesh::terrain(&field, Vec3::new(SIDE, HILL_HEIGHT, SIDE), 96).expect("terrain");
    let mut app = App::new();
    app.add_plugin(RenderPlugin::new(SIZE, SIZE).with_format(TargetFormat::Float32))
        .add_plugin(LitPlugin);
    let mesh = app.resources.get_or_default::<Assets<Mesh>>().add(terrain);
    let material = LitMaterial {
        specular_strength: 0.0,
        ..LitMaterial::from_color(Color::WHITE)
    };
    app.world.spawn((mesh, material, Transform::IDENTITY));
    // Straight down, +X to the right of the image and +Z down it.
    let eye = Transform::from_xyz(0.0, 5.0, 0.0).looking_at(Vec3::ZERO, Vec3::NEG_Z);
    app.world.spawn((Camera::orthographic(SIDE), eye));
    let to_sun = Vec3::new(1.0, 1.2, 0.3).normalize();
    let sun = Transform::IDENTITY.looking_at(-to_sun, Vec3::Y);
    app.world.spawn((DirectionalLight::default(), sun));
    app.insert_resource(AmbientLight {
        color: Color::WHITE,
        intensity: 0.0,
    });
    for path in [RenderPath::Forward, RenderPath::Deferred] {
        set_path(&mut app, path);
        // The light the material computed, before tonemapping bends it.
        let image = in_error_scopes(&mut app, "render", |app| {
            app.update()?;
            Ok(pom::capture_scene(app)?)
        })
        .expect("render");
        let brightness = |x: u32, y: u32| image.get_pixel(x, y).0[1];
        assert!(
            image
                .pixels()
                .all(|pixel| pixel.0.iter().all(|v| v.is_finite())),
            "{path:?}: a pixel is not finite"
        );
        // The corner is flat ground (the hill is 1e-5 of its height there).
        let flat = brightness(1, 1);
        assert!(flat > 0.0, "{path:?}: the flat ground is black");
        let mut worst = (0.0_f32, 0, 0);
        for y in 4..SIZE - 4 {
            for x in 4..SIZE - 4 {
                // The pixel's centre on the ground (x right, z down the image).
                let world = |pixel: u32| ((pixel as f32 + 0.5) / SIZE as f32 - 0.5) * SIDE;
                let normal = analytic_normal(world(x), world(y));
                let expected = normal.dot(to_sun).max(0.0) / Vec3::Y.dot(to_sun);
                let error = (brightness(x, y) / flat - expected).abs();
                if error > worst.0 {
                    worst = (error, x, y);
                }
            }
        }
        eprintln!(
            "{path:?}: worst error {:.4} at {:?}",
            worst.0,
            (worst.1, worst.2)
        );
        assert!(
            worst.0 < 0.03,
            "{path:?}: pixel {:?} is {:.3} off Lambert's law for the hill's normal",
            (worst.1, worst.2),
            worst.0
        );
    }
}
