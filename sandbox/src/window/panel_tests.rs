//! The side panel driven by egui_kittest, without a window or a GPU: the panel only edits the
//! `pom::App`'s world, so a bare `App` with one material entity is enough.

use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use pom::hecs::Entity;
use pom::{App, ParallaxOcclusionMaterial, ShadowMode};

use super::panels::{PanelState, side_panel_contents};

pub(super) struct Fixture {
    pub(super) app: App,
    pub(super) panel: PanelState,
    pub(super) material: Entity,
}

fn harness() -> Harness<'static, Fixture> {
    harness_with(App::new())
}

/// The panel over `app`, with one material entity added.
pub(super) fn harness_with(mut app: App) -> Harness<'static, Fixture> {
    let material = app.world.spawn((ParallaxOcclusionMaterial::default(),));
    let fixture = Fixture {
        app,
        panel: PanelState::default(),
        material,
    };
    let mut harness = Harness::builder()
        .with_size(egui::vec2(420.0, 1400.0))
        .build_ui_state(
            |ui, fixture: &mut Fixture| {
                side_panel_contents(ui, &mut fixture.app, &mut fixture.panel)
            },
            fixture,
        );
    harness.run();
    harness
}

pub(super) fn material(harness: &Harness<'_, Fixture>) -> ParallaxOcclusionMaterial {
    let fixture = harness.state();
    fixture
        .app
        .world
        .get::<&ParallaxOcclusionMaterial>(fixture.material)
        .map(|material| (*material).clone())
        .unwrap()
}

pub(super) fn scratch_file(name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("sandbox-panel-tests-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

#[test]
fn moving_the_height_scale_slider_changes_the_component() {
    let mut harness = harness();
    assert_eq!(material(&harness).height_scale, 0.05);
    harness
        .get_by_role_and_label(egui::Role::Slider, "height scale")
        .set_value_accesskit(0.12);
    harness.run();
    assert!((material(&harness).height_scale - 0.12).abs() < 1e-6);
    // Other parameters stay as they were.
    assert_eq!(material(&harness).max_samples, 50);
}

#[test]
fn the_selected_material_is_listed_and_every_group_of_controls_is_there() {
    let mut harness = harness();
    let entity = harness.state().material;
    harness.get_by_label(&format!("entity {}", entity.id()));
    // The essential group is open; open the others.
    for group in pom::material::ParamGroup::ALL
        .into_iter()
        .filter(|group| *group != pom::material::ParamGroup::Essential)
    {
        harness.get_by_label(group.heading()).click();
        harness.run();
    }
    // One control per declared parameter, labelled with its name.
    for param in pom::ParallaxOcclusionMaterial::PARAMETERS {
        let label = param.label();
        assert!(
            harness.query_all_by_label(&label).next().is_some(),
            "no control labelled {label:?}"
        );
    }
}

#[test]
fn presets_round_trip_through_save_and_load() {
    let path = scratch_file("round-trip.ron");
    let mut harness = harness();
    let material_entity = harness.state().material;
    {
        let fixture = harness.state_mut();
        fixture.panel.presets.path = path.display().to_string();
        let mut material = fixture
            .app
            .world
            .get::<&mut ParallaxOcclusionMaterial>(material_entity)
            .unwrap();
        material.height_scale = 0.08;
        material.shadows = ShadowMode::Hard;
    }
    harness.run();
    harness.get_by_label("Save preset…").click();
    harness.run();
    assert!(path.exists(), "the preset file was written");
    let saved = material(&harness);
    {
        let fixture = harness.state_mut();
        let mut material = fixture
            .app
            .world
            .get::<&mut ParallaxOcclusionMaterial>(material_entity)
            .unwrap();
        *material = ParallaxOcclusionMaterial::default();
    }
    harness.run();
    harness.get_by_label("Load preset…").click();
    harness.run();
    assert_eq!(material(&harness).preset(), saved.preset());
    assert_eq!(material(&harness).shadows, ShadowMode::Hard);
    let _ = std::fs::remove_file(&path);
}

#[test]
fn a_bad_preset_file_shows_an_error_and_leaves_the_material_alone() {
    let path = scratch_file("bad.ron");
    std::fs::write(&path, "(height_scale: \"deep\")").unwrap();
    let mut harness = harness();
    harness.state_mut().panel.presets.path = path.display().to_string();
    harness.run();
    let before = material(&harness);
    harness.get_by_label("Load preset…").click();
    harness.run();
    harness.get_by_label_contains("could not load");
    assert_eq!(material(&harness), before);
    let _ = std::fs::remove_file(&path);
}

#[test]
fn lights_can_be_added_and_removed() {
    let mut harness = harness();
    let lights = |harness: &Harness<'_, Fixture>| {
        harness
            .state()
            .app
            .world
            .query::<&pom::DirectionalLight>()
            .iter()
            .count()
    };
    assert_eq!(lights(&harness), 0);
    harness.get_by_label("Light").click();
    harness.run();
    harness.get_by_label("Add light").click();
    harness.run();
    assert_eq!(lights(&harness), 1);
    harness
        .get_by_role_and_label(egui::Role::Slider, "light elevation °")
        .set_value_accesskit(60.0);
    harness.run();
    let fixture = harness.state();
    let (_, transform) = fixture
        .app
        .world
        .query::<(&pom::DirectionalLight, &pom::Transform)>()
        .iter()
        .next()
        .map(|(light, transform)| (*light, *transform))
        .unwrap();
    let (_, elevation) = super::light_control::azimuth_elevation(&transform);
    assert!((elevation - 60.0).abs() < 0.01, "{elevation}");
    harness.get_by_label("Remove light").click();
    harness.run();
    assert_eq!(lights(&harness), 0);
}

#[test]
fn a_shader_reload_error_shows_in_the_panel() {
    let mut harness = harness();
    harness.get_by_label_contains("Shader hot reload: off");
    harness
        .state_mut()
        .app
        .insert_resource(pom::ShaderReloadStatus {
            source_dir: "plugin/src".into(),
            reloads: 2,
            error: Some(pom::ShaderReloadError::Invalid {
                file: "parallax/pom.wgsl".into(),
                line: 12,
                column: 5,
                message: "expected ';'".into(),
            }),
        });
    harness.run();
    harness.get_by_label("Shader hot reload: 2 reloads");
    harness.get_by_label_contains("parallax/pom.wgsl:12:5: expected ';'");
}

#[test]
fn the_timing_panel_shows_the_frame_times_and_gpu_times_as_not_available() {
    let mut harness = harness();
    for _ in 0..10 {
        harness.state_mut().panel.frame_times.push(0.020);
    }
    harness.get_by_label("Timing").click();
    harness.run();
    harness.get_by_label("CPU frame: 20.0 ms mean, 20.0 ms max over 10 frames");
    harness.get_by_label("GPU time per pass: n/a (no timestamp queries on this adapter)");
}

#[test]
fn the_timing_panel_lists_the_plugins_gpu_pass_times() {
    let mut harness = harness();
    let passes = [
        ("main pass".to_owned(), 2.5),
        ("sobel pass".to_owned(), 0.25),
    ];
    harness
        .state_mut()
        .app
        .insert_resource(pom::GpuTimings::Supported {
            passes: passes.into_iter().collect(),
            frame: 42,
            rejected: 0,
        });
    harness.get_by_label("Timing").click();
    harness.run();
    harness.get_by_label("GPU time per pass (frame 42):");
    harness.get_by_label("  main pass: 2.500 ms");
    harness.get_by_label("  sobel pass: 0.250 ms");
}

/// Needs a GPU (lavapipe in `tests/run`): the control edits the renderer, which the render
/// plugin makes once the GPU has started.
#[test]
fn switching_the_render_path_control_changes_the_renderers_path() {
    use pom::RenderPath;
    use pom::render::Renderer;
    let mut app = App::new();
    app.add_plugin(pom::RenderPlugin::new(16, 16));
    app.finish().expect("a GPU or lavapipe for this test");
    let mut harness = harness_with(app);
    let renderer = |harness: &Harness<'_, Fixture>| {
        let renderer = harness.state().app.resources.get::<Renderer>().unwrap();
        let status = super::render_path_control::path_status(
            renderer.runs_deferred(),
            renderer.deferred_unavailable(),
        );
        (renderer.path(), status)
    };
    assert_eq!(renderer(&harness).0, RenderPath::Auto);
    harness.get_by_label("Timing").click();
    harness.run();
    for path in [RenderPath::Deferred, RenderPath::Forward, RenderPath::Auto] {
        harness.get_by_label("render path").click();
        harness.run();
        harness.get_by_label(path.name()).click();
        harness.run();
        assert_eq!(renderer(&harness).0, path);
        // The next frame runs on it, and the panel says which path that was.
        harness.state_mut().app.update().unwrap();
        harness.run();
        let (_, status) = renderer(&harness);
        harness.get_by_label(&status);
        if path == RenderPath::Forward {
            assert_eq!(status, "path: forward");
        }
    }
}

#[test]
fn a_bad_scene_file_shows_an_error_and_the_scene_stays() {
    let path = scratch_file("broken.glb");
    std::fs::write(&path, b"this is not a glb").unwrap();
    let mut harness = harness();
    let material_entity = harness.state().material;
    harness.get_by_label("Open…").click();
    harness.run();
    harness.state_mut().panel.browser.path = path.display().to_string();
    harness.run();
    harness.get_by_label("Open scene").click();
    harness.run();
    let shown = format!("could not open: {}", path.display());
    assert!(
        harness.query_all_by_label_contains(&shown).next().is_some(),
        "no error naming the file: {:?}",
        harness.state().panel.messages
    );
    let fixture = harness.state();
    assert!(fixture.app.world.contains(material_entity));
    assert_eq!(fixture.app.world.len(), 1);
    assert!(fixture.panel.opened.is_none());
    let _ = std::fs::remove_file(&path);
}

/// A file dropped on the window, as the platform integration reports it.
#[derive(Debug)]
struct DroppedPath(std::path::PathBuf);

impl egui::DroppedFile for DroppedPath {
    fn path(&self) -> &std::path::Path {
        &self.0
    }

    fn bytes(&self) -> Result<Vec<u8>, String> {
        std::fs::read(&self.0).map_err(|error| error.to_string())
    }
}

#[test]
fn dropping_an_image_set_opens_it_on_a_plane() {
    let dir = scratch_file("dropped-set");
    std::fs::create_dir_all(&dir).unwrap();
    let height = dir.join("ridges.png");
    image::GrayImage::from_fn(16, 16, |x, _| image::Luma([(x * 16) as u8]))
        .save(&height)
        .unwrap();
    let mut harness = harness();
    harness
        .input_mut()
        .dropped_files
        .push(std::sync::Arc::new(DroppedPath(height.clone())));
    harness.run();
    let fixture = harness.state();
    let opened = fixture.panel.opened.as_ref().expect("the set was opened");
    assert!(opened.label.contains("ridges.png"), "{}", opened.label);
    let materials: Vec<_> = fixture
        .app
        .world
        .query::<&ParallaxOcclusionMaterial>()
        .iter()
        .map(|material| material.height_map.is_some())
        .collect();
    assert_eq!(
        materials,
        [true],
        "one plane with the height map replaced the old entity"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn split_view_b_copies_a_then_takes_its_own_method() {
    let mut harness = harness();
    let entity = harness.state().material;
    harness.get_by_label("split view (A | B)").click();
    harness.run();
    harness.get_by_label("Copy A's parameters to B").click();
    harness.run();
    let b = |harness: &Harness<'_, Fixture>| {
        harness
            .state()
            .app
            .resources
            .get::<pom::SplitView>()
            .expect("the split view is on")
            .overrides[&entity]
            .clone()
    };
    assert_eq!(b(&harness), material(&harness));
    harness.get_by_label("B method").click();
    harness.run();
    harness.get_by_label("normal").click();
    harness.run();
    assert_eq!(b(&harness).method, pom::ParallaxMethod::NormalMapping);
    assert_eq!(
        material(&harness).method,
        pom::ParallaxMethod::Occlusion,
        "A keeps its method"
    );
    harness.get_by_label("split view (A | B)").click();
    harness.run();
    assert!(
        harness
            .state()
            .app
            .resources
            .get::<pom::SplitView>()
            .is_none()
    );
}

#[test]
fn the_display_controls_set_the_cameras_exposure_and_tonemapping() {
    let mut harness = harness();
    let camera = harness
        .state_mut()
        .app
        .world
        .spawn((pom::Camera::perspective(45.0), pom::Transform::IDENTITY));
    harness.run();
    harness.get_by_label("Display").click();
    harness.run();
    harness
        .get_by_role_and_label(egui::Role::Slider, "exposure (EV100)")
        .set_value_accesskit(2.5);
    harness.run();
    let exposure = *harness
        .state()
        .app
        .world
        .get::<&pom::Exposure>(camera)
        .unwrap();
    assert!((exposure.ev100 - 2.5).abs() < 1e-6, "{exposure:?}");
    // The operator's choice is there, and the camera holds the default, Neutral.
    harness.get_by_label("tonemapping");
    let tonemapping = *harness
        .state()
        .app
        .world
        .get::<&pom::Tonemapping>(camera)
        .unwrap();
    assert_eq!(tonemapping, pom::Tonemapping::Neutral);
    // Anti-aliasing defaults to TAA, whose parameters show and reach the camera.
    harness.get_by_label("anti-aliasing");
    harness
        .get_by_role_and_label(egui::Role::Slider, "current weight")
        .set_value_accesskit(0.25);
    harness.run();
    let world = &harness.state().app.world;
    assert_eq!(
        *world.get::<&pom::AntiAliasing>(camera).unwrap(),
        pom::AntiAliasing::Taa
    );
    let taa = *world.get::<&pom::TemporalAntiAliasing>(camera).unwrap();
    assert!((taa.current_weight - 0.25).abs() < 1e-6, "{taa:?}");
}

#[test]
fn a_spot_light_is_added_and_its_cone_edited_from_the_panel() {
    let mut harness = harness();
    harness.get_by_label("Spot lights").click();
    harness.run();
    harness.get_by_label("Add spot light").click();
    harness.run();
    let spot = |harness: &Harness<'_, Fixture>| {
        *harness
            .state()
            .app
            .world
            .query::<&pom::SpotLight>()
            .iter()
            .next()
            .expect("a spot light was added")
    };
    assert_eq!(spot(&harness), pom::SpotLight::default());
    harness
        .get_by_role_and_label(egui::Role::Slider, "outer cone °")
        .set_value_accesskit(30.0);
    harness.run();
    assert!((spot(&harness).outer_angle - 30_f32.to_radians()).abs() < 1e-4);
}

fn shadows_of(harness: &Harness<'_, Fixture>, light: Entity) -> Option<pom::LightShadows> {
    harness
        .state()
        .app
        .world
        .get::<&pom::LightShadows>(light)
        .map(|shadows| *shadows)
        .ok()
}

#[test]
fn a_directional_lights_shadow_controls_reach_its_component() {
    let mut harness = harness();
    let sun = harness.state_mut().app.world.spawn((
        pom::DirectionalLight::default(),
        super::light_control::light_transform(glam::Vec3::ZERO, 0.0, 45.0),
    ));
    harness.get_by_label("Light").click();
    harness.run();
    assert_eq!(shadows_of(&harness, sun), None, "untouched: the defaults");
    harness
        .get_by_role_and_label(egui::Role::Slider, "shadow softness (texels)")
        .set_value_accesskit(4.0);
    harness.run();
    harness.get_by_label("shadow map size").click();
    harness.run();
    harness.get_by_label("1024").click();
    harness.run();
    harness
        .get_by_role_and_label(egui::Role::Slider, "cascade distance")
        .set_value_accesskit(200.0);
    harness.run();
    let shadows = shadows_of(&harness, sun).expect("the controls added a LightShadows");
    assert!(shadows.enabled);
    assert_eq!(shadows.map_size, 1024);
    assert!((shadows.softness - 4.0).abs() < 1e-4, "{shadows:?}");
    assert!((shadows.distance - 200.0).abs() < 0.5, "{shadows:?}");
    harness.get_by_label("scene shadows").click();
    harness.run();
    assert!(!shadows_of(&harness, sun).unwrap().enabled);
}

#[test]
fn point_and_spot_lights_have_shadow_controls_without_a_cascade_distance() {
    let mut harness = harness();
    let lamp = harness.state_mut().app.world.spawn((
        pom::PointLight::default(),
        pom::Transform::from_xyz(0.0, 1.0, 0.0),
    ));
    harness.get_by_label("Point lights").click();
    harness.run();
    harness.get_by_label("point 0");
    assert!(harness.query_by_label("cascade distance").is_none());
    harness.get_by_label("scene shadows").click();
    harness.run();
    assert_eq!(shadows_of(&harness, lamp), Some(pom::LightShadows::off()));
    // Closed again, so the spot's controls below are the only ones shown.
    harness.get_by_label("Point lights").click();
    harness.run();
    harness.get_by_label("Spot lights").click();
    harness.run();
    harness.get_by_label("Add spot light").click();
    harness.run();
    harness
        .get_by_role_and_label(egui::Role::Slider, "shadow softness (texels)")
        .set_value_accesskit(0.0);
    harness.run();
    let spot = harness
        .state()
        .app
        .world
        .query::<(Entity, &pom::SpotLight)>()
        .iter()
        .map(|(entity, _)| entity)
        .next()
        .unwrap();
    assert_eq!(shadows_of(&harness, spot).unwrap().softness, 0.0);
}

#[test]
fn the_environment_panel_switches_to_the_sky_and_sets_its_parameters() {
    let mut app = App::new();
    let sun = app
        .world
        .spawn((pom::DirectionalLight::default(), pom::Transform::IDENTITY));
    let mut harness = harness_with(app);
    harness.get_by_label("Light").click();
    harness.run();
    harness.get_by_label("Environment").click();
    harness.run();
    harness.get_by_label("environment").click();
    harness.run();
    harness.get_by_label("sky").click();
    harness.run();
    harness
        .get_by_role_and_label(egui::Role::Slider, "intensity")
        .set_value_accesskit(2.0);
    harness.run();
    harness
        .get_by_role_and_label(egui::Role::Slider, "time of day")
        .set_value_accesskit(12.0);
    harness.run();
    let fixture = harness.state();
    let light = fixture
        .app
        .resources
        .get::<pom::EnvironmentLight>()
        .unwrap();
    assert!(
        matches!(light.source, pom::EnvironmentSource::Sky(_)),
        "{light:?}"
    );
    assert!((light.settings.intensity - 2.0).abs() < 1e-6, "{light:?}");
    // At noon the sun stands 60° up in the south: the light shines down and north.
    let transform = *fixture.app.world.get::<&pom::Transform>(sun).unwrap();
    let towards_sun = -(transform.rotation * glam::Vec3::NEG_Z);
    assert!(
        (towards_sun.y - 60f32.to_radians().sin()).abs() < 1e-3,
        "{towards_sun}"
    );
    assert!(towards_sun.z < -0.4, "{towards_sun}");
}

#[test]
fn an_environment_file_that_does_not_open_says_why_in_the_panel() {
    let mut harness = harness();
    harness.get_by_label("Light").click();
    harness.run();
    harness.get_by_label("Environment").click();
    harness.run();
    let missing = scratch_file("no-such-sky.hdr");
    harness.state_mut().panel.environment.path = missing.display().to_string();
    harness.run();
    harness.get_by_label("open environment").click();
    harness.run();
    let message = harness.state().panel.environment.message.clone().unwrap();
    assert!(message.contains("no-such-sky.hdr"), "{message}");
    harness.get_by_label_contains("no-such-sky.hdr");
    assert!(
        harness
            .state()
            .app
            .resources
            .get::<pom::EnvironmentLight>()
            .is_none()
    );
}
