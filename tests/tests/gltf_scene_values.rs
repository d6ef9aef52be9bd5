//! NaN, infinity and absurd numbers in a glTF scene's data: each is an error naming the file,
//! the element and the field, or a fix with a warning naming them; never a silently wrong
//! picture. Loading needs no GPU.

use glam::Quat;
use pom::{
    App, Camera, DirectionalLight, GltfError, Handle, MAX_LIGHT_OUTPUT, Mesh, PointLight,
    PomPlugin, RenderPlugin, Transform, load_gltf,
};
use pom_tests::gltf_fixture::{GltfFixture, png, scratch_dir};
use serde_json::json;

fn app() -> App {
    let mut app = App::new();
    app.add_plugin(RenderPlugin::new(16, 16))
        .add_plugin(PomPlugin);
    app
}

/// Byte offsets of the quad fixture's attributes in its buffer (four vertices each).
const NORMALS: usize = 4 * 12;
const UVS: usize = NORMALS + 4 * 12;
const TANGENTS: usize = UVS + 4 * 8;

fn put_f32(fixture: &mut GltfFixture, offset: usize, value: f32) {
    fixture.bin[offset..offset + 4].copy_from_slice(&value.to_le_bytes());
}

/// Loads `fixture` (written as `NAME.gltf`) and returns the error, whose message must name
/// the file and hold every one of `needles`; nothing may stay loaded.
fn load_error(fixture: &GltfFixture, name: &str, needles: &[&str]) -> GltfError {
    let dir = scratch_dir(name);
    let mut app = app();
    let error = load_gltf(&mut app, fixture.write(&dir, name)).unwrap_err();
    let message = error.to_string();
    for needle in [&format!("{name}.gltf")[..]].iter().chain(needles) {
        assert!(
            message.contains(needle),
            "{message:?} should name {needle:?}"
        );
    }
    assert_eq!(app.world.len(), 0, "nothing half-loaded stays behind");
    error
}

/// Loads `fixture` and returns the app and the load's warnings.
fn load_with_warnings(fixture: &GltfFixture, name: &str) -> (App, Vec<String>) {
    let dir = scratch_dir(name);
    let mut app = app();
    let scene = load_gltf(&mut app, fixture.write(&dir, name)).unwrap();
    (app, scene.warnings)
}

/// The one warning of `warnings`, which must hold every one of `needles`.
fn assert_one_warning(warnings: &[String], needles: &[&str]) {
    assert_eq!(warnings.len(), 1, "{warnings:?}");
    for needle in needles {
        assert!(
            warnings[0].contains(needle),
            "{warnings:?} should name {needle:?}"
        );
    }
}

#[test]
fn a_nan_normal_is_an_error_naming_the_mesh_primitive_and_attribute() {
    let mut fixture = GltfFixture::quad(1.0);
    put_f32(&mut fixture, NORMALS + 2 * 12 + 4, f32::NAN);
    load_error(
        &fixture,
        "nan-normal",
        &[
            "mesh \"quad\" (#0), primitive 0",
            "NORMAL of vertex 2 is not finite",
        ],
    );
}

#[test]
fn a_nan_texture_coordinate_in_a_glb_is_an_error_naming_the_attribute() {
    let mut fixture = GltfFixture::quad(1.0);
    put_f32(&mut fixture, UVS + 8, f32::NAN);
    let dir = scratch_dir("nan-uv");
    let mut app = app();
    let error = load_gltf(&mut app, fixture.write_glb(&dir, "nan-uv"))
        .unwrap_err()
        .to_string();
    for needle in ["nan-uv.glb", "primitive 0", "TEXCOORD_0", "vertex 1"] {
        assert!(error.contains(needle), "{error:?} should name {needle:?}");
    }
}

#[test]
fn an_infinite_tangent_is_an_error_naming_the_attribute() {
    let mut fixture = GltfFixture::quad(1.0);
    put_f32(&mut fixture, TANGENTS + 3 * 16, f32::INFINITY);
    load_error(
        &fixture,
        "inf-tangent",
        &["TANGENT of vertex 3 is not finite"],
    );
}

#[test]
fn a_texture_transform_of_1e38_is_an_error_naming_the_material_and_field() {
    let mut fixture = GltfFixture::quad(1.0);
    let texture = fixture.add_texture(
        "albedo.png",
        png(&image::RgbaImage::from_pixel(
            2,
            2,
            image::Rgba([9, 9, 9, 255]),
        )),
    );
    fixture.json["extensionsUsed"] = json!(["KHR_texture_transform"]);
    fixture.json["materials"][0]["pbrMetallicRoughness"] = json!({"baseColorTexture": {
        "index": texture,
        "extensions": {"KHR_texture_transform": {"scale": [1e38, 1.0]}}
    }});
    let error = load_error(
        &fixture,
        "huge-transform",
        &["material \"surface\" (#0)", "KHR_texture_transform scale"],
    );
    assert!(matches!(error, GltfError::Material { .. }), "{error:?}");
}

#[test]
fn a_sparse_index_past_the_vertex_count_is_an_error_naming_the_accessor() {
    let mut fixture = GltfFixture::quad(1.0);
    let indices = fixture.bin.len();
    fixture.bin.extend_from_slice(&[9, 0, 0, 0]);
    let values = fixture.bin.len();
    for value in [5.0_f32, 5.0, 5.0] {
        fixture.bin.extend_from_slice(&value.to_le_bytes());
    }
    let views = fixture.json["bufferViews"].as_array_mut().unwrap();
    views.push(json!({"buffer": 0, "byteOffset": indices, "byteLength": 2}));
    views.push(json!({"buffer": 0, "byteOffset": values, "byteLength": 12}));
    let (index_view, value_view) = (views.len() - 2, views.len() - 1);
    fixture.json["accessors"][0]["sparse"] = json!({
        "count": 1,
        "indices": {"bufferView": index_view, "componentType": 5123},
        "values": {"bufferView": value_view}
    });
    fixture.json["buffers"][0]["byteLength"] = json!(fixture.bin.len());
    load_error(
        &fixture,
        "sparse-past",
        &["accessor 0: sparse index 9 (entry 0) is past its 4 elements"],
    );
}

/// The quad plus lights `lights` (`KHR_lights_punctual`), one node each named `light N`.
fn with_lights(lights: serde_json::Value) -> GltfFixture {
    let mut fixture = GltfFixture::quad(1.0);
    let count = lights.as_array().unwrap().len();
    fixture.json["extensionsUsed"] = json!(["KHR_lights_punctual"]);
    fixture.json["extensions"] = json!({"KHR_lights_punctual": {"lights": lights}});
    let nodes = fixture.json["nodes"].as_array_mut().unwrap();
    for light in 0..count {
        nodes.push(json!({"name": format!("light {light}"),
            "extensions": {"KHR_lights_punctual": {"light": light}}}));
    }
    fixture.json["scenes"][0]["nodes"] = json!((0..=count).collect::<Vec<_>>());
    fixture
}

#[test]
fn a_light_of_intensity_or_colour_1e38_is_clamped_with_a_warning_each() {
    let fixture = with_lights(json!([
        {"type": "directional", "intensity": 1e38},
        {"type": "point", "intensity": 1.0, "color": [1e38, 0.5, 0.5]}
    ]));
    let (app, warnings) = load_with_warnings(&fixture, "bright-lights");
    assert_eq!(warnings.len(), 2, "{warnings:?}");
    assert!(
        warnings[0].contains("\"light 0\"") && warnings[0].contains("intensity 1e38"),
        "{warnings:?}"
    );
    assert!(
        warnings[1].contains("\"light 1\"") && warnings[1].contains("color [1e38"),
        "{warnings:?}"
    );
    let output = |color: pom::Color, intensity: f32| color.r.max(color.g).max(color.b) * intensity;
    let sun = app
        .world
        .query::<&DirectionalLight>()
        .iter()
        .next()
        .copied()
        .unwrap();
    let bulb = app
        .world
        .query::<&PointLight>()
        .iter()
        .next()
        .copied()
        .unwrap();
    for value in [
        output(sun.color, sun.intensity),
        output(bulb.color, bulb.intensity),
    ] {
        assert!(value > 0.0 && value <= MAX_LIGHT_OUTPUT, "{value}");
    }
}

/// The quad's node with `transform` (glTF node fields) in place of none.
fn placed_quad(transform: serde_json::Value) -> GltfFixture {
    let mut fixture = GltfFixture::quad(1.0);
    let node = fixture.json["nodes"][0].as_object_mut().unwrap();
    node.extend(transform.as_object().unwrap().clone());
    fixture
}

fn mesh_count(app: &App) -> usize {
    app.world.query::<&Handle<Mesh>>().iter().count()
}

#[test]
fn a_node_matrix_of_3e38_or_zeros_or_a_zero_scale_leaves_the_node_out_with_a_warning() {
    let zeros = [0.0_f32; 16];
    let huge = [
        3e38_f32, 0.0, 0.0, 0.0, 0.0, 3e38, 0.0, 0.0, 0.0, 0.0, 3e38, 0.0, 0.0, 0.0, 0.0, 1.0,
    ];
    for (name, transform, needle) in [
        ("huge-matrix", json!({"matrix": huge}), "matrix"),
        ("zero-matrix", json!({"matrix": zeros}), "matrix"),
        ("zero-scale", json!({"scale": [1.0, 0.0, 1.0]}), "scale"),
    ] {
        let (app, warnings) = load_with_warnings(&placed_quad(transform), name);
        assert_one_warning(&warnings, &["node \"quad\" (#0)", needle, "left out"]);
        assert_eq!(mesh_count(&app), 0, "{name}: the node is not drawn");
    }
}

#[test]
fn a_child_whose_world_transform_overflows_is_left_out_with_a_warning() {
    // Each scale alone is fine; their product (1e24, a determinant of 1e72) overflows f32.
    let mut fixture = placed_quad(json!({"scale": [1e12, 1e12, 1e12]}));
    fixture.json["scenes"][0]["nodes"] = json!([1]);
    fixture.json["nodes"]
        .as_array_mut()
        .unwrap()
        .push(json!({"name": "giant", "scale": [1e12, 1e12, 1e12], "children": [0]}));
    let (app, warnings) = load_with_warnings(&fixture, "overflowing-world");
    assert_one_warning(
        &warnings,
        &["node \"quad\" (#0)", "world transform", "left out"],
    );
    assert_eq!(mesh_count(&app), 0);
}

#[test]
fn a_zero_rotation_is_replaced_by_none_with_a_warning() {
    let fixture = placed_quad(json!({"rotation": [0.0, 0.0, 0.0, 0.0]}));
    let (app, warnings) = load_with_warnings(&fixture, "zero-rotation");
    assert_one_warning(
        &warnings,
        &["node \"quad\" (#0)", "rotation [0.0, 0.0, 0.0, 0.0]"],
    );
    let rotations: Vec<Quat> = app
        .world
        .query::<(&Transform, &Handle<Mesh>)>()
        .iter()
        .map(|(transform, _)| transform.rotation)
        .collect();
    assert_eq!(rotations, [Quat::IDENTITY]);
}

/// The quad with a node looking through `camera` (a glTF camera).
fn with_camera(camera: serde_json::Value) -> GltfFixture {
    let mut fixture = GltfFixture::quad(1.0);
    fixture.json["cameras"] = json!([camera]);
    fixture.json["nodes"]
        .as_array_mut()
        .unwrap()
        .push(json!({"name": "eye", "camera": 0}));
    fixture.json["scenes"][0]["nodes"] = json!([0, 1]);
    fixture
}

#[test]
fn a_camera_with_yfov_0_or_zfar_under_znear_is_an_error_naming_it() {
    for (name, perspective, needle) in [
        (
            "zero-fov",
            json!({"yfov": 0.0, "znear": 0.1}),
            "perspective.yfov 0",
        ),
        (
            "far-under-near",
            json!({"yfov": 0.8, "znear": 10.0, "zfar": 1.0}),
            "perspective.zfar 1",
        ),
    ] {
        let fixture =
            with_camera(json!({"name": "view", "type": "perspective", "perspective": perspective}));
        let error = load_error(&fixture, name, &["camera \"view\" (#0)", needle]);
        assert!(matches!(error, GltfError::Camera { .. }), "{error:?}");
    }
    // The same file with a usable camera loads, so the errors above are the camera's.
    let fixture =
        with_camera(json!({"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.1}}));
    let (app, warnings) = load_with_warnings(&fixture, "usable-camera");
    assert!(warnings.is_empty(), "{warnings:?}");
    assert_eq!(app.world.query::<&Camera>().iter().count(), 1);
}

#[test]
fn a_glb_whose_header_length_is_short_of_the_file_gives_a_warning_naming_both() {
    let dir = scratch_dir("short-header");
    let path = GltfFixture::quad(1.0).write_glb(&dir, "short-header");
    let mut bytes = std::fs::read(&path).unwrap();
    let actual = bytes.len();
    let declared = (actual - 8) as u32;
    bytes[8..12].copy_from_slice(&declared.to_le_bytes());
    std::fs::write(&path, bytes).unwrap();
    let mut app = app();
    let scene = load_gltf(&mut app, &path).unwrap();
    assert_one_warning(
        &scene.warnings,
        &[
            "short-header.glb",
            &format!("{declared} bytes"),
            &format!("holds {actual}"),
        ],
    );
}

#[test]
fn a_camera_exposure_out_of_range_is_an_error_naming_it_and_one_in_range_is_used() {
    let camera = |exposure: serde_json::Value| {
        with_camera(json!({"name": "night", "type": "perspective",
            "perspective": {"yfov": 0.8, "znear": 0.1}, "extras": {"pom": {"exposure": exposure}}}))
    };
    for (name, exposure, needle) in [
        (
            "exposure-too-bright",
            json!(40.0),
            "extras.pom.exposure 40.0",
        ),
        (
            "exposure-not-a-number",
            json!("dark"),
            "extras.pom.exposure \"dark\"",
        ),
    ] {
        let error = load_error(
            &camera(exposure),
            name,
            &["camera \"night\" (#0)", needle, "-16..=24"],
        );
        assert!(matches!(error, GltfError::Camera { .. }), "{error:?}");
    }
    let (app, warnings) = load_with_warnings(&camera(json!(6.5)), "exposure-at-night");
    assert!(warnings.is_empty(), "{warnings:?}");
    let exposures: Vec<f32> = app
        .world
        .query::<&pom::Exposure>()
        .iter()
        .map(|exposure| exposure.ev100)
        .collect();
    assert_eq!(exposures, [6.5]);
}

#[test]
fn a_scene_ambient_light_is_used_and_a_bad_one_ignored_with_a_warning() {
    let with_ambient = |ambient: serde_json::Value| {
        let mut fixture = GltfFixture::quad(1.0);
        fixture.json["scenes"][0]["extras"] = json!({"pom": {"ambient": ambient}});
        fixture
    };
    let night = json!({"color": [0.35, 0.45, 0.8], "intensity": 3.0});
    let (app, warnings) = load_with_warnings(&with_ambient(night), "ambient-at-night");
    assert!(warnings.is_empty(), "{warnings:?}");
    let ambient = app.resources.get::<pom::AmbientLight>().copied().unwrap();
    assert_eq!(ambient.intensity, 3.0);
    assert_eq!(ambient.color, pom::Color::linear_rgb(0.35, 0.45, 0.8));
    for (name, bad) in [
        (
            "ambient-negative",
            json!({"color": [1.0, 1.0, 1.0], "intensity": -2.0}),
        ),
        (
            "ambient-two-channels",
            json!({"color": [1.0, 1.0], "intensity": 2.0}),
        ),
    ] {
        let (app, warnings) = load_with_warnings(&with_ambient(bad), name);
        assert_one_warning(&warnings, &["extras.pom.ambient", "ignored"]);
        assert_ne!(
            app.resources
                .get::<pom::AmbientLight>()
                .map(|a| a.intensity),
            Some(-2.0)
        );
    }
}
