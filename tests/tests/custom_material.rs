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
use pom::render::shaders::{self, ComposedShader};
use pom::{
    Assets, Color, DirectionalLight, LitMaterial, MaterialPlugin, Mesh, RenderPath, Transform,
};
use pom_tests::{FlipTolerance, check_golden, headless_app, render_and_capture, render_on_path};
use tinted::Tinted;

/// The example's orange cube standing on a grey lit floor.
fn spawn_cube_over_floor(app: &mut pom::App) {
    let meshes = app.resources.get_mut::<Assets<Mesh>>().unwrap();
    let cube = meshes.add(Mesh::cube(0.8));
    let floor = meshes.add(Mesh::plane(3.0));
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
}

#[test]
fn a_material_written_outside_the_crate_renders() {
    let mut app = headless_app(96, 96).unwrap();
    app.add_plugin(MaterialPlugin::<Tinted>::default());
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
    spawn_cube_over_floor(&mut app);
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

/// The example's cube over a lit floor, lit by a sun that casts scene shadows.
fn tinted_scene(size: u32) -> pom::App {
    let mut app = headless_app(size, size).unwrap();
    app.add_plugin(MaterialPlugin::<Tinted>::default());
    app.world.spawn((
        pom::Camera::perspective(45.0),
        Transform::from_xyz(1.6, 1.8, 2.4).looking_at(Vec3::ZERO, Vec3::Y),
    ));
    // From behind the cube: its shadow falls towards the camera.
    app.world.spawn((
        DirectionalLight::default(),
        pom::LightShadows::default(),
        Transform::IDENTITY.looking_at(Vec3::new(0.5, -1.0, 0.6), Vec3::Y),
    ));
    spawn_cube_over_floor(&mut app);
    app
}

#[test]
fn the_example_runs_on_the_deferred_path_as_it_does_forward() {
    let mut app = tinted_scene(96);
    let deferred = render_on_path(&mut app, RenderPath::Deferred).unwrap();
    let renderer = app.resources.get::<Renderer>().unwrap();
    assert!(
        renderer.runs_deferred(),
        "the frame ran forward: {:?}",
        renderer.deferred_unavailable()
    );
    let forward = render_on_path(&mut app, RenderPath::Forward).unwrap();
    assert!(!app.resources.get::<Renderer>().unwrap().runs_deferred());
    let flip = pom::flip_compare(&forward, &deferred, 0.99).unwrap();
    assert!(
        flip.mean <= pom_tests::PATHS_AGREE_MEAN,
        "deferred differs from forward: FLIP mean {}",
        flip.mean
    );
}

#[test]
fn the_example_casts_a_scene_shadow_on_both_paths() {
    for path in [RenderPath::Forward, RenderPath::Deferred] {
        let mut app = tinted_scene(96);
        let shadowed = render_on_path(&mut app, path).unwrap();
        let cube = app
            .world
            .query::<(pom::hecs::Entity, &Tinted)>()
            .iter()
            .map(|(entity, _)| entity)
            .next()
            .unwrap();
        app.world.insert_one(cube, pom::NotShadowCaster).unwrap();
        let unshadowed = render_on_path(&mut app, path).unwrap();
        let darker = shadowed
            .pixels()
            .zip(unshadowed.pixels())
            .filter(|(with, without)| with.0[1] + 20 < without.0[1])
            .count();
        assert!(
            darker > 100,
            "{path:?}: only {darker} pixels fell in the cube's shadow"
        );
    }
}

/// A material of the example's uniform, named `$name`, with its own shading file `$wgsl`
/// (composed after the core's FRAME and MESH_VERTEX), and the given surface capability and
/// deferred shader.
macro_rules! test_material {
    ($ty:ident, $name:literal, $wgsl:expr, on_polygon: $on_polygon:expr, deferred: $deferred:expr) => {
        #[derive(Clone, Debug, Default, PartialEq)]
        struct $ty(Tinted);

        impl pom::Material for $ty {
            type Uniform = <Tinted as pom::Material>::Uniform;
            type Key = ();
            const NAME: &'static str = $name;
            const UNIFORM_WGSL_NAME: &'static str = "TintedUniform";
            const TEXTURE_SLOTS: &'static [pom::render::DefaultTexture] = &[];
            const SURFACE_ON_POLYGON: bool = $on_polygon;
            fn shader() -> ComposedShader {
                ComposedShader {
                    name: $name,
                    constants: &[],
                    files: &[
                        shaders::FRAME,
                        shaders::MESH_VERTEX,
                        shaders::WgslFile {
                            path: concat!($name, ".wgsl"),
                            source: $wgsl,
                        },
                    ],
                }
            }
            fn deferred_shader() -> Option<ComposedShader> {
                let deferred: fn() -> Option<ComposedShader> = $deferred;
                deferred()
            }
            fn textures(&self) -> pom::material::MaterialTextures {
                self.0.textures()
            }
            fn key(&self) {}
            fn fragment(_: ()) -> pom::material::FragmentVariant {
                pom::material::FragmentVariant::entry("fs_main")
            }
            fn uniform(
                &self,
                textures: &[Option<pom::material::TextureFacts>;
                     pom::material::MAX_MATERIAL_TEXTURES],
            ) -> Self::Uniform {
                self.0.uniform(textures)
            }
        }
    };
}

const TINTED_SHADING: &str = "struct TintedUniform { color: vec4<f32> }
@group(0) @binding(2) var<storage, read> materials: array<TintedUniform>;
@fragment
fn fs_main(in: VertexOut) -> @location(0) vec4<f32> { return materials[in.object_index].color; }";

test_material!(ForwardOnly, "forward only", TINTED_SHADING, on_polygon: true, deferred: || None);
test_material!(
    Misspelt,
    "misspelt",
    "struct TintedUniform { color: vec4<f32> }
@group(0) @binding(2) var<storage, read> materials: array<TintedUniform>;
@fragment
fn fs_main(in: VertexOut) -> @location(0) vec4<f32> {
    return materials[in.object_index].colour;
}",
    on_polygon: true,
    deferred: || None
);
test_material!(
    SecretlyCut,
    "secretly cut",
    "struct TintedUniform { color: vec4<f32> }
@group(0) @binding(2) var<storage, read> materials: array<TintedUniform>;
@fragment
fn fs_main(in: VertexOut) -> @location(0) vec4<f32> {
    let color = materials[in.object_index].color;
    if color.a < 0.5 { discard; }
    return color;
}",
    on_polygon: true,
    deferred: || None
);

#[test]
fn a_material_that_opts_out_of_the_deferred_path_renders_forward_and_says_why() {
    let mut app = headless_app(32, 32).unwrap();
    app.add_plugin(MaterialPlugin::<ForwardOnly>::default());
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
        .spawn((cube, ForwardOnly::default(), Transform::IDENTITY));
    render_on_path(&mut app, RenderPath::Deferred).unwrap();
    let renderer = app.resources.get::<Renderer>().unwrap();
    assert!(!renderer.runs_deferred());
    let reason = renderer.deferred_unavailable().unwrap().to_string();
    assert!(reason.contains("forward only"), "{reason}");
}

#[test]
fn a_shader_that_does_not_compile_is_an_error_naming_the_material_file_and_line() {
    let mut app = headless_app(8, 8).unwrap();
    app.add_plugin(MaterialPlugin::<Misspelt>::default());
    let error = app.finish().unwrap_err().to_string();
    assert!(
        error.contains("the shader of material misspelt does not compile: misspelt.wgsl line 5:"),
        "{error}"
    );
    // Nothing of the material was made: a frame still renders (without it).
    app.world.spawn((
        pom::Camera::perspective(45.0),
        Transform::from_xyz(0.0, 0.0, 2.0),
    ));
    assert!(
        app.update().is_err(),
        "finish keeps failing: the material never half-starts"
    );
}

#[test]
fn a_material_that_discards_but_says_its_surface_is_on_its_polygon_is_an_error() {
    let mut app = headless_app(8, 8).unwrap();
    app.add_plugin(MaterialPlugin::<SecretlyCut>::default());
    let error = app.finish().unwrap_err().to_string();
    assert!(
        error.contains(
            "material secretly cut says its surface lies on its polygon (Material::SURFACE_ON_POLYGON), but its fragment entry fs_main discards"
        ),
        "{error}"
    );
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
