//! Pipelines compiled on worker threads (`PipelineCompilation::background`, what windows use):
//! the frame that first uses a variant does not wait for its compile but draws the material's
//! fallback (normal mapping, for the parallax material); once the compile is in, the variant
//! draws as a blocking compile would have drawn it from the start.

use pom::glam::Vec3;
use pom::gpu::{PipelineCompilation, wait_for_pipelines};
use pom::material::pipelines_ready;
use pom::{
    App, Assets, Camera, DirectionalLight, HeightSource, Image, Material, Mesh, ParallaxMethod,
    ParallaxOcclusionMaterial, PomPlugin, RenderPlugin, ShadowMode, Transform, patterns,
};
use pom_tests::render_and_capture;

const SIZE: u32 = 96;

/// A lit brick plane seen at an angle, its material `material`.
fn scene(
    compilation: PipelineCompilation,
    material: impl Fn(&mut App) -> ParallaxOcclusionMaterial,
) -> App {
    let mut app = App::new();
    app.insert_resource(compilation);
    app.add_plugin(RenderPlugin::new(SIZE, SIZE))
        .add_plugin(PomPlugin);
    let material = material(&mut app);
    let plane = app
        .resources
        .get_or_default::<Assets<Mesh>>()
        .add(Mesh::plane(2.0));
    app.world.spawn((plane, material, Transform::IDENTITY));
    let eye = Transform::from_xyz(0.0, 1.2, 1.6).looking_at(Vec3::ZERO, Vec3::Y);
    app.world.spawn((Camera::perspective(45.0), eye));
    let sun = Transform::IDENTITY.looking_at(Vec3::new(1.0, -1.0, -1.0), Vec3::Y);
    app.world.spawn((DirectionalLight::default(), sun));
    app
}

fn bricks(app: &mut App) -> ParallaxOcclusionMaterial {
    let height = patterns::bricks(128, 4.0, 8.0);
    let images = app.resources.get_or_default::<Assets<Image>>();
    ParallaxOcclusionMaterial {
        normal_map: Some(images.add(height.normal_map(0.08))),
        height_map: Some(HeightSource::Texture(images.add(height.to_image()))),
        height_scale: 0.08,
        ..ParallaxOcclusionMaterial::default()
    }
}

fn with_modes(
    method: ParallaxMethod,
    shadows: ShadowMode,
) -> impl Fn(&mut App) -> ParallaxOcclusionMaterial {
    move |app| ParallaxOcclusionMaterial {
        method,
        shadows,
        ..bricks(app)
    }
}

fn flip_mean(a: &image::RgbaImage, b: &image::RgbaImage) -> f32 {
    pom::flip_compare(a, b, 0.99).expect("same size").mean
}

#[test]
fn a_new_variant_draws_its_fallback_without_waiting_then_itself() {
    let mut app = scene(PipelineCompilation::background(), bricks);
    // The first frame's variants compile in it: the app's loading frame.
    render_and_capture(&mut app).unwrap();
    let switched = ParallaxOcclusionMaterial {
        method: ParallaxMethod::MaxMip,
        shadows: ShadowMode::Hard,
        ..ParallaxOcclusionMaterial::default()
    };
    for material in app.world.query_mut::<&mut ParallaxOcclusionMaterial>() {
        material.method = switched.method;
        material.shadows = switched.shadows;
    }
    let key = app
        .world
        .query_mut::<&ParallaxOcclusionMaterial>()
        .into_iter()
        .map(|material| material.key())
        .next()
        .unwrap();
    let while_compiling = render_and_capture(&mut app).unwrap();
    assert!(
        !pipelines_ready::<ParallaxOcclusionMaterial>(&app.resources, key),
        "the frame that first used MaxMip waited for its pipelines"
    );
    let normal_mapped = render_and_capture(&mut scene(
        PipelineCompilation::blocking(),
        with_modes(ParallaxMethod::NormalMapping, ShadowMode::Off),
    ))
    .unwrap();
    let fallback_error = flip_mean(&normal_mapped, &while_compiling);
    assert!(
        fallback_error < 0.01,
        "the waiting frame is not the normal-mapped fallback: FLIP mean {fallback_error}"
    );

    wait_for_pipelines(&app.resources);
    let compiled = render_and_capture(&mut app).unwrap();
    assert!(pipelines_ready::<ParallaxOcclusionMaterial>(
        &app.resources,
        key
    ));
    let blocking = render_and_capture(&mut scene(
        PipelineCompilation::blocking(),
        with_modes(ParallaxMethod::MaxMip, ShadowMode::Hard),
    ))
    .unwrap();
    let compiled_error = flip_mean(&blocking, &compiled);
    assert!(
        compiled_error < 0.001,
        "MaxMip compiled in the background draws otherwise: FLIP mean {compiled_error}"
    );
    assert!(
        flip_mean(&normal_mapped, &compiled) > 0.01,
        "MaxMip and normal mapping look alike here: the test shows nothing"
    );
}
