//! The environment light: in a furnace (the same radiance from everywhere, no direct light)
//! white spheres, metal and dielectric, reflect the environment whole on both paths; the
//! background shows the environment; the default sky follows the sun; a bad environment file
//! is an error naming it.

use glam::Vec3;
use pom::{
    AmbientLight, App, Assets, Camera, Color, EnvironmentLight, EnvironmentSettings, LightingModel,
    LitMaterial, Mesh, RenderPath, RenderPlugin, TargetFormat, Tonemapping, Transform,
};
use pom_tests::{HarnessError, in_error_scopes, set_path};

const SIZE: u32 = 64;
/// The furnace's radiance, cd/m²: well inside half floats and the default exposure's range.
const FURNACE: f32 = 2000.0;

/// A white sphere of `lighting`, `roughness` and `metallic` filling most of a float target,
/// seen in orthographic projection, lit by a uniform environment and nothing else.
fn furnace(sphere: LitMaterial, energy_compensation: bool) -> Result<App, HarnessError> {
    let mut app = App::new();
    app.add_plugin(RenderPlugin::new(SIZE, SIZE).with_format(TargetFormat::Float32))
        .add_plugin(pom::LitPlugin);
    app.finish()?;
    app.insert_resource(AmbientLight {
        color: Color::WHITE,
        intensity: 0.0,
    });
    app.insert_resource(EnvironmentLight::uniform([FURNACE; 3]).with_settings(
        EnvironmentSettings {
            resolution: 64,
            energy_compensation,
            ..EnvironmentSettings::default()
        },
    ));
    let mesh = app
        .resources
        .get_mut::<Assets<Mesh>>()
        .unwrap()
        .add(Mesh::uv_sphere(1.0, 64, 32));
    app.world.spawn((
        Camera::orthographic(2.6),
        Tonemapping::None,
        Transform::from_xyz(0.0, 0.0, 5.0).looking_at(Vec3::ZERO, Vec3::Y),
    ));
    app.world.spawn((mesh, sphere, Transform::IDENTITY));
    Ok(app)
}

/// The mean of the sphere's centre region (within a fifth of its radius of the middle) over
/// the background's radiance, in the pre-exposed scene.
fn reflected_fraction(app: &mut App, path: RenderPath) -> f32 {
    set_path(app, path);
    let scene = in_error_scopes(app, "furnace", |app| {
        app.update()?;
        Ok(pom::capture_scene(app)?)
    })
    .unwrap();
    let background = scene.get_pixel(0, 0).0[1];
    let radius_px = SIZE as f32 / 2.6;
    let centre = SIZE as f32 / 2.0;
    let (mut sum, mut count) = (0.0, 0);
    for (x, y, pixel) in scene.enumerate_pixels() {
        let offset = Vec3::new(x as f32 + 0.5 - centre, y as f32 + 0.5 - centre, 0.0);
        if offset.length() < radius_px * 0.2 {
            sum += pixel.0[0..3].iter().sum::<f32>() / 3.0;
            count += 1;
        }
    }
    assert!(
        count > 0 && background > 0.0,
        "{count} pixels, background {background}"
    );
    sum / count as f32 / background
}

fn white(lighting: LightingModel, roughness: f32, metallic: f32) -> LitMaterial {
    LitMaterial {
        lighting,
        roughness,
        metallic,
        ..LitMaterial::from_color(Color::WHITE)
    }
}

#[test]
fn white_spheres_in_a_furnace_reflect_the_environment_whole_on_both_paths() {
    let mut report = Vec::new();
    for path in [RenderPath::Forward, RenderPath::Deferred] {
        for (name, material, least) in [
            (
                "metal 0.1",
                white(LightingModel::GgxLambert, 0.1, 1.0),
                0.95,
            ),
            (
                "metal 0.5",
                white(LightingModel::GgxLambert, 0.5, 1.0),
                0.95,
            ),
            (
                "metal 0.9",
                white(LightingModel::GgxLambert, 0.9, 1.0),
                0.95,
            ),
            (
                "dielectric 0.5",
                white(LightingModel::GgxLambert, 0.5, 0.0),
                0.9,
            ),
            (
                "Cook-Torrance metal 0.9",
                white(LightingModel::CookTorrance, 0.9, 1.0),
                0.95,
            ),
        ] {
            let with = reflected_fraction(&mut furnace(material.clone(), true).unwrap(), path);
            let without = reflected_fraction(&mut furnace(material, false).unwrap(), path);
            report.push(format!(
                "{path:?} {name}: {with:.3} (without compensation {without:.3})"
            ));
            assert!(
                (least..=1.05).contains(&with),
                "{path:?} {name} reflects {with} of the furnace"
            );
            assert!(
                without <= with + 1e-3,
                "{path:?} {name}: {without} > {with}"
            );
        }
    }
    println!("{}", report.join("\n"));
}

#[test]
fn without_an_environment_the_ambient_light_lights_as_before() {
    let mut app = furnace(white(LightingModel::GgxLambert, 0.5, 0.0), true).unwrap();
    app.insert_resource(EnvironmentLight::default());
    app.insert_resource(AmbientLight {
        color: Color::WHITE,
        intensity: 10_000.0,
    });
    set_path(&mut app, RenderPath::Forward);
    let scene = in_error_scopes(&mut app, "ambient", |app| {
        app.update()?;
        Ok(pom::capture_scene(app)?)
    })
    .unwrap();
    // The ambient term is the albedo × illuminance / π, pre-exposed.
    let exposure = pom::Exposure::default().multiplier();
    let expected = 10_000.0 / std::f32::consts::PI * exposure;
    let centre = scene.get_pixel(SIZE / 2, SIZE / 2).0[1];
    assert!(
        (centre - expected).abs() < 1e-3 * expected.max(1.0),
        "{centre} vs {expected}"
    );
    // No environment behind the sphere: the camera's clear colour.
    let corner = scene.get_pixel(0, 0).0;
    let clear = Camera::orthographic(2.6).clear_color;
    assert_eq!(corner[..3], [clear.r, clear.g, clear.b], "{corner:?}");
}

/// The sky's radiance the CPU model gives along `direction` for a sun towards `sun` of
/// `lux`, pre-exposed at the default exposure.
fn cpu_sky(sun: Vec3, lux: f32, direction: Vec3) -> Vec3 {
    let sky = pom::render::environment::SkyState::new(pom::Sky::default(), sun, lux);
    sky.radiance(direction.normalize()) * pom::Exposure::default().multiplier()
}

#[test]
fn a_mirror_ball_reflects_the_sky_where_the_model_puts_it_and_the_background_shows_it() {
    let sun = Vec3::new(0.8, 0.6, 0.0);
    let lux = 50_000.0;
    let mut app = furnace(white(LightingModel::GgxLambert, 0.0, 1.0), true).unwrap();
    // The eye 30° up, so that the ball's reflections are of the sky above the horizon.
    let to_eye = Vec3::new(0.0, 0.5, 0.866);
    let camera = app
        .world
        .query::<(pom::hecs::Entity, &Camera)>()
        .iter()
        .map(|(entity, _)| entity)
        .next()
        .unwrap();
    *app.world.get::<&mut Transform>(camera).unwrap() =
        Transform::from_translation(to_eye * 5.0).looking_at(Vec3::ZERO, Vec3::Y);
    app.insert_resource(EnvironmentLight::sky().with_settings(EnvironmentSettings {
        resolution: 128,
        ..EnvironmentSettings::default()
    }));
    app.world.spawn((
        pom::DirectionalLight {
            color: Color::WHITE,
            intensity: lux,
        },
        Transform::IDENTITY.looking_at(-sun, Vec3::Y),
    ));
    for path in [RenderPath::Forward, RenderPath::Deferred] {
        set_path(&mut app, path);
        let scene = in_error_scopes(&mut app, "mirror ball", |app| {
            app.update()?;
            Ok(pom::capture_scene(app)?)
        })
        .unwrap();
        let radius_px = SIZE as f32 / 2.6;
        let centre = SIZE as f32 / 2.0;
        // Seen from `to_eye`, the ball's point at `offset` of its radius to the right has the
        // normal `offset · X + √(1 − offset²) · to_eye` and reflects the sky about it. The sun
        // lights the ball too, but a mirror reflects it only towards the sun. Within 7 %: the
        // shading's least roughness (0.03) blends a little of the next mip in, a slightly
        // wider lobe, which near the sun whitens the sky's blue.
        for offset in [0.0, 0.5, -0.5_f32] {
            let x = (centre + offset * radius_px) as u32;
            // The pixel's own centre.
            let offset = (x as f32 + 0.5 - centre) / radius_px;
            let normal = Vec3::X * offset + to_eye * (1.0 - offset * offset).sqrt();
            let reflected = 2.0 * normal.dot(to_eye) * normal - to_eye;
            let seen = Vec3::from_slice(&scene.get_pixel(x, SIZE / 2).0[..3]);
            let expected = cpu_sky(sun, lux, reflected);
            assert!(
                (seen - expected).abs().max_element() < 0.07 * expected.max_element(),
                "{path:?}: at {offset} of the radius the ball shows {seen}, the sky along \
                 {reflected} is {expected}"
            );
        }
        // The corner's view ray (orthographic: along −to_eye, down) sees the ground.
        let corner = Vec3::from_slice(&scene.get_pixel(0, 0).0[..3]);
        let expected = cpu_sky(sun, lux, -to_eye);
        assert!(
            (corner - expected).abs().max_element() < 0.01 * expected.max_element(),
            "{path:?}: the background shows {corner}, the ground there is {expected}"
        );
    }
}

/// The cobblestones, head-on, lit by the furnace alone; returns the pre-exposed scene with the
/// material's relief occlusion at `strength`.
fn cobblestones_in_a_furnace(strength: f32, path: RenderPath) -> image::Rgba32FImage {
    use pom::preview::PreviewView;
    use pom_tests::pom_scene::{HeightMaterial, preview_app};
    let textures = HeightMaterial {
        // Deep grout: the border between two domes is a V whose sides rise by a quarter of the
        // texture within a twentieth of it.
        field: pom::patterns::cobblestones(128, 2),
        height_scale: 0.25,
    };
    let mut app = preview_app(
        SIZE,
        TargetFormat::Float32,
        &textures,
        &PreviewView::default(),
        |material| pom::ParallaxOcclusionMaterial {
            relief_occlusion: strength,
            shadows: pom::ShadowMode::Off,
            ..material
        },
    )
    .unwrap();
    app.insert_resource(AmbientLight {
        color: Color::WHITE,
        intensity: 0.0,
    });
    for light in app.world.query_mut::<&mut pom::DirectionalLight>() {
        light.intensity = 0.0;
    }
    app.insert_resource(EnvironmentLight::uniform([FURNACE; 3]).with_settings(
        EnvironmentSettings {
            resolution: 32,
            ..EnvironmentSettings::default()
        },
    ));
    set_path(&mut app, path);
    in_error_scopes(&mut app, "relief occlusion", |app| {
        app.update()?;
        Ok(pom::capture_scene(app)?)
    })
    .unwrap()
}

#[test]
fn the_relief_darkens_the_sky_light_in_its_grout_and_leaves_the_tops_open() {
    for path in [RenderPath::Forward, RenderPath::Deferred] {
        let open = cobblestones_in_a_furnace(0.0, path);
        let occluded = cobblestones_in_a_furnace(1.0, path);
        let mut ratios: Vec<f32> = open
            .pixels()
            .zip(occluded.pixels())
            .map(|(open, occluded)| occluded.0[1] / open.0[1].max(1e-6))
            .collect();
        ratios.sort_by(f32::total_cmp);
        let (darkest, median, brightest) = (
            ratios[ratios.len() / 50],
            ratios[ratios.len() / 2],
            ratios[ratios.len() - 1],
        );
        println!(
            "{path:?}: occluded / open, 2nd percentile {darkest:.3}, median {median:.3}, brightest {brightest:.3}"
        );
        // Nothing is brightened; the grout loses much of the sky, the stones' tops little.
        assert!(brightest <= 1.0 + 1e-4, "{path:?}: {brightest}");
        assert!(
            darkest < 0.6,
            "{path:?}: the darkest grout keeps {darkest} of the sky"
        );
        assert!(ratios[ratios.len() * 9 / 10] > 0.9, "{path:?}: {ratios:?}");
    }
}

#[test]
fn a_bad_environment_file_is_an_error_naming_it() {
    let dir = pom_tests::gltf_fixture::scratch_dir("bad-environment");
    let missing = dir.join("missing.hdr");
    let message = EnvironmentLight::from_file(&missing)
        .unwrap_err()
        .to_string();
    assert!(message.contains("missing.hdr"), "{message}");
    let garbage = dir.join("garbage.hdr");
    std::fs::write(&garbage, b"#?RADIANCE\nnot really\n").unwrap();
    let message = EnvironmentLight::from_file(&garbage)
        .unwrap_err()
        .to_string();
    assert!(message.contains("garbage.hdr"), "{message}");
    let message = EnvironmentLight::from_file(&dir).unwrap_err().to_string();
    assert!(message.contains("not a regular file"), "{message}");
}

#[test]
fn an_hdr_file_lights_like_the_same_uniform_radiance() {
    let dir = pom_tests::gltf_fixture::scratch_dir("uniform-hdr");
    let path = dir.join("grey.hdr");
    let image = image::Rgb32FImage::from_pixel(64, 32, image::Rgb([FURNACE; 3]));
    image::DynamicImage::ImageRgb32F(image).save(&path).unwrap();
    let material = white(LightingModel::GgxLambert, 0.5, 1.0);
    let mut app = furnace(material, true).unwrap();
    app.insert_resource(EnvironmentLight::from_file(&path).unwrap().with_settings(
        EnvironmentSettings {
            resolution: 64,
            ..EnvironmentSettings::default()
        },
    ));
    let fraction = reflected_fraction(&mut app, RenderPath::Forward);
    assert!((0.95..=1.05).contains(&fraction), "{fraction}");
}

#[test]
fn a_script_lights_its_scene_with_an_environment_file_from_its_folder() {
    let dir = pom_tests::gltf_fixture::scratch_dir("script-environment");
    let image = image::Rgb32FImage::from_pixel(16, 8, image::Rgb([FURNACE; 3]));
    image::DynamicImage::ImageRgb32F(image)
        .save(dir.join("grey.hdr"))
        .unwrap();
    let script = dir.join("environment.ron");
    std::fs::write(
        &script,
        r#"(
    size: (32, 32),
    camera: (position: (0.0, 0.0, 3.0), target: (0.0, 0.0, 0.0), orthographic_height: 3.0),
    environment: (source: "grey.hdr", settings: (resolution: 16, intensity: 0.5)),
    steps: [Capture(name: "sky")],
)"#,
    )
    .unwrap();
    let report = pom::run_script_with(&script, &pom::RunOptions::default()).unwrap();
    assert_eq!(report.failures(), 0, "{report:?}");
    // Named outside the folder, the same file is refused before anything runs.
    let outside = dir.join("nested");
    std::fs::create_dir_all(&outside).unwrap();
    let text = std::fs::read_to_string(&script)
        .unwrap()
        .replace("grey.hdr", "../grey.hdr");
    std::fs::write(outside.join("environment.ron"), text).unwrap();
    let error = pom::run_script_with(outside.join("environment.ron"), &pom::RunOptions::default())
        .unwrap_err()
        .to_string();
    assert!(
        error.contains("grey.hdr") && error.contains("refused"),
        "{error}"
    );
}

#[test]
fn taa_settles_the_sky_behind_the_scene_like_any_other_pixel() {
    use pom::AntiAliasing;
    use pom_tests::anti_aliasing::{save_for_looking, settled};
    let mut app = App::new();
    app.add_plugin(RenderPlugin::new(96, 64))
        .add_plugin(pom::LitPlugin);
    app.finish().unwrap();
    app.insert_resource(EnvironmentLight::sky().with_settings(EnvironmentSettings {
        resolution: 32,
        ..EnvironmentSettings::default()
    }));
    let mesh = app
        .resources
        .get_mut::<Assets<Mesh>>()
        .unwrap()
        .add(Mesh::uv_sphere(1.0, 32, 16));
    app.world.spawn((
        Camera::perspective(50.0),
        Transform::from_xyz(0.0, 0.5, 4.0).looking_at(Vec3::new(0.0, 0.8, 0.0), Vec3::Y),
    ));
    app.world.spawn((
        pom::DirectionalLight::default(),
        Transform::IDENTITY.looking_at(Vec3::new(-0.3, -0.6, -0.5), Vec3::Y),
    ));
    app.world.spawn((
        mesh,
        white(LightingModel::GgxLambert, 0.3, 1.0),
        Transform::IDENTITY,
    ));
    for path in [RenderPath::Forward, RenderPath::Deferred] {
        set_path(&mut app, path);
        let still = settled(&mut app, AntiAliasing::Off);
        let accumulated = settled(&mut app, AntiAliasing::Taa);
        save_for_looking(&format!("sky-taa-{path:?}"), &accumulated);
        // The top rows are sky only: TAA's settled mean of a smooth sky is the sky.
        let mut largest = 0_i32;
        for x in 0..96 {
            for y in 0..6 {
                let (a, b) = (still.get_pixel(x, y).0, accumulated.get_pixel(x, y).0);
                for c in 0..3 {
                    largest = largest.max((i32::from(a[c]) - i32::from(b[c])).abs());
                }
            }
        }
        assert!(
            largest <= 3,
            "{path:?}: the settled sky differs by {largest}/255"
        );
        let sky = still.get_pixel(48, 2).0;
        assert!(
            sky[2] > sky[0] && sky[2] > 60,
            "{path:?}: the sky is {sky:?}"
        );
    }
}
