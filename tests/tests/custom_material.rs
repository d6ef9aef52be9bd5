//! The material seam, proved from outside the `pom` crate: the material of the README and of
//! "Writing your own material" (plugin/docs/custom-material.md; `custom_material/matte.rs` and
//! `matte.wgsl`, kept identical to the documents by a test) renders on both paths, casts and
//! receives scene shadows; a second one written the same way (`custom_material/screen.rs`, a
//! texture and two parameters) renders against a reference; bad materials fail when their
//! plugin starts, and a material of its own entry points (the escape hatch) still works.

#[rustfmt::skip]
#[path = "custom_material/matte.rs"]
pub(crate) mod matte;
#[rustfmt::skip]
#[path = "custom_material/screen.rs"]
mod screen;
#[rustfmt::skip]
#[path = "custom_material/lattice.rs"]
pub(crate) mod lattice;

use lattice::Lattice;
use matte::Matte;
use pom::glam::Vec3;
use pom::material::{DeclaredMaterial, check_material_layout};
use pom::render::Renderer;
use pom::render::shaders::{self, ComposedShader};
use pom::{Assets, Color, DirectionalLight, MaterialPlugin, Mesh, RenderPath, Transform};
use pom_tests::sources::fenced_block;
use pom_tests::{FlipTolerance, check_golden, headless_app, render_on_path};
use screen::Screen;

/// The example's orange cube standing on a grey floor, both `Matte`.
fn spawn_cube_over_floor(app: &mut pom::App) {
    let meshes = app.resources.get_mut::<Assets<Mesh>>().unwrap();
    let cube = meshes.add(Mesh::cube(0.8));
    let floor = meshes.add(Mesh::plane(3.0));
    app.world.spawn((
        floor,
        Matte {
            color: Color::linear_rgb(0.5, 0.5, 0.5),
        },
        Transform::from_xyz(0.0, -0.4, 0.0),
    ));
    app.world.spawn((
        cube,
        Matte {
            color: Color::linear_rgb(0.9, 0.35, 0.05),
        },
        Transform::IDENTITY,
    ));
}

/// The example's cube over its floor, lit by a sun that casts scene shadows.
fn matte_scene(size: u32) -> pom::App {
    let mut app = headless_app(size, size).unwrap();
    app.add_plugin(MaterialPlugin::<Matte>::default());
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
fn the_example_resolves_on_the_deferred_path_as_it_renders_forward() {
    let mut app = matte_scene(96);
    let deferred = render_on_path(&mut app, RenderPath::Deferred).unwrap();
    let renderer = app.resources.get::<Renderer>().unwrap();
    assert!(
        renderer.runs_deferred(),
        "the frame ran forward: {:?}",
        renderer.deferred_unavailable()
    );
    // It shades in the compute resolve: no opaque raster pass drew it.
    assert_eq!(
        pom::material::drawn_in_opaque_and_resolve::<Matte>(&app.resources),
        (false, true)
    );
    let forward = render_on_path(&mut app, RenderPath::Forward).unwrap();
    assert!(!app.resources.get::<Renderer>().unwrap().runs_deferred());
    let flip = pom::flip_compare(&forward, &deferred, 0.99).unwrap();
    assert!(
        flip.mean <= pom_tests::PATHS_AGREE_MEAN,
        "deferred differs from forward: FLIP mean {}",
        flip.mean
    );
    check_golden("custom_material", &forward, FlipTolerance::default()).unwrap();
}

#[test]
fn the_example_casts_and_receives_a_scene_shadow_on_both_paths() {
    for path in [RenderPath::Forward, RenderPath::Deferred] {
        let mut app = matte_scene(96);
        let shadowed = render_on_path(&mut app, path).unwrap();
        // The floor, a `Matte` too, darkens where the cube's shadow falls on it.
        let cube = app
            .world
            .query::<(pom::hecs::Entity, &Matte)>()
            .iter()
            .find(|(_, matte)| matte.color.r > 0.8)
            .map(|(entity, _)| entity)
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

#[test]
fn a_material_with_a_texture_and_parameters_renders_on_both_paths() {
    let mut app = headless_app(96, 96).unwrap();
    app.add_plugin(MaterialPlugin::<Screen>::default());
    let picture = pom_tests::fixtures::checker_albedo(64, 8, [230, 200, 40], [30, 60, 200]);
    let picture = app
        .resources
        .get_or_default::<Assets<pom::Image>>()
        .add(picture);
    let plane = app
        .resources
        .get_mut::<Assets<Mesh>>()
        .unwrap()
        .add(Mesh::plane(2.0));
    // Seen at a slant, so the picture's far cells shrink to a few pixels (its mips show).
    app.world.spawn((
        pom::Camera::perspective(45.0),
        pom::Tonemapping::None,
        Transform::from_xyz(0.0, 0.9, 1.6).looking_at(Vec3::new(0.0, 0.0, -0.3), Vec3::Y),
    ));
    app.world.spawn((
        plane,
        Screen {
            picture: Some(picture),
            tint: Color::linear_rgb(1.0, 0.8, 0.8),
            brightness: 1.5,
        },
        Transform::IDENTITY,
    ));
    let image = pom_tests::render_both_paths(&mut app, "custom_material_screen").unwrap();
    check_golden("custom_material_screen", &image, FlipTolerance::default()).unwrap();
    // Parameters out of their limits are clamped and named, as for the shipped materials.
    let bad = Screen {
        brightness: f32::NAN,
        ..Screen::default()
    };
    assert_eq!(bad.params().brightness, 1.0);
    assert!(
        bad.parameter_problems()[0].contains("brightness"),
        "{:?}",
        bad.parameter_problems()
    );
}

/// A lattice plate at `hole_radius` over a `Matte` floor, under a sun that casts scene shadows,
/// seen from above at a slant.
fn lattice_scene(hole_radius: f32) -> pom::App {
    let mut app = headless_app(96, 96).unwrap();
    app.add_plugin(MaterialPlugin::<Matte>::default())
        .add_plugin(MaterialPlugin::<Lattice>::default());
    let meshes = app.resources.get_mut::<Assets<Mesh>>().unwrap();
    let (plate, floor) = (meshes.add(Mesh::plane(1.6)), meshes.add(Mesh::plane(4.0)));
    app.world.spawn((
        floor,
        Matte {
            color: Color::linear_rgb(0.2, 0.6, 0.2),
        },
        Transform::from_xyz(0.0, -0.5, 0.0),
    ));
    app.world.spawn((
        plate,
        Lattice {
            color: Color::linear_rgb(0.8, 0.8, 0.8),
            hole_radius,
            ..Lattice::default()
        },
        Transform::IDENTITY,
    ));
    app.world.spawn((
        pom::Camera::perspective(45.0),
        Transform::from_xyz(0.0, 2.2, 1.6).looking_at(Vec3::new(0.0, -0.2, 0.0), Vec3::Y),
    ));
    app.world.spawn((
        DirectionalLight::default(),
        pom::LightShadows::default(),
        Transform::IDENTITY.looking_at(Vec3::new(0.3, -1.0, -0.2), Vec3::Y),
    ));
    app
}

#[test]
fn a_material_that_cuts_holes_says_so_and_runs_on_both_paths() {
    let mut app = lattice_scene(0.3);
    let holed = render_on_path(&mut app, RenderPath::Deferred).unwrap();
    assert!(app.resources.get::<Renderer>().unwrap().runs_deferred());
    // Its holes are decided in the visibility pass; what is left shades in the resolve.
    assert_eq!(
        pom::material::drawn_in_opaque_and_resolve::<Lattice>(&app.resources),
        (false, true)
    );
    let forward = render_on_path(&mut app, RenderPath::Forward).unwrap();
    let flip = pom::flip_compare(&forward, &holed, 0.99).unwrap();
    assert!(
        flip.mean <= pom_tests::PATHS_AGREE_MEAN,
        "deferred differs from forward: FLIP mean {}",
        flip.mean
    );
    check_golden(
        "custom_material_lattice",
        &forward,
        FlipTolerance::default(),
    )
    .unwrap();
    // Through the holes: the green floor, and sunlight on it where the plate's shadow has holes.
    let mut solid_app = lattice_scene(0.0);
    let solid = render_on_path(&mut solid_app, RenderPath::Deferred).unwrap();
    let green = |image: &image::RgbaImage| {
        image
            .pixels()
            .filter(|pixel| i32::from(pixel.0[1]) > i32::from(pixel.0[0]) + 30)
            .count()
    };
    assert!(
        green(&holed) > green(&solid) + 200,
        "the floor shows through the holes: {} green pixels against {} without holes",
        green(&holed),
        green(&solid)
    );
}

#[test]
fn the_examples_parameters_match_their_wgsl() {
    assert_eq!(check_material_layout::<Matte>(), Ok(()));
    assert_eq!(check_material_layout::<Screen>(), Ok(()));
    assert_eq!(check_material_layout::<Lattice>(), Ok(()));
}

/// A material of its own entry points (the escape hatch) with the example's parameters, named `$name`, with its own shading file `$wgsl`
/// (composed after the core's FRAME and MESH_VERTEX), and the given surface capability and
/// deferred shader.
macro_rules! test_material {
    ($ty:ident, $name:literal, $wgsl:expr, on_polygon: $on_polygon:expr, deferred: $deferred:expr) => {
        #[derive(Clone, Debug, Default, PartialEq)]
        struct $ty(Matte);

        impl pom::Material for $ty {
            type PerDraw = <Matte as DeclaredMaterial>::Params;
            type Key = ();
            const NAME: &'static str = $name;
            const PER_DRAW_WGSL_NAME: &'static str = "MaterialParams";
            const TEXTURE_SLOTS: &'static [pom::gpu::DefaultTexture] = &[];
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
                self.0.texture_images()
            }
            fn key(&self) {}
            fn fragment(_: ()) -> pom::material::ShaderEntry {
                pom::material::ShaderEntry::entry("fs_main")
            }
            fn per_draw(
                &self,
                _: &[Option<pom::material::TextureFacts>; pom::material::MAX_MATERIAL_TEXTURES],
            ) -> Self::PerDraw {
                self.0.params()
            }
        }
    };
}

const TINTED_SHADING: &str = "struct MaterialParams { color: array<f32, 4> }
@group(0) @binding(2) var<storage, read> materials: array<MaterialParams>;
@fragment
fn fs_main(in: VertexOut) -> @location(0) vec4<f32> { return vec4<f32>(materials[in.object_index].color[0]); }";

/// Shaded materials that cannot work: each fails when its plugin starts.
mod bad {
    use pom::prelude::*;

    pom::material_parameters! {
        /// `shade` names a parameter that does not exist, on line 3 of its file.
        #[derive(Clone, Debug, PartialEq)]
        pub struct Misshaded {
            parameters {
                /// A colour.
                color: Color = Color::WHITE, ParamSpec::color();
            }
        }
    }
    impl ShadedMaterial for Misshaded {
        const SHADING: WgslFile = WgslFile::new(
            "misshaded.wgsl",
            "// A typo.
fn shade(surface: SurfaceInput, material: MaterialParams) -> vec4<f32> {
    return rgba(material.colour);
}",
        );
    }

    pom::material_parameters! {
        /// One texture more than a material binds.
        #[derive(Clone, Debug, PartialEq)]
        pub struct Crowded {
            textures {
                /// 1.
                a: WhiteSrgb,
                /// 2.
                b: WhiteSrgb,
                /// 3.
                c: WhiteSrgb,
                /// 4.
                d: WhiteSrgb,
                /// 5.
                e: WhiteSrgb,
                /// 6.
                f: WhiteSrgb,
                /// 7.
                g: WhiteSrgb,
                /// 8.
                h: WhiteSrgb,
                /// 9.
                i: WhiteSrgb,
                /// 10.
                j: WhiteSrgb,
                /// 11.
                k: WhiteSrgb,
            }
            parameters {
                /// A colour.
                color: Color = Color::WHITE, ParamSpec::color();
            }
        }
    }
    impl ShadedMaterial for Crowded {
        const SHADING: WgslFile = WgslFile::new(
            "crowded.wgsl",
            "fn shade(surface: SurfaceInput, material: MaterialParams) -> vec4<f32> {
    return texture_at(k, surface);
}",
        );
    }

    pom::material_parameters! {
        /// Cuts holes in its surface, which a shaded material says it never does.
        #[derive(Clone, Debug, PartialEq)]
        pub struct Holed {
            parameters {
                /// A colour.
                color: Color = Color::WHITE, ParamSpec::color();
            }
        }
    }
    impl ShadedMaterial for Holed {
        const SHADING: WgslFile = WgslFile::new(
            "holed.wgsl",
            "fn shade(surface: SurfaceInput, material: MaterialParams) -> vec4<f32> {
    if fract(surface.uv.x * 8.0) < 0.5 {
        discard;
    }
    return rgba(material.color);
}",
        );
    }
}

/// The error the plugin of material `M` gives when the app starts.
fn start_error<M: pom::Material>() -> String {
    let mut app = headless_app(8, 8).unwrap();
    app.add_plugin(MaterialPlugin::<M>::default());
    app.finish().unwrap_err().to_string()
}

#[test]
fn a_shading_function_that_does_not_compile_is_an_error_naming_the_material_file_and_line() {
    let error = start_error::<bad::Misshaded>();
    assert!(
        error.contains("the shader of material Misshaded does not compile: misshaded.wgsl line 3:"),
        "{error}"
    );
}

#[test]
fn a_material_declaring_more_textures_than_a_group_holds_is_an_error() {
    let error = start_error::<bad::Crowded>();
    assert!(
        error.contains("material Crowded declares 11 texture slots; at most 10 are bound"),
        "{error}"
    );
}

#[test]
fn a_shading_function_that_discards_is_an_error() {
    let error = start_error::<bad::Holed>();
    assert!(
        error.contains("material Holed discards in its compute entry cs_resolve"),
        "{error}"
    );
}

test_material!(ForwardOnly, "forward only", TINTED_SHADING, on_polygon: true, deferred: || None);
test_material!(
    Misspelt,
    "misspelt",
    "struct MaterialParams { color: array<f32, 4> }
@group(0) @binding(2) var<storage, read> materials: array<MaterialParams>;
@fragment
fn fs_main(in: VertexOut) -> @location(0) vec4<f32> {
    return vec4<f32>(materials[in.object_index].colour[0]);
}",
    on_polygon: true,
    deferred: || None
);
test_material!(
    SecretlyCut,
    "secretly cut",
    "struct MaterialParams { color: array<f32, 4> }
@group(0) @binding(2) var<storage, read> materials: array<MaterialParams>;
@fragment
fn fs_main(in: VertexOut) -> @location(0) vec4<f32> {
    let alpha = materials[in.object_index].color[3];
    if alpha < 0.5 { discard; }
    return vec4<f32>(alpha);
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
    let error = start_error::<SecretlyCut>();
    assert!(
        error.contains(
            "material secretly cut says its surface lies on its polygon (Material::SURFACE_ON_POLYGON), but its fragment entry fs_main discards"
        ),
        "{error}"
    );
}

#[test]
fn the_readme_and_the_custom_material_doc_show_this_example_verbatim() {
    let rust = include_str!("custom_material/matte.rs");
    let wgsl = include_str!("custom_material/matte.wgsl");
    let readme = include_str!("../../README.md");
    let doc = include_str!("../../plugin/docs/custom-material.md");
    for (name, document, heading) in [
        ("README.md", readme, "## A material of your own"),
        (
            "plugin/docs/custom-material.md",
            doc,
            "# Writing your own material",
        ),
    ] {
        assert_eq!(
            fenced_block(document, heading, "rust"),
            rust,
            "{name}'s material and tests/tests/custom_material/matte.rs differ"
        );
        assert_eq!(
            fenced_block(document, heading, "wgsl"),
            wgsl,
            "{name}'s shading function and tests/tests/custom_material/matte.wgsl differ"
        );
    }
    let covers = fenced_block(doc, "## Cutting holes", "wgsl");
    assert!(
        include_str!("custom_material/lattice.wgsl").contains(covers),
        "custom-material.md's `covers` and tests/tests/custom_material/lattice.wgsl differ"
    );
    // The promise: a material in at most 15 lines of Rust and 10 of WGSL.
    assert!(rust.lines().count() <= 15, "the Rust grew past 15 lines");
    assert!(wgsl.lines().count() <= 10, "the WGSL grew past 10 lines");
}
