//! Loading glTF scenes: every loader path and every error case.

use glam::{Vec2, Vec3};
use image::{GrayImage, ImageBuffer, Luma, RgbaImage};
use pom::{
    App, Assets, DirectionalLight, GlobalTransform, Handle, HeightConvention, HeightSource, Image,
    LitMaterial, Mesh, ParallaxMethod, ParallaxOcclusionMaterial, Pixels, PomPlugin, RenderPlugin,
    ShadowMode, load_gltf,
};
use pom_tests::gltf_fixture::{GltfFixture, png, scratch_dir};
use pom_tests::run_frames;
use serde_json::json;

fn app() -> App {
    let mut app = App::new();
    app.add_plugin(RenderPlugin::new(64, 64))
        .add_plugin(PomPlugin);
    app
}

fn height_png_16(width: u32, height: u32) -> Vec<u8> {
    png(&ImageBuffer::from_fn(width, height, |x, y| {
        Luma([((x * 977 + y * 131) % 65536) as u16])
    }))
}

fn pom_quad(extras: serde_json::Value) -> GltfFixture {
    let mut fixture = GltfFixture::quad(1.0);
    let normal = fixture.add_texture(
        "normal.png",
        png(&RgbaImage::from_pixel(
            4,
            4,
            image::Rgba([128, 128, 255, 200]),
        )),
    );
    fixture.json["materials"][0]["normalTexture"] = json!({"index": normal});
    let mut extras = extras;
    if extras.get("height_texture") == Some(&json!("HEIGHT")) {
        let height = fixture.add_texture("height.png", height_png_16(48, 40));
        extras["height_texture"] = json!(height);
    }
    fixture.json["materials"][0]["extras"] = json!({"pom": extras});
    fixture
}

fn only<T: Clone + Send + Sync + 'static>(app: &App) -> T {
    let mut query = app.world.query::<&T>();
    let found: Vec<T> = query.iter().cloned().collect();
    assert_eq!(
        found.len(),
        1,
        "expected one {}",
        std::any::type_name::<T>()
    );
    found[0].clone()
}

#[test]
fn pom_extras_with_a_16_bit_npot_height_map() {
    let dir = scratch_dir("pom-extras");
    let fixture = pom_quad(json!({
        "height_texture": "HEIGHT", "height_scale": 0.03, "min_samples": 4, "max_samples": 40,
        "shadows": "hard", "method": "relief", "relief_binary_steps": 5, "lighting": "blinn_phong"
    }));
    let mut app = app();
    let scene = load_gltf(&mut app, fixture.write(&dir, "pom")).unwrap();
    assert!(scene.warnings.is_empty(), "{:?}", scene.warnings);
    let material: ParallaxOcclusionMaterial = only(&app);
    assert_eq!(material.height_scale, 0.03);
    assert_eq!((material.min_samples, material.max_samples), (4, 40));
    assert_eq!(material.shadows, ShadowMode::Hard);
    assert_eq!(material.method, ParallaxMethod::Relief);
    assert_eq!(material.relief_binary_steps, 5);
    let Some(HeightSource::Texture(height)) = &material.height_map else {
        panic!("height from its own texture");
    };
    let images = app.resources.get::<Assets<Image>>().unwrap();
    let height = images.get(height).unwrap();
    assert_eq!(height.size(), (48, 40), "non-power-of-two sizes load");
    assert!(
        matches!(height.pixels(), Pixels::Gray16(_)),
        "16-bit stays 16-bit"
    );
    assert!(app.world.query::<&LitMaterial>().iter().next().is_none());
    run_frames(&mut app, 1).unwrap();
}

#[test]
fn height_packed_in_the_normal_maps_alpha_and_depth_maps() {
    let dir = scratch_dir("packed");
    let fixture = pom_quad(json!({"height_in_normal_alpha": true, "height_convention": "depth"}));
    let mut app = app();
    load_gltf(&mut app, fixture.write(&dir, "packed")).unwrap();
    let material: ParallaxOcclusionMaterial = only(&app);
    assert_eq!(material.height_map, Some(HeightSource::NormalMapAlpha));
    assert_eq!(material.height_convention, HeightConvention::Depth);
}

#[test]
fn max_mip_from_extras_on_a_packed_depth_map_and_a_16_bit_npot_map() {
    for (name, extras) in [
        (
            "maxmip-packed",
            json!({"height_in_normal_alpha": true, "height_convention": "depth", "method": "maxmip"}),
        ),
        (
            "maxmip-npot",
            json!({"height_texture": "HEIGHT", "method": "maxmip", "height_units": "world"}),
        ),
    ] {
        let dir = scratch_dir(name);
        let fixture = pom_quad(extras);
        let mut app = app();
        let scene = load_gltf(&mut app, fixture.write(&dir, name)).unwrap();
        assert!(scene.warnings.is_empty(), "{:?}", scene.warnings);
        let material: ParallaxOcclusionMaterial = only(&app);
        assert_eq!(material.method, ParallaxMethod::MaxMip);
        // Its pyramid is derived and the frame renders without a validation error.
        run_frames(&mut app, 2).unwrap();
    }
}

#[test]
fn a_material_without_extras_is_normal_mapped() {
    let dir = scratch_dir("plain");
    let mut fixture = GltfFixture::quad(1.0);
    fixture.json["materials"][0]["pbrMetallicRoughness"] =
        json!({"baseColorFactor": [0.5, 0.25, 1.0, 1.0]});
    let mut app = app();
    load_gltf(&mut app, fixture.write(&dir, "plain")).unwrap();
    let material: LitMaterial = only(&app);
    assert_eq!(material.base_color.to_array(), [0.5, 0.25, 1.0, 1.0]);
}

fn mesh_of(app: &App) -> Mesh {
    let handle: Handle<Mesh> = only(app);
    app.resources
        .get::<Assets<Mesh>>()
        .unwrap()
        .get(&handle)
        .unwrap()
        .clone()
}

#[test]
fn texture_transforms_are_baked_into_the_coordinates() {
    let dir = scratch_dir("transform");
    let mut fixture = GltfFixture::quad(1.0);
    let texture = fixture.add_texture(
        "albedo.png",
        png(&RgbaImage::from_pixel(2, 2, image::Rgba([9, 9, 9, 255]))),
    );
    fixture.json["extensionsUsed"] = json!(["KHR_texture_transform"]);
    fixture.json["materials"][0]["pbrMetallicRoughness"] = json!({"baseColorTexture": {
        "index": texture,
        "extensions": {"KHR_texture_transform": {"scale": [4.0, 2.0], "offset": [0.5, 0.0]}}
    }});
    let mut app = app();
    load_gltf(&mut app, fixture.write(&dir, "transform")).unwrap();
    let mesh = mesh_of(&app);
    // uv' = offset + scale × uv: the corner (1, 1) lands on (4.5, 2).
    assert!(
        mesh.uvs
            .iter()
            .any(|uv| Vec2::from(*uv).distance(Vec2::new(4.5, 2.0)) < 1e-5),
        "{:?}",
        mesh.uvs
    );
}

#[test]
fn hierarchy_cameras_and_lights_become_entities() {
    let dir = scratch_dir("hierarchy");
    let mut fixture = GltfFixture::quad(1.0);
    fixture.json["extensionsUsed"] = json!(["KHR_lights_punctual"]);
    fixture.json["extensions"] = json!({"KHR_lights_punctual": {"lights": [
        {"type": "directional", "intensity": 2.0, "color": [1.0, 0.5, 0.5]},
        {"type": "spot", "intensity": 3.0, "spot": {}}
    ]}});
    fixture.json["cameras"] =
        json!([{"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.1}}]);
    fixture.json["scenes"][0]["nodes"] = json!([1, 3, 4]);
    fixture.json["nodes"] = json!([
        {"name": "quad", "mesh": 0, "translation": [0.0, 1.0, 0.0]},
        {"name": "parent", "translation": [10.0, 0.0, 0.0], "children": [0, 2]},
        {"name": "camera", "camera": 0, "translation": [0.0, 0.0, 5.0]},
        {"name": "sun", "extensions": {"KHR_lights_punctual": {"light": 0}}},
        {"name": "spot", "extensions": {"KHR_lights_punctual": {"light": 1}}}
    ]);
    let mut app = app();
    let scene = load_gltf(&mut app, fixture.write(&dir, "hierarchy")).unwrap();
    assert_eq!(scene.cameras.len(), 1);
    assert_eq!(scene.lights.len(), 2);
    // The spot is a spot light now: nothing to warn about.
    assert!(scene.warnings.is_empty(), "{:?}", scene.warnings);
    let (min, max) = scene.bounds.unwrap();
    assert!(
        (min - Vec3::new(9.5, 1.0, -0.5)).length() < 1e-5
            && (max - Vec3::new(10.5, 1.0, 0.5)).length() < 1e-5
    );
    run_frames(&mut app, 1).unwrap();
    let quad = app
        .world
        .query::<(&Handle<Mesh>, &GlobalTransform)>()
        .iter()
        .map(|(_, global)| global.translation())
        .next()
        .unwrap();
    assert_eq!(
        quad,
        Vec3::new(10.0, 1.0, 0.0),
        "the child moves with its parent"
    );
    let sun: DirectionalLight = only(&app);
    assert_eq!(sun.intensity, 2.0);
    // glTF's default cone, no range: unbounded.
    let spot: pom::SpotLight = only(&app);
    assert_eq!(
        (
            spot.intensity,
            spot.inner_angle,
            spot.outer_angle,
            spot.range
        ),
        (3.0, 0.0, std::f32::consts::FRAC_PI_4, f32::INFINITY)
    );
}

#[test]
fn unsupported_features_warn_and_the_rest_still_loads() {
    let dir = scratch_dir("unsupported");
    let mut fixture = GltfFixture::quad(1.0);
    let mut lines = fixture.json["meshes"][0]["primitives"][0].clone();
    lines["mode"] = json!(1);
    fixture.json["meshes"][0]["primitives"]
        .as_array_mut()
        .unwrap()
        .push(lines);
    fixture.json["extensionsUsed"] = json!(["EXT_made_up"]);
    fixture.json["extensionsRequired"] = json!(["EXT_made_up"]);
    let mut app = app();
    let scene = load_gltf(&mut app, fixture.write(&dir, "unsupported")).unwrap();
    assert_eq!(scene.warnings.len(), 2, "{:?}", scene.warnings);
    assert!(scene.warnings.iter().any(|w| w.contains("EXT_made_up")));
    assert!(
        scene
            .warnings
            .iter()
            .any(|w| w.contains("mode") && w.contains("\"quad\" (#0)"))
    );
    assert_eq!(
        app.world.query::<&Handle<Mesh>>().iter().count(),
        1,
        "the triangles still load"
    );
}

#[test]
fn meshes_without_normals_or_uvs_get_flat_normals_and_zero_uvs() {
    let dir = scratch_dir("bare");
    let mut fixture = GltfFixture::quad(1.0);
    let attributes = fixture.json["meshes"][0]["primitives"][0]["attributes"]
        .as_object_mut()
        .unwrap();
    attributes.remove("NORMAL");
    attributes.remove("TEXCOORD_0");
    attributes.remove("TANGENT");
    let mut app = app();
    load_gltf(&mut app, fixture.write(&dir, "bare")).unwrap();
    let mesh = mesh_of(&app);
    assert!(
        mesh.normals
            .iter()
            .all(|n| (Vec3::from(*n) - Vec3::Y).length() < 1e-6)
    );
    assert_eq!(mesh.tangents.len(), mesh.positions.len());
    run_frames(&mut app, 1).unwrap();
}

/// Loads `fixture` and returns the error message, which must name `needle`.
fn load_error(fixture: &GltfFixture, test: &str, needle: &str) -> String {
    let mut app = app();
    let error = fixture.load_error(&mut app, test, needle);
    assert_eq!(app.world.len(), 0, "nothing half-loaded stays behind");
    error
}

#[test]
fn a_missing_buffer_file_is_named() {
    let mut fixture = GltfFixture::quad(1.0);
    fixture.json["buffers"][0]["uri"] = json!("gone.bin");
    load_error(&fixture, "missing-buffer", "gone.bin");
}

#[test]
fn out_of_range_indices_name_the_mesh() {
    let mut fixture = GltfFixture::quad(1.0);
    let last = fixture.bin.len() - 2;
    fixture.bin[last..].copy_from_slice(&99_u16.to_le_bytes());
    load_error(&fixture, "bad-index", "mesh \"quad\" (#0), primitive 0");
}

#[test]
fn nan_positions_name_the_mesh() {
    let mut fixture = GltfFixture::quad(1.0);
    fixture.bin[0..4].copy_from_slice(&f32::NAN.to_le_bytes());
    load_error(&fixture, "nan", "not finite");
}

#[test]
fn an_accessor_past_its_buffer_is_an_error() {
    let mut fixture = GltfFixture::quad(1.0);
    fixture.json["accessors"][0]["count"] = json!(400);
    fixture.json["accessors"][0]["min"] = json!([-0.5, 0.0, -0.5]);
    let dir = scratch_dir("long-accessor");
    let mut app = app();
    assert!(load_gltf(&mut app, fixture.write(&dir, "long")).is_err());
}

#[test]
fn bad_extras_are_errors_naming_the_material() {
    for (test, extras, needle) in [
        (
            "unknown-key",
            json!({"height_texture": "HEIGHT", "hieght_scale": 1}),
            "unknown field `hieght_scale`",
        ),
        (
            "bad-enum",
            json!({"height_texture": "HEIGHT", "shadows": "blurry"}),
            "extras.pom.shadows is \"blurry\"",
        ),
        (
            "wrong-type",
            json!({"height_texture": "HEIGHT", "min_samples": "many"}),
            "invalid type",
        ),
        (
            "no-height",
            json!({"height_scale": 0.1}),
            "needs height_texture",
        ),
        (
            "height-out-of-range",
            json!({"height_texture": 42}),
            "height_texture is 42",
        ),
        (
            "inverted",
            json!({"height_texture": "HEIGHT", "min_samples": 60, "max_samples": 10}),
            "min_samples (60)",
        ),
        (
            "negative",
            json!({"height_texture": "HEIGHT", "height_scale": -1.0}),
            "height_scale",
        ),
    ] {
        let message = load_error(&pom_quad(extras), test, needle);
        assert!(message.contains("material \"surface\" (#0)"), "{message}");
    }
}

#[test]
fn a_broken_image_is_named() {
    let mut fixture = pom_quad(json!({"height_texture": "HEIGHT"}));
    fixture.images[1].1.truncate(20);
    load_error(&fixture, "broken-image", "image");
}

#[test]
fn a_truncated_glb_is_a_clean_error() {
    let dir = scratch_dir("truncated");
    let fixture = GltfFixture::quad(1.0);
    let path = fixture.write_glb(&dir, "whole");
    let mut app = app();
    load_gltf(&mut app, &path).unwrap();
    let bytes = std::fs::read(&path).unwrap();
    for cut in [8, 30, bytes.len() / 2, bytes.len() - 4] {
        let truncated = dir.join(format!("cut-{cut}.glb"));
        std::fs::write(&truncated, &bytes[..cut]).unwrap();
        let error = load_gltf(&mut App::new(), &truncated)
            .unwrap_err()
            .to_string();
        assert!(error.contains(&format!("cut-{cut}.glb")), "{error}");
    }
    let empty = dir.join("empty.gltf");
    std::fs::write(&empty, b"").unwrap();
    assert!(
        load_gltf(&mut App::new(), &empty)
            .unwrap_err()
            .to_string()
            .contains("empty.gltf")
    );
    assert!(load_gltf(&mut App::new(), dir.join("absent.glb")).is_err());
}

#[test]
fn an_alpha_height_from_an_image_without_alpha_is_an_error() {
    let mut fixture = GltfFixture::quad(1.0);
    let grey = fixture.add_texture("grey.png", png(&GrayImage::new(4, 4)));
    fixture.json["materials"][0]["extras"] =
        json!({"pom": {"height_texture": grey, "height_channel": "a"}});
    load_error(&fixture, "no-alpha", "no alpha channel");
}

#[test]
fn entities_keep_their_node_names_and_primitives_get_numbered_children() {
    let dir = scratch_dir("names");
    let mut fixture = GltfFixture::quad(1.0);
    let primitive = fixture.json["meshes"][0]["primitives"][0].clone();
    fixture.json["meshes"][0]["primitives"] = json!([primitive.clone(), primitive]);
    fixture.json["scenes"][0]["nodes"] = json!([0, 1]);
    fixture.json["nodes"] = json!([{"name": "quad", "mesh": 0}, {}]);
    let mut app = app();
    let scene = load_gltf(&mut app, fixture.write(&dir, "names")).unwrap();
    let names: Vec<String> = scene
        .entities
        .iter()
        .map(|entity| app.world.get::<&pom::Name>(*entity).unwrap().to_string())
        .collect();
    assert_eq!(
        names,
        ["quad", "quad / primitive 0", "quad / primitive 1", "node 1"]
    );
}

#[test]
fn every_parameter_survives_gltf_extras() {
    use pom_tests::parameters::{assert_same_parameters, every_parameter_changed};
    let material = every_parameter_changed();
    let mut extras = serde_json::to_value(pom::PomPatch::from_material(&material)).unwrap();
    extras["height_texture"] = json!("HEIGHT");
    let dir = scratch_dir("extras-round-trip");
    let mut app = app();
    let scene = load_gltf(&mut app, pom_quad(extras).write(&dir, "all")).unwrap();
    assert!(scene.warnings.is_empty(), "{:?}", scene.warnings);
    let loaded: ParallaxOcclusionMaterial = only(&app);
    assert_same_parameters(&loaded, &material, "glTF extras");
}
