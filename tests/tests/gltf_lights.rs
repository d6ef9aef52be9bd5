//! glTF lights as authored: `KHR_lights_punctual` in physical units (lux, candela),
//! no range = unbounded, spot cones, and bad values clamped with one warning each.

use glam::Vec3;
use pom::{App, Camera, DirectionalLight, LitMaterial, TargetFormat, Transform, load_gltf};
use pom_tests::gltf_fixture::{GltfFixture, scratch_dir};
use pom_tests::pom_scene::pom_app;
use pom_tests::{FlipTolerance, check_golden, render_both_paths};
use serde_json::json;

fn app(size: u32) -> App {
    pom_app(size, TargetFormat::Srgb8).unwrap()
}

#[test]
fn a_point_light_without_range_reaches_a_floor_fifty_units_away() {
    let dir = scratch_dir("unbounded-point");
    let mut fixture = GltfFixture::quad(200.0);
    fixture.json["extensionsUsed"] = json!(["KHR_lights_punctual"]);
    fixture.json["extensions"] = json!({"KHR_lights_punctual": {"lights": [
        {"type": "point", "intensity": 2500.0}
    ]}});
    fixture.json["nodes"] = json!([
        {"name": "floor", "mesh": 0},
        {"name": "bulb", "translation": [0.0, 50.0, 0.0],
         "extensions": {"KHR_lights_punctual": {"light": 0}}}
    ]);
    fixture.json["scenes"] = json!([{"nodes": [0, 1]}]);
    let mut app = app(48);
    let scene = load_gltf(&mut app, fixture.write(&dir, "bulb")).unwrap();
    assert!(scene.warnings.is_empty(), "{:?}", scene.warnings);
    let range = app
        .world
        .query::<&pom::PointLight>()
        .iter()
        .map(|light| light.range)
        .next();
    assert_eq!(range, Some(f32::INFINITY));
    *app.resources.get_mut::<pom::AmbientLight>().unwrap() = pom::AmbientLight {
        color: pom::Color::WHITE,
        intensity: 0.0,
    };
    // A night exposure: 2,500 cd at 50 m is 1 lux on the floor below.
    app.world.spawn((
        Camera::perspective(60.0),
        pom::Exposure { ev100: -2.0 },
        Transform::from_xyz(0.0, 30.0, 40.0).looking_at(Vec3::ZERO, Vec3::Y),
    ));
    let image = render_both_paths(&mut app, "gltf_unbounded_point_light").unwrap();
    // Under the bulb the floor is lit, fading outwards; without the fix the 20-unit default
    // range left it black.
    let (under, edge) = (image.get_pixel(24, 30).0, image.get_pixel(2, 47).0);
    assert!(under[1] > 150, "{under:?}");
    assert!(edge[1] < under[1], "{edge:?} vs {under:?}");
    check_golden(
        "gltf_unbounded_point_light",
        &image,
        FlipTolerance::default(),
    )
    .unwrap();
}

#[test]
fn a_light_with_a_negative_intensity_is_clamped_with_one_warning() {
    let dir = scratch_dir("negative-light");
    let mut fixture = GltfFixture::quad(1.0);
    fixture.json["extensionsUsed"] = json!(["KHR_lights_punctual"]);
    fixture.json["extensions"] = json!({"KHR_lights_punctual": {"lights": [
        {"type": "directional", "intensity": -5.0}
    ]}});
    fixture.json["nodes"] = json!([
        {"name": "quad", "mesh": 0},
        {"name": "sun", "extensions": {"KHR_lights_punctual": {"light": 0}}}
    ]);
    fixture.json["scenes"] = json!([{"nodes": [0, 1]}]);
    let mut app = app(8);
    let scene = load_gltf(&mut app, fixture.write(&dir, "negative")).unwrap();
    assert_eq!(scene.warnings.len(), 1, "{:?}", scene.warnings);
    assert!(scene.warnings[0].contains("\"sun\"") && scene.warnings[0].contains("-5"));
    let intensities: Vec<f32> = app
        .world
        .query::<&DirectionalLight>()
        .iter()
        .map(|light| light.intensity)
        .collect();
    assert_eq!(intensities, [0.0]);
}

#[test]
fn a_box_in_a_real_sun_does_not_clip_at_the_default_exposure() {
    // The file brings a 100,000 lux sun (bright daylight), as glTF states it; a white box of
    // albedo 0.9 stands in it, seen from its lit side.
    let dir = scratch_dir("real-sun");
    let mut fixture = GltfFixture::quad(0.1);
    fixture.json["extensionsUsed"] = json!(["KHR_lights_punctual"]);
    fixture.json["extensions"] = json!({"KHR_lights_punctual": {"lights": [
        {"type": "directional", "intensity": 100000.0}
    ]}});
    fixture.json["nodes"] = json!([
        {"name": "sun", "rotation": [-0.3535534, 0.3535534, 0.1464466, 0.8535534],
         "extensions": {"KHR_lights_punctual": {"light": 0}}}
    ]);
    fixture.json["scenes"] = json!([{"nodes": [0]}]);
    let mut app = app(64);
    load_gltf(&mut app, fixture.write(&dir, "sun")).unwrap();
    let cube = app
        .resources
        .get_mut::<pom::Assets<pom::Mesh>>()
        .unwrap()
        .add(pom::Mesh::cube(1.0));
    app.world.spawn((
        cube,
        LitMaterial::from_color(pom::Color::linear_rgb(0.9, 0.9, 0.9)),
        Transform::IDENTITY,
    ));
    app.world.spawn((
        Camera::perspective(45.0),
        Transform::from_xyz(1.8, 1.6, 2.4).looking_at(Vec3::ZERO, Vec3::Y),
    ));
    let image = render_both_paths(&mut app, "gltf_real_sun_box").unwrap();
    let background = *image.get_pixel(0, 0);
    let lit: Vec<_> = image.pixels().filter(|p| **p != background).collect();
    let clipped = lit.iter().filter(|p| p.0[..3].contains(&255)).count();
    eprintln!("{} box pixels, {clipped} clipped", lit.len());
    assert!(lit.len() > 500);
    assert!(
        clipped as f32 <= 0.01 * lit.len() as f32,
        "{clipped} of {}",
        lit.len()
    );
    // And it is daylight, not dusk: the sunlit faces are bright.
    assert!(lit.iter().any(|p| p.0[0] > 200), "nothing bright");
    check_golden("gltf_real_sun_box", &image, FlipTolerance::default()).unwrap();
}

#[test]
fn a_spot_lights_the_floor_out_to_its_outer_cone() {
    // A 400,000 cd spot 2 m above a white floor, pointing down: inner 20°, outer 30°, so the
    // lit disc ends 2 · tan 30° = 1.155 m from the centre, fading from 2 · tan 20° = 0.728 m.
    let dir = scratch_dir("spot");
    let mut fixture = GltfFixture::quad(6.0);
    fixture.json["extensionsUsed"] = json!(["KHR_lights_punctual"]);
    let (inner, outer) = (20_f32.to_radians(), 30_f32.to_radians());
    fixture.json["extensions"] = json!({"KHR_lights_punctual": {"lights": [
        {"type": "spot", "intensity": 400000.0,
         "spot": {"innerConeAngle": inner, "outerConeAngle": outer}}
    ]}});
    // Pointing down: −Z turned onto −Y (a quarter turn about X).
    fixture.json["nodes"] = json!([
        {"name": "floor", "mesh": 0},
        {"name": "spot", "translation": [0.0, 2.0, 0.0],
         "rotation": [-std::f32::consts::FRAC_1_SQRT_2, 0.0, 0.0, std::f32::consts::FRAC_1_SQRT_2],
         "extensions": {"KHR_lights_punctual": {"light": 0}}}
    ]);
    fixture.json["scenes"] = json!([{"nodes": [0, 1]}]);
    let mut app = app(64);
    let scene = load_gltf(&mut app, fixture.write(&dir, "spot")).unwrap();
    assert!(scene.warnings.is_empty(), "{:?}", scene.warnings);
    *app.resources.get_mut::<pom::AmbientLight>().unwrap() = pom::AmbientLight {
        color: pom::Color::WHITE,
        intensity: 0.0,
    };
    // Straight down, 4 m across 64 pixels: 16 pixels per metre, the spot under pixel (32, 32).
    app.world.spawn((
        Camera::orthographic(4.0),
        Transform::from_xyz(0.0, 5.0, 0.0).looking_at(Vec3::ZERO, Vec3::NEG_Z),
    ));
    let image = render_both_paths(&mut app, "gltf_spot_light").unwrap();
    let green = |x: u32| image.get_pixel(x, 32).0[1];
    let centre = green(32);
    // Pixel centres along +x: radius (x − 32 + 0.5) / 16 m.
    let lit_out_to = (32..64).take_while(|&x| green(x) > 0).last().unwrap();
    let edge = (f32::from(lit_out_to as u16) - 32.0 + 0.5) / 16.0;
    eprintln!("centre {centre}, lit out to {edge:.3} m (cone: 1.155 m)");
    assert!(centre > 200, "{centre}");
    assert!((edge - 2.0 * outer.tan()).abs() < 1.5 / 16.0, "{edge}");
    // Full strength inside the inner cone (nearly: the distance grows a little), fading past it.
    let at = |radius: f32| green((32.0 + radius * 16.0) as u32);
    assert!(at(0.5) as f32 > 0.9 * centre as f32, "{}", at(0.5));
    assert!(
        at(0.95) < at(0.7) && at(0.95) > 0,
        "{} {}",
        at(0.95),
        at(0.7)
    );
    check_golden("gltf_spot_light", &image, FlipTolerance::default()).unwrap();
}

#[test]
fn a_spot_whose_inner_angle_exceeds_its_outer_is_clamped_with_one_warning() {
    let dir = scratch_dir("bad-spot");
    let mut fixture = GltfFixture::quad(1.0);
    fixture.json["extensionsUsed"] = json!(["KHR_lights_punctual"]);
    fixture.json["extensions"] = json!({"KHR_lights_punctual": {"lights": [
        {"type": "spot", "intensity": 100.0, "spot": {"innerConeAngle": 0.6, "outerConeAngle": 0.4}}
    ]}});
    fixture.json["nodes"] = json!([
        {"name": "quad", "mesh": 0},
        {"name": "lamp", "extensions": {"KHR_lights_punctual": {"light": 0}}}
    ]);
    fixture.json["scenes"] = json!([{"nodes": [0, 1]}]);
    let mut app = app(8);
    // The inner angle is clamped to the outer with one warning naming the node.
    let scene = load_gltf(&mut app, fixture.write(&dir, "bad_spot")).unwrap();
    assert_eq!(scene.warnings.len(), 1, "{:?}", scene.warnings);
    assert!(
        scene.warnings[0].contains("\"lamp\""),
        "{:?}",
        scene.warnings
    );
    let cones: Vec<(f32, f32)> = app
        .world
        .query::<&pom::SpotLight>()
        .iter()
        .map(|spot| (spot.inner_angle, spot.outer_angle))
        .collect();
    assert_eq!(cones, [(0.4, 0.4)]);
}
