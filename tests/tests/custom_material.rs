//! The material seam, proved from outside the `pom` crate: the example of "Writing your own
//! material" (plugin/docs/custom-material.md; `custom_material/tinted.rs`, kept identical to the
//! document's code by a test)
//! renders beside the shipped materials, and its uniform matches its WGSL.

#[rustfmt::skip]
#[path = "custom_material/tinted.rs"]
mod tinted;

use pom::glam::Vec3;
use pom::material::check_material_layout;
use pom::render::Renderer;
use pom::{
    Assets, Color, DirectionalLight, LitMaterial, MaterialPlugin, Mesh, RenderPath, Transform,
};
use pom_tests::{FlipTolerance, check_golden, headless_app, render_and_capture, render_on_path};
use tinted::Tinted;

#[test]
fn a_material_written_outside_the_crate_renders() {
    let mut app = headless_app(96, 96).unwrap();
    app.add_plugin(MaterialPlugin::<Tinted>::default());
    let meshes = app.resources.get_mut::<Assets<Mesh>>().unwrap();
    let cube = meshes.add(Mesh::cube(0.8));
    let floor = meshes.add(Mesh::plane(3.0));
    // Tonemapping off: an unlit colour reaches the image exactly.
    app.world.spawn((
        pom::Camera::perspective(45.0),
        pom::Tonemapping::None,
        Transform::from_xyz(1.6, 1.8, 2.4).looking_at(Vec3::ZERO, Vec3::Y),
    ));
    app.world.spawn((
        DirectionalLight::default(),
        Transform::IDENTITY.looking_at(Vec3::new(-0.4, -1.0, -0.6), Vec3::Y),
    ));
    app.world.spawn((
        floor,
        LitMaterial::from_color(Color::linear_rgb(0.5, 0.5, 0.5)),
        Transform::from_xyz(0.0, -0.4, 0.0),
    ));
    app.world.spawn((
        cube,
        Tinted {
            color: Color::linear_rgb(0.9, 0.35, 0.05),
        },
        Transform::IDENTITY,
    ));
    let image = render_and_capture(&mut app).unwrap();
    // Unlit: every pixel of the cube has exactly its colour, whatever the light.
    let orange = pom::linear_to_srgb(0.35);
    let center = image.get_pixel(48, 48).0;
    assert!(
        (f32::from(center[1]) / 255.0 - orange).abs() < 0.01,
        "{center:?}"
    );
    check_golden("custom_material", &image, FlipTolerance::default()).unwrap();
}

#[test]
fn an_app_with_a_material_without_deferred_shader_renders_forward_and_says_why() {
    let mut app = headless_app(32, 32).unwrap();
    app.add_plugin(MaterialPlugin::<Tinted>::default());
    let cube = app
        .resources
        .get_mut::<Assets<Mesh>>()
        .unwrap()
        .add(Mesh::cube(0.8));
    app.world.spawn((
        pom::Camera::perspective(45.0),
        Transform::from_xyz(1.6, 1.8, 2.4).looking_at(Vec3::ZERO, Vec3::Y),
    ));
    app.world
        .spawn((cube, Tinted::default(), Transform::IDENTITY));
    render_on_path(&mut app, RenderPath::Deferred).unwrap();
    let renderer = app.resources.get::<Renderer>().unwrap();
    assert!(!renderer.runs_deferred());
    let reason = renderer.deferred_unavailable().unwrap().to_string();
    assert!(reason.contains("tinted"), "{reason}");
}

#[test]
fn the_example_uniform_matches_its_wgsl() {
    assert_eq!(check_material_layout::<Tinted>(), Ok(()));
}

#[test]
fn the_custom_material_doc_shows_this_example_verbatim() {
    let doc = include_str!("../../plugin/docs/custom-material.md");
    let example = include_str!("custom_material/tinted.rs");
    let start = doc
        .find("# Writing your own material")
        .expect("the document has the section");
    let section = &doc[start..];
    let code_start = section.find("```rust").expect("a Rust block") + "```rust".len();
    let code = &section[code_start..];
    let code = &code[code.find('\n').unwrap() + 1..code.find("```").unwrap()];
    assert!(
        code.contains(example.trim()),
        "plugin/docs/custom-material.md's example and tests/tests/custom_material/tinted.rs differ"
    );
    assert!(
        example.lines().count() <= 40,
        "the example grew past 40 lines"
    );
}
