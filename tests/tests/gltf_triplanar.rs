//! Triplanar parallax from glTF `extras.pom`: its keys load, a mesh without texture coordinates
//! is fine, one without normals is warned about by name, and bad values are errors naming the
//! material and the key.

use image::{GrayImage, Luma};
use pom::{App, ParallaxOcclusionMaterial, PomPlugin, RenderPlugin, TextureMapping, load_gltf};
use pom_tests::gltf_fixture::{GltfFixture, png, scratch_dir};
use pom_tests::run_frames;
use serde_json::{Value, json};

fn app() -> App {
    let mut app = App::new();
    app.add_plugin(RenderPlugin::new(32, 32))
        .add_plugin(PomPlugin);
    app
}

/// A quad without texture coordinates or tangents (and without normals unless `normals`) whose
/// material's `extras.pom` is a height map and `keys`.
fn triplanar_quad(keys: Value, normals: bool) -> GltfFixture {
    let mut fixture = GltfFixture::quad(1.0);
    let attributes = &mut fixture.json["meshes"][0]["primitives"][0]["attributes"];
    let attributes = attributes.as_object_mut().expect("attributes");
    attributes.remove("TEXCOORD_0");
    attributes.remove("TANGENT");
    if !normals {
        attributes.remove("NORMAL");
    }
    let field = GrayImage::from_fn(8, 8, |x, y| Luma([((x + y) * 16) as u8]));
    let height = fixture.add_texture("height.png", png(&field));
    let mut pom = json!({"height_texture": height, "height_scale": 0.05});
    if let (Value::Object(pom), Value::Object(keys)) = (&mut pom, keys) {
        pom.extend(keys);
    }
    fixture.json["materials"][0]["extras"] = json!({ "pom": pom });
    fixture
}

fn load(fixture: &GltfFixture, test: &str) -> (App, pom::GltfScene) {
    let dir = scratch_dir(test);
    let mut app = app();
    let scene = load_gltf(&mut app, fixture.write(&dir, test)).expect("loads");
    (app, scene)
}

fn material(app: &App) -> ParallaxOcclusionMaterial {
    app.world
        .query::<&ParallaxOcclusionMaterial>()
        .iter()
        .next()
        .cloned()
        .expect("a parallax material")
}

#[test]
fn the_triplanar_keys_load_on_a_mesh_without_texture_coordinates_and_it_draws() {
    let keys = json!({"mapping": "triplanar", "triplanar_scale": 2.5, "triplanar_sharpness": 8});
    let (mut app, scene) = load(&triplanar_quad(keys, true), "triplanar-keys");
    assert!(scene.warnings.is_empty(), "{:?}", scene.warnings);
    let material = material(&app);
    assert_eq!(material.mapping, TextureMapping::Triplanar);
    assert_eq!(
        (material.triplanar_scale, material.triplanar_sharpness),
        (2.5, 8.0)
    );
    run_frames(&mut app, 2).expect("draws");
}

#[test]
fn a_mesh_without_normals_under_triplanar_mapping_is_warned_about_by_name() {
    let (_, scene) = load(
        &triplanar_quad(json!({"mapping": "triplanar"}), false),
        "triplanar-no-normals",
    );
    assert_eq!(scene.warnings.len(), 1, "{:?}", scene.warnings);
    let warning = &scene.warnings[0];
    assert!(
        warning.contains("mesh \"quad\"") && warning.contains("no NORMAL under triplanar mapping"),
        "{warning}"
    );
    // Under uv mapping the flat normals are no problem of the mix.
    let (_, scene) = load(&triplanar_quad(json!({}), false), "uv-no-normals");
    assert!(scene.warnings.is_empty(), "{:?}", scene.warnings);
}

#[test]
fn bad_triplanar_values_are_errors_naming_the_material_and_the_key() {
    for (test, keys, needle) in [
        (
            "triplanar-negative-scale",
            json!({"mapping": "triplanar", "triplanar_scale": -1.0}),
            "triplanar_scale is -1 but must be at least 0.001",
        ),
        (
            "triplanar-sharpness-too-high",
            json!({"mapping": "triplanar", "triplanar_sharpness": 100}),
            "triplanar_sharpness is 100 but must be at most 64",
        ),
        (
            "triplanar-unknown-mapping",
            json!({"mapping": "cubic"}),
            "mapping",
        ),
    ] {
        let error = triplanar_quad(keys, true).load_error(&mut app(), test, needle);
        assert!(error.contains("material \"surface\" (#0)"), "{error}");
    }
}
