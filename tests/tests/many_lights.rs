//! Hundreds of lights: 256 lights over a 16 × 16 grid of floor cells, each reaching only its own
//! cell, light every cell with their own pool on both paths, seen straight down (orthographic)
//! and in perspective; a spot's cone and a light's range cut off as `KHR_lights_punctual`
//! says; a cell lit by its light among 255 others shows what it shows lit alone; the parallax
//! material's relief shadows go to the brightest lights at each pixel.

use glam::{Mat4, Vec3};
use pom::{
    AmbientLight, App, Assets, Camera, Color, LightingModel, LitMaterial, Mesh, PointLight,
    RenderPath, RenderPlugin, SpotLight, TargetFormat, Transform,
};
use pom_tests::{in_error_scopes, set_path};

const SIZE: u32 = 512;
/// Cells along each side of the floor (one metre each).
const CELLS: i32 = 16;
/// Each light's height over its cell's centre, and its range: it reaches the floor out to
/// √(0.5² − 0.4²) = 0.3 m from the centre, inside its cell.
const HEIGHT: f32 = 0.4;
const RANGE: f32 = 0.5;
/// The spots' cone: at 0.4 m their disc ends 0.4 · tan 20° = 0.146 m from the centre.
const SPOT_INNER: f32 = 10.0;
const SPOT_OUTER: f32 = 20.0;

/// The colour of cell (i, j)'s light: red, green or blue, in a pattern a mirrored image breaks.
fn channel(i: i32, j: i32) -> usize {
    (i + 2 * j).rem_euclid(3) as usize
}

fn cell_centre(i: i32, j: i32) -> Vec3 {
    Vec3::new(i as f32 - 7.5, 0.0, j as f32 - 7.5)
}

/// Every other cell (a checkerboard) has a spot pointing down instead of a point light.
fn is_spot(i: i32, j: i32) -> bool {
    (i + j) % 2 == 1
}

struct Floor {
    app: App,
    view_projection: Mat4,
}

/// The floor under the lights of `cells`, seen from `camera` (straight down from 12 m).
fn floor(camera: Camera, cells: &[(i32, i32)]) -> Floor {
    let mut app = App::new();
    app.add_plugin(RenderPlugin::new(SIZE, SIZE).with_format(TargetFormat::Float32))
        .add_plugin(pom::LitPlugin);
    app.finish().unwrap();
    app.insert_resource(AmbientLight {
        color: Color::WHITE,
        intensity: 0.0,
    });
    let mesh = app
        .resources
        .get_mut::<Assets<Mesh>>()
        .unwrap()
        .add(Mesh::plane(CELLS as f32));
    let material = LitMaterial {
        lighting: LightingModel::GgxLambert,
        roughness: 1.0,
        metallic: 0.0,
        ..LitMaterial::from_color(Color::WHITE)
    };
    app.world.spawn((mesh, material, Transform::IDENTITY));
    for &(i, j) in cells {
        let mut rgb = [0.0; 3];
        rgb[channel(i, j)] = 1.0;
        let color = Color::linear_rgb(rgb[0], rgb[1], rgb[2]);
        let above = cell_centre(i, j) + Vec3::Y * HEIGHT;
        let place = Transform::from_translation(above).looking_at(cell_centre(i, j), Vec3::Z);
        if is_spot(i, j) {
            let spot = SpotLight {
                color,
                intensity: 2000.0,
                range: RANGE,
                inner_angle: SPOT_INNER.to_radians(),
                outer_angle: SPOT_OUTER.to_radians(),
            };
            app.world.spawn((spot, place));
        } else {
            let point = PointLight {
                color,
                intensity: 2000.0,
                range: RANGE,
            };
            app.world.spawn((point, place));
        }
    }
    let transform = Transform::from_xyz(0.0, 12.0, 0.0).looking_at(Vec3::ZERO, Vec3::NEG_Z);
    let view_projection =
        camera.projection.matrix(1.0) * Mat4::from(transform.to_affine()).inverse();
    app.world.spawn((camera, pom::Tonemapping::None, transform));
    Floor {
        app,
        view_projection,
    }
}

impl Floor {
    /// The pre-exposed scene on `path`.
    fn render(&mut self, path: RenderPath) -> image::Rgba32FImage {
        set_path(&mut self.app, path);
        in_error_scopes(&mut self.app, "many lights", |app| {
            app.update()?;
            Ok(pom::capture_scene(app)?)
        })
        .unwrap()
    }

    /// The pixel `world` falls in.
    fn pixel(&self, world: Vec3) -> (u32, u32) {
        let ndc = self.view_projection.project_point3(world);
        let x = (ndc.x * 0.5 + 0.5) * SIZE as f32;
        let y = (0.5 - ndc.y * 0.5) * SIZE as f32;
        (x as u32, y as u32)
    }
}

fn every_cell() -> Vec<(i32, i32)> {
    (0..CELLS)
        .flat_map(|i| (0..CELLS).map(move |j| (i, j)))
        .collect()
}

fn cameras() -> [(&'static str, Camera); 2] {
    // 16 m across from 12 m up: 2 · atan(8.4 / 12) of vertical field of view.
    let fov = 2.0 * (8.4_f32 / 12.0).atan().to_degrees();
    [
        ("orthographic", Camera::orthographic(16.8)),
        ("perspective", Camera::perspective(fov)),
    ]
}

#[test]
fn two_hundred_fifty_six_lights_each_light_their_own_cell_on_both_paths() {
    for (name, camera) in cameras() {
        let mut floor = floor(camera, &every_cell());
        for path in [RenderPath::Forward, RenderPath::Deferred] {
            let scene = floor.render(path);
            let at = |world: Vec3| {
                let (x, y) = floor.pixel(world);
                scene.get_pixel(x, y).0
            };
            let mut centres = Vec::new();
            for (i, j) in every_cell() {
                let centre = cell_centre(i, j);
                let lit = at(centre);
                let own = channel(i, j);
                let others = (0..3)
                    .filter(|&c| c != own)
                    .map(|c| lit[c])
                    .fold(0.0, f32::max);
                assert!(
                    lit[own] > 0.0 && others <= 1e-4 * lit[own],
                    "{name} {path:?}: cell ({i}, {j}) shows {lit:?}, not its light's channel {own}"
                );
                centres.push(lit[own]);
                // Past the light's reach (0.3 m), up to the cell's corner: nothing.
                for offset in [
                    Vec3::new(0.36, 0.0, 0.0),
                    Vec3::new(0.0, 0.0, -0.36),
                    Vec3::new(0.45, 0.0, 0.45),
                ] {
                    let dark = at(centre + offset);
                    assert!(
                        dark[..3].iter().all(|&v| v == 0.0),
                        "{name} {path:?}: cell ({i}, {j}) is lit at {offset} past its light's range: {dark:?}"
                    );
                }
                // Inside the range but outside a spot's cone: a point lights it, a spot not.
                let ring = at(centre + Vec3::new(0.22, 0.0, 0.0))[own];
                if is_spot(i, j) {
                    assert_eq!(
                        ring, 0.0,
                        "{name} {path:?}: spot ({i}, {j}) lights past its cone"
                    );
                } else {
                    assert!(
                        ring > 0.0,
                        "{name} {path:?}: point ({i}, {j}) does not reach 0.22 m"
                    );
                }
            }
            let mean = centres.iter().sum::<f32>() / centres.len() as f32;
            let spread = centres
                .iter()
                .map(|value| (value / mean - 1.0).abs())
                .fold(0.0, f32::max);
            eprintln!(
                "{name} {path:?}: 256 cell centres, mean {mean:.4}, largest departure {spread:.4}"
            );
            // Straight down every centre is lit alike; in perspective the view differs a
            // little from cell to cell (the specular lobe).
            let tolerance = if name == "orthographic" { 0.01 } else { 0.1 };
            assert!(
                spread <= tolerance,
                "{name} {path:?}: centres differ by {spread}"
            );
        }
    }
}

#[test]
fn a_cell_among_two_hundred_fifty_five_other_lights_shows_what_it_shows_alone() {
    let (_, camera) = cameras()[1];
    for path in [RenderPath::Forward, RenderPath::Deferred] {
        let cell = (5, 9);
        let mut alone = floor(camera, &[cell]);
        let mut crowded = floor(camera, &every_cell());
        let (alone_scene, crowded_scene) = (alone.render(path), crowded.render(path));
        let centre = cell_centre(cell.0, cell.1);
        let own = channel(cell.0, cell.1);
        for offset in [0.0, 0.08, 0.14] {
            let (x, y) = alone.pixel(centre + Vec3::new(offset, 0.0, 0.0));
            let (a, c) = (
                alone_scene.get_pixel(x, y).0[own],
                crowded_scene.get_pixel(x, y).0[own],
            );
            assert!(
                a > 0.0 && (c / a - 1.0).abs() < 1e-3,
                "{path:?} at {offset} m: alone {a}, among the others {c}"
            );
        }
    }
}

/// The parallax material's relief shadows march for the brightest `shadowed_lights` lights at a
/// pixel: with one, a bright sun keeps its relief's shadows and a dim one lights the relief
/// unshadowed by it, exactly the sum of the two lit alone that way; with two, the dim one's
/// relief shadows show too.
#[test]
fn relief_shadows_go_to_the_brightest_lights_at_each_pixel() {
    use pom::preview::PreviewView;
    use pom::{DirectionalLight, ShadowMode, patterns};
    use pom_tests::pom_scene::{HeightMaterial, preview_app, set_material};

    let textures = HeightMaterial {
        field: patterns::raised_block(128, 0.4),
        height_scale: 0.08,
    };
    let view = PreviewView {
        view_angle: 20.0,
        light_angle: 60.0,
        ..PreviewView::default()
    };
    let mut app = preview_app(64, TargetFormat::Float32, &textures, &view, |material| {
        material
    })
    .unwrap();
    app.insert_resource(AmbientLight {
        color: Color::WHITE,
        intensity: 0.0,
    });
    let dim_view = PreviewView {
        light_azimuth: 180.0,
        ..view
    };
    let dim = app.world.spawn((
        DirectionalLight {
            intensity: 20_000.0,
            ..DirectionalLight::default()
        },
        dim_view.light_transform(),
    ));
    let lights: Vec<_> = app
        .world
        .query::<(pom::hecs::Entity, &DirectionalLight)>()
        .iter()
        .map(|(entity, _)| entity)
        .collect();
    let bright = *lights.iter().find(|&&entity| entity != dim).unwrap();
    let mut render = |bright_lux: f32, dim_lux: f32, shadows: ShadowMode, shadowed: u32| {
        for (entity, lux) in [(bright, bright_lux), (dim, dim_lux)] {
            app.world
                .get::<&mut DirectionalLight>(entity)
                .unwrap()
                .intensity = lux;
        }
        set_material(&mut app, |material| {
            material.shadows = shadows;
            material.shadowed_lights = shadowed;
        });
        in_error_scopes(&mut app, "shadowed lights", |app| {
            app.update()?;
            Ok(pom::capture_scene(app)?)
        })
        .unwrap()
    };
    let both_one = render(100_000.0, 20_000.0, ShadowMode::Soft, 1);
    let both_two = render(100_000.0, 20_000.0, ShadowMode::Soft, 2);
    let bright_alone = render(100_000.0, 0.0, ShadowMode::Soft, 1);
    let dim_unshadowed = render(0.0, 20_000.0, ShadowMode::Off, 1);
    let (mut worst, mut dim_shadows) = (0.0_f32, 0.0_f32);
    for (((one, two), alone), unshadowed) in both_one
        .pixels()
        .zip(both_two.pixels())
        .zip(bright_alone.pixels())
        .zip(dim_unshadowed.pixels())
    {
        for c in 0..3 {
            let sum = alone.0[c] + unshadowed.0[c];
            worst = worst.max((one.0[c] - sum).abs() / sum.max(1e-3));
            dim_shadows = dim_shadows.max(one.0[c] - two.0[c]);
        }
    }
    eprintln!(
        "one shadowed light: within {worst:.5} of the sum; the dim light's shadows take up to {dim_shadows:.4}"
    );
    assert!(worst < 1e-3, "{worst}");
    assert!(
        dim_shadows > 0.01,
        "the dim light casts no relief shadow with two: {dim_shadows}"
    );
}
