//! Dynamic height fields: heights rewritten every frame, normals derived on the GPU.

use pom::gpu::read_rgba8;
use pom::preview::{PreviewView, spawn_preview};
use pom::render::Renderer;
use pom::{
    Assets, Channel, DynamicHeightField, GpuContext, HeightConvention, HeightField, HeightSource,
    Image, ParallaxOcclusionMaterial, TargetFormat,
};
use pom_tests::pom_scene::pom_app;
use pom_tests::{render_and_capture, render_both_paths};

const SIZE: u32 = 48;
const HEIGHT_SCALE: f32 = 0.04;

/// Expanding ripples: rings around the centre, `radius` the position of the outer crest.
fn ripples(radius: f32) -> HeightField {
    HeightField::from_fn(SIZE, SIZE, move |u, v| {
        let distance = ((u - 0.5).powi(2) + (v - 0.5).powi(2)).sqrt();
        let wave = ((distance - radius) * 40.0).cos() * 0.5 + 0.5;
        let envelope = (1.0 - (distance - radius).abs() * 6.0).max(0.0);
        0.5 + 0.5 * (wave - 0.5) * envelope
    })
}

fn setup() -> (pom::App, DynamicHeightField) {
    let mut app = pom_app(64, TargetFormat::Srgb8).unwrap();
    let images = app.resources.get_mut::<Assets<Image>>().unwrap();
    let field = DynamicHeightField::new(images, &ripples(0.1), HEIGHT_SCALE).unwrap();
    let material = ParallaxOcclusionMaterial {
        normal_map: Some(field.normal.clone()),
        height_map: Some(HeightSource::Texture(field.height.clone())),
        height_scale: HEIGHT_SCALE,
        ..ParallaxOcclusionMaterial::default()
    };
    let view = PreviewView {
        view_angle: 40.0,
        light_angle: 60.0,
        light_azimuth: 20.0,
        ..PreviewView::default()
    };
    spawn_preview(&mut app, material, &view).unwrap();
    let plane = app
        .world
        .query::<(pom::hecs::Entity, &ParallaxOcclusionMaterial)>()
        .iter()
        .map(|(entity, _)| entity)
        .next()
        .unwrap();
    app.world.insert_one(plane, field.clone()).unwrap();
    (app, field)
}

fn gpu_normals(app: &pom::App, field: &DynamicHeightField) -> image::RgbaImage {
    let gpu = app.resources.get::<GpuContext>().unwrap();
    let renderer = app.resources.get::<Renderer>().unwrap();
    read_rgba8(gpu, renderer.gpu_texture(field.normal.id()).unwrap()).unwrap()
}

#[test]
fn gpu_normals_match_the_cpu_sobel_filter() {
    let (mut app, field) = setup();
    render_and_capture(&mut app).unwrap();
    let gpu = gpu_normals(&app, &field);
    let images = app.resources.get::<Assets<Image>>().unwrap();
    let heights = HeightField::from_image(
        images.get(&field.height).unwrap(),
        Channel::Red,
        HeightConvention::Height,
    );
    let cpu = heights.normal_map(HEIGHT_SCALE).to_rgba8();
    let worst = gpu
        .as_raw()
        .iter()
        .zip(cpu.as_raw())
        .map(|(a, b)| a.abs_diff(*b))
        .max()
        .unwrap();
    assert!(worst <= 1, "GPU and CPU Sobel differ by {worst} levels");
    assert!(
        gpu.pixels().any(|p| p.0 != [128, 128, 255, 255]),
        "the ripples tilt the normals"
    );
}

#[test]
fn rewriting_the_heights_changes_the_next_frame() {
    let (mut app, field) = setup();
    let mut previous = render_and_capture(&mut app).unwrap();
    let mut previous_normals = gpu_normals(&app, &field);
    for frame in 1..4 {
        let heights = ripples(0.1 + 0.08 * frame as f32).to_image_16();
        *app.resources
            .get_mut::<Assets<Image>>()
            .unwrap()
            .get_mut(&field.height)
            .unwrap() = heights;
        // The deferred resolve reads the rewritten heights as the fragment stage does.
        let image = render_both_paths(&mut app, "dynamic_height").unwrap();
        let normals = gpu_normals(&app, &field);
        assert!(
            image != previous,
            "frame {frame}: the capture did not change"
        );
        assert!(
            normals != previous_normals,
            "frame {frame}: the normals did not follow"
        );
        previous = image;
        previous_normals = normals;
    }
}
