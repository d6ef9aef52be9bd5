//! The split view's second image: the same scene with material overrides, the world and the
//! main image untouched.

use pom::gpu::read_rgba8;
use pom::preview::PreviewView;
use pom::render::RenderTarget;
use pom::{
    GpuContext, ParallaxMethod, ParallaxOcclusionMaterial, SplitView, TargetFormat, patterns,
    render_split_view,
};
use pom_tests::in_error_scopes;
use pom_tests::pom_scene::{HeightMaterial, preview_app};

fn app() -> pom::App {
    let material = HeightMaterial {
        field: patterns::bricks(64, 4.0, 8.0),
        height_scale: 0.08,
    };
    preview_app(
        48,
        TargetFormat::Srgb8,
        &material,
        &PreviewView::default(),
        |m| m,
    )
    .unwrap()
}

/// One frame, the split view's second render, and both images read back.
fn render_both(app: &mut pom::App) -> (image::RgbaImage, image::RgbaImage) {
    in_error_scopes(app, "split view", |app| {
        app.update()?;
        render_split_view(app).map_err(|error| pom_tests::HarnessError::Gpu {
            during: "split view",
            error: error.to_string(),
        })?;
        let main = pom::capture(app)?;
        let gpu = app.resources.get::<GpuContext>().unwrap();
        let split = app.resources.get::<SplitView>().unwrap();
        let second: &RenderTarget = split.target.as_ref().expect("the second target was made");
        assert_eq!(second.size(), (48, 48));
        let second = read_rgba8(gpu, &second.color).map_err(pom::RenderError::from)?;
        Ok((main, second))
    })
    .unwrap()
}

#[test]
fn without_overrides_both_images_are_the_same() {
    let mut app = app();
    app.insert_resource(SplitView::default());
    let (main, second) = render_both(&mut app);
    assert!(main == second);
}

#[test]
fn an_override_changes_only_the_second_image_and_not_the_world() {
    let mut app = app();
    let (entity, original) = app
        .world
        .query::<(pom::hecs::Entity, &ParallaxOcclusionMaterial)>()
        .iter()
        .map(|(entity, material)| (entity, material.clone()))
        .next()
        .unwrap();
    let mut split = SplitView::default();
    split.overrides.insert(
        entity,
        ParallaxOcclusionMaterial {
            method: ParallaxMethod::NormalMapping,
            ..original.clone()
        },
    );
    app.insert_resource(split);
    let (main, second) = render_both(&mut app);
    let changed = pom_tests::differing_pixels(&main, &second);
    assert!(changed > 100, "only {changed} pixels differ");
    assert_eq!(
        *app.world.get::<&ParallaxOcclusionMaterial>(entity).unwrap(),
        original,
        "the world keeps method A"
    );
    // The main image is what the scene looks like without any split view.
    app.resources.remove::<SplitView>();
    app.update().unwrap();
    assert!(pom::capture(&app).unwrap() == main);
}

#[test]
fn the_second_image_is_not_timed() {
    let mut app = app();
    pom::gpu::set_gpu_timing(&mut app.resources, Some(pom::TimingMode::Blocking));
    app.insert_resource(SplitView::default());
    let frame_of = |app: &pom::App| match app.resources.get::<pom::GpuTimings>() {
        Some(pom::GpuTimings::Supported { frame, .. }) => Some(*frame),
        _ => None,
    };
    render_both(&mut app);
    let after_first = frame_of(&app);
    render_both(&mut app);
    // lavapipe has timestamps; where an adapter has none there is nothing to keep apart.
    if let (Some(first), Some(second)) = (after_first, frame_of(&app)) {
        assert_eq!(
            second,
            first + 1,
            "one timed frame per update, none per split image"
        );
        assert!(app.resources.get::<pom::gpu::GpuTimer>().is_some());
    }
}
