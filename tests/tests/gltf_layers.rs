//! A layered parallax material from glTF `extras.pom.layers` and `layer_weights_texture`, and
//! every bad layer description a file can hold.

use image::{GrayImage, Luma, Rgba, RgbaImage};
use pom::{
    App, Assets, Image, LayerWeights, ParallaxOcclusionMaterial, PomPlugin, RenderPlugin, load_gltf,
};
use pom_tests::gltf_fixture::{GltfFixture, png, scratch_dir};
use pom_tests::run_frames;
use serde_json::{Value, json};

fn app() -> App {
    let mut app = App::new();
    app.add_plugin(RenderPlugin::new(32, 32))
        .add_plugin(PomPlugin);
    app
}

/// A quad whose material has `layers` (their `"HEIGHT n"`, `"COLOUR"` and `"WEIGHTS"` values
/// replaced by textures: a height of n × n texels, a colour, an RGBA weight map of 16 × 8).
fn layered_quad(mut layers: Value, weights: bool) -> GltfFixture {
    let mut fixture = GltfFixture::quad(1.0);
    let texture = |fixture: &mut GltfFixture, value: &Value| -> Option<usize> {
        let text = value.as_str()?;
        if let Some(size) = text.strip_prefix("HEIGHT ") {
            let size: u32 = size.parse().ok()?;
            let field =
                GrayImage::from_fn(size, size, |x, _| Luma([(x * 255 / size.max(2)) as u8]));
            return Some(fixture.add_texture(
                &format!("height{size}-{}.png", fixture.images.len()),
                png(&field),
            ));
        }
        (text == "COLOUR").then(|| {
            fixture.add_texture(
                &format!("colour{}.png", fixture.images.len()),
                png(&RgbaImage::from_pixel(2, 2, Rgba([90, 160, 60, 255]))),
            )
        })
    };
    if let Value::Array(list) = &mut layers {
        for layer in list {
            if let Value::Object(keys) = layer {
                for value in keys.values_mut() {
                    if let Some(index) = texture(&mut fixture, value) {
                        *value = json!(index);
                    }
                }
            }
        }
    }
    let mut pom = json!({"layers": layers, "height_scale": 0.05});
    if weights {
        let map = RgbaImage::from_fn(16, 8, |x, _| {
            Rgba([255 - (x * 16) as u8, (x * 16) as u8, 0, 0])
        });
        pom["layer_weights_texture"] = json!(fixture.add_texture("weights.png", png(&map)));
    }
    fixture.json["materials"][0]["extras"] = json!({ "pom": pom });
    fixture
}

fn loaded_material(fixture: &GltfFixture, test: &str) -> (App, ParallaxOcclusionMaterial) {
    let dir = scratch_dir(test);
    let mut app = app();
    let scene = load_gltf(&mut app, fixture.write(&dir, test)).expect("loads");
    assert!(scene.warnings.is_empty(), "{:?}", scene.warnings);
    let material = app
        .world
        .query::<&ParallaxOcclusionMaterial>()
        .iter()
        .next()
        .cloned()
        .expect("a parallax material");
    (app, material)
}

fn load_error(fixture: &GltfFixture, test: &str, needle: &str) {
    let error = fixture.load_error(&mut app(), test, needle);
    assert!(error.contains("material \"surface\" (#0)"), "{error}");
}

#[test]
fn four_layers_load_with_their_maps_packed_heights_and_weight_map() {
    let layers = json!([
        {"base_color_texture": "COLOUR", "normal_texture": "COLOUR", "height_texture": "HEIGHT 16", "tiling": 4, "height_scale": 1.0},
        {"base_color_texture": "COLOUR", "height_texture": "HEIGHT 32", "tiling": 8, "height_scale": 0.5},
        {"height_texture": "HEIGHT 8"},
        {"base_color_texture": "COLOUR"}
    ]);
    // The weight map (16 × 8) is of another size than every layer: that is fine.
    let (mut app, material) = loaded_material(&layered_quad(layers, true), "layers-four");
    let layers = material.layers.as_ref().expect("layered");
    assert_eq!(layers.layers.len(), 4);
    assert_eq!(
        layers
            .layers
            .iter()
            .map(|layer| (layer.tiling, layer.height_scale))
            .collect::<Vec<_>>(),
        [(4.0, 1.0), (8.0, 0.5), (1.0, 1.0), (1.0, 1.0)]
    );
    assert!(layers.layers[0].normal_map.is_some() && layers.layers[1].normal_map.is_none());
    assert!(matches!(layers.weights, LayerWeights::Texture(_)));
    assert!(
        material.height_map.is_none(),
        "the layers replace the material's own maps"
    );
    let images = app.resources.get::<Assets<Image>>().unwrap();
    let packed = images
        .get(&layers.heights)
        .expect("packed heights")
        .to_rgba8();
    // The largest layer's size; the fourth layer has no height map: flat at the top.
    assert_eq!(packed.dimensions(), (32, 32));
    assert!(packed.pixels().all(|texel| texel.0[3] == 255));
    assert!(
        packed.pixels().any(|texel| texel.0[1] < 20)
            && packed.pixels().any(|texel| texel.0[1] > 230)
    );
    run_frames(&mut app, 2).expect("draws");
}

#[test]
fn without_a_weight_map_the_vertex_colours_weigh_the_layers() {
    let layers = json!([{"height_texture": "HEIGHT 4"}, {}]);
    let (_, material) = loaded_material(&layered_quad(layers, false), "layers-vertex-colours");
    assert_eq!(
        material.layers.expect("layered").weights,
        LayerWeights::VertexColors
    );
}

#[test]
fn bad_layers_are_errors_naming_the_material_and_the_key() {
    let one = json!({"height_texture": "HEIGHT 4"});
    for (test, layers, needle) in [
        (
            "layers-five",
            json!([one, one, one, one, one]),
            "extras.pom.layers has 5 layers; a layered material has 1 to 4",
        ),
        ("layers-none", json!([]), "extras.pom.layers has 0 layers"),
        (
            "layers-missing-texture",
            json!([one, {"height_texture": 42}]),
            "extras.pom.layers[1].height_texture is 42 but the file has",
        ),
        (
            "layers-zero-tiling",
            json!([{"tiling": 0}]),
            "layers[0].tiling is 0 but must be within",
        ),
        (
            "layers-deep",
            json!([{"height_scale": 1.5}]),
            "layers[0].height_scale is 1.5 but must be within 0..=1",
        ),
        (
            "layers-not-a-list",
            json!({"tiling": 2}),
            "expected a list of layer objects",
        ),
        (
            "layers-unknown-key",
            json!([{"tilling": 2}]),
            "unknown field `tilling`",
        ),
    ] {
        load_error(&layered_quad(layers, true), test, needle);
    }
}

#[test]
fn a_weight_map_index_past_the_textures_is_named() {
    let mut fixture = layered_quad(json!([{}]), false);
    fixture.json["materials"][0]["extras"]["pom"]["layer_weights_texture"] = json!(9);
    load_error(
        &fixture,
        "layers-weights-missing",
        "extras.pom.layer_weights_texture is 9 but the file has",
    );
}
