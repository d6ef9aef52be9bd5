//! The side panel's layers: each layer of a layered material edited live, and a preset's layer
//! files loaded from the panel (the fixtures are panel_tests.rs').

use egui_kittest::kittest::Queryable;
use pom::{App, ParallaxOcclusionMaterial};

use super::panel_tests::{harness_with, material, scratch_file};

#[test]
fn a_layered_materials_layers_are_edited_live_from_the_panel() {
    let mut app = App::new();
    let mut images = pom::Assets::<pom::Image>::default();
    let field = pom::HeightField::from_fn(4, 4, |u, _| u);
    let layers = pom::ParallaxLayers::new(
        &mut images,
        vec![
            (pom::ParallaxLayer::default(), Some(&field)),
            (pom::ParallaxLayer::default(), None),
        ],
        pom::LayerWeights::VertexColors,
    )
    .unwrap();
    let material = app.world.spawn((ParallaxOcclusionMaterial {
        layers: Some(layers),
        ..ParallaxOcclusionMaterial::default()
    },));
    let mut harness = harness_with(app);
    // The fixture's own material comes second; edit the layered one.
    harness.state_mut().panel.selected = Some(material);
    harness.run();
    harness.get_by_label("2 layers, weighed by the vertex colours");
    harness
        .get_by_role_and_label(egui::Role::Slider, "layer 2 tiling")
        .set_value_accesskit(8.0);
    harness
        .get_by_role_and_label(egui::Role::Slider, "layer 1 depth")
        .set_value_accesskit(0.4);
    harness.run();
    let fixture = harness.state();
    let edited = fixture
        .app
        .world
        .get::<&ParallaxOcclusionMaterial>(material)
        .unwrap();
    let layers = &edited.layers.as_ref().unwrap().layers;
    assert!(
        (layers[1].tiling - 8.0).abs() < 1e-4,
        "{}",
        layers[1].tiling
    );
    assert!((layers[0].height_scale - 0.4).abs() < 1e-6);
    assert_eq!((layers[0].tiling, layers[1].height_scale), (1.0, 1.0));
}

#[test]
fn loading_a_preset_with_layer_files_gives_the_material_its_layers() {
    let dir = scratch_file("layered").with_extension("d");
    std::fs::create_dir_all(&dir).unwrap();
    for name in ["bright.png", "dark.png"] {
        image::RgbaImage::from_pixel(4, 4, image::Rgba([200, 200, 200, 255]))
            .save(dir.join(name))
            .unwrap();
    }
    let preset = dir.join("layered.ron");
    std::fs::write(
        &preset,
        "(height_scale: 0.07, layers: [(base_color_texture: \"bright.png\", tiling: 4.0), \
          (base_color_texture: \"dark.png\")])",
    )
    .unwrap();
    let outside = dir.join("outside.ron");
    std::fs::write(&outside, "(layers: [(base_color_texture: \"../x.png\")])").unwrap();

    let mut app = App::new();
    app.resources.insert(pom::Assets::<pom::Image>::default());
    let mut harness = harness_with(app);
    harness.state_mut().panel.presets.path = outside.display().to_string();
    harness.run();
    harness.get_by_label("Load preset…").click();
    harness.run();
    harness.get_by_label_contains("leads out");
    assert!(material(&harness).layers.is_none());

    harness.state_mut().panel.presets.path = preset.display().to_string();
    harness.run();
    harness.get_by_label("Load preset…").click();
    harness.run();
    let loaded = material(&harness);
    std::fs::remove_dir_all(&dir).unwrap();
    let layers = loaded.layers.expect("the preset's layers");
    assert_eq!(layers.layers.len(), 2);
    assert_eq!(layers.layers[0].tiling, 4.0);
    assert_eq!(loaded.height_scale, 0.07);
    let images = harness
        .state()
        .app
        .resources
        .get::<pom::Assets<pom::Image>>()
        .unwrap();
    assert!(images.len() >= 2, "the layer images were added");
}
