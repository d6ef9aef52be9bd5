//! glTF files render as their authors meant them (issue 17): each feature on a small scene the
//! test writes itself, with a reference image where the look matters.

use glam::Vec3;
use pom::{
    App, Camera, DirectionalLight, LitMaterial, PomPlugin, RenderPlugin, Tonemapping, Transform,
    load_gltf,
};
use pom_tests::gltf_fixture::{GltfFixture, scratch_dir};
use pom_tests::{FlipTolerance, check_golden, render_and_capture};
use serde_json::json;

fn app(size: u32) -> App {
    let mut app = App::new();
    app.add_plugin(RenderPlugin::headless(size, size))
        .add_plugin(PomPlugin);
    app
}

/// The fixture's quad (facing +Y) seen from below, lit from below, `double_sided` or not.
fn quad_from_behind(double_sided: bool) -> image::RgbaImage {
    let dir = scratch_dir(&format!("double-sided-{double_sided}"));
    let mut fixture = GltfFixture::quad(1.0);
    fixture.json["materials"][0] = json!({
        "name": "orange",
        "doubleSided": double_sided,
        "pbrMetallicRoughness": {"baseColorFactor": [0.9, 0.4, 0.1, 1.0], "roughness": 0.6}
    });
    let mut app = app(64);
    load_gltf(&mut app, fixture.write(&dir, "quad")).unwrap();
    assert_eq!(
        app.world
            .query::<&LitMaterial>()
            .iter()
            .map(|material| material.double_sided)
            .collect::<Vec<_>>(),
        [double_sided]
    );
    app.world.spawn((
        Camera::perspective(50.0),
        Tonemapping::None,
        Transform::from_xyz(0.3, -1.4, 0.4).looking_at(Vec3::ZERO, Vec3::Z),
    ));
    // The light shines up onto the back: only a reversed normal faces it.
    app.world.spawn((
        DirectionalLight::default(),
        Transform::IDENTITY.looking_at(Vec3::new(0.2, 1.0, 0.1), Vec3::Z),
    ));
    render_and_capture(&mut app).unwrap()
}

#[test]
fn a_double_sided_quad_seen_from_behind() {
    let culled = quad_from_behind(false);
    let background = *culled.get_pixel(0, 0);
    assert!(
        culled.pixels().all(|p| *p == background),
        "a single-sided quad's back is culled"
    );
    let image = quad_from_behind(true);
    let centre = image.get_pixel(32, 32).0;
    // Lit from the side it shows: the orange is bright, red over green over blue.
    assert!(
        centre[0] > 150 && centre[0] > centre[1] && centre[1] > centre[2],
        "{centre:?}"
    );
    check_golden("gltf_double_sided_back", &image, FlipTolerance::default()).unwrap();
}

#[test]
fn the_first_camera_node_is_the_one_looked_through() {
    let dir = scratch_dir("two-cameras");
    let mut fixture = GltfFixture::quad(1.0);
    // Camera nodes: a parent with one child camera, listed after a sibling camera; the walk is
    // depth first, parents before children, siblings in file order.
    fixture.json["cameras"] = json!([
        {"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.1}},
        {"type": "orthographic", "orthographic": {"xmag": 1.0, "ymag": 1.0, "znear": 0.1, "zfar": 10.0}}
    ]);
    fixture.json["nodes"] = json!([
        {"name": "quad", "mesh": 0},
        {"name": "rig", "children": [2]},
        {"name": "near", "camera": 1, "translation": [0.0, 2.0, 0.0]},
        {"name": "far", "camera": 0, "translation": [0.0, 5.0, 5.0]}
    ]);
    fixture.json["scenes"] = json!([{"nodes": [0, 1, 3]}]);
    let mut app = app(16);
    let scene = load_gltf(&mut app, fixture.write(&dir, "cameras")).unwrap();
    let names = |app: &App| -> Vec<(String, bool)> {
        scene
            .cameras
            .iter()
            .map(|&entity| {
                let name = app.world.get::<&pom::Name>(entity).unwrap().0.clone();
                (name, app.world.get::<&Camera>(entity).unwrap().active)
            })
            .collect()
    };
    assert_eq!(
        names(&app),
        [("near".to_owned(), true), ("far".to_owned(), false)]
    );
    assert!(scene.activate_camera(&mut app.world, Some(1)));
    assert_eq!(
        names(&app),
        [("near".to_owned(), false), ("far".to_owned(), true)]
    );
    assert!(
        !scene.activate_camera(&mut app.world, Some(2)),
        "no third camera"
    );
    assert!(scene.activate_camera(&mut app.world, None));
    assert!(names(&app).iter().all(|(_, active)| !active));
}
