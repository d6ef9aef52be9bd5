//! Per-pixel LOD (T §5.4.3): past the threshold only normal mapping runs; the band blends smoothly.

use pom::preview::PreviewView;
use pom::{DebugView, ParallaxMethod, ParallaxOcclusionMaterial, TargetFormat, patterns};
use pom_tests::pom_scene::{HeightMaterial, preview_app};
use pom_tests::{FlipTolerance, render_and_capture};

fn cobblestones() -> HeightMaterial {
    HeightMaterial {
        field: patterns::cobblestones(128, 4),
        height_scale: 0.05,
    }
}

fn render(
    view: &PreviewView,
    configure: impl FnOnce(ParallaxOcclusionMaterial) -> ParallaxOcclusionMaterial,
) -> image::RgbaImage {
    let mut app = preview_app(64, TargetFormat::Srgb8, &cobblestones(), view, configure).unwrap();
    render_and_capture(&mut app).unwrap()
}

#[test]
fn past_the_threshold_pom_renders_as_normal_mapping_and_marches_nothing() {
    // 32 repeats of a 128² texture on 64 pixels: 64 texels per pixel, mip level 6 > 4.
    let view = PreviewView {
        view_angle: 45.0,
        tiling: 32.0,
        ..PreviewView::default()
    };
    let pom = render(&view, |material| material);
    let normal_mapping = render(&view, |material| ParallaxOcclusionMaterial {
        method: ParallaxMethod::NormalMapping,
        ..material
    });
    let tight = FlipTolerance {
        mean: 0.01,
        percentile: 0.99,
        percentile_max: 0.05,
    };
    pom_tests::compare_images(
        "far field POM vs normal mapping",
        &normal_mapping,
        &pom,
        tight,
    )
    .unwrap();
    let samples = render(&view, |material| ParallaxOcclusionMaterial {
        debug_view: DebugView::Samples,
        ..material
    });
    assert!(
        samples.pixels().all(|p| p.0[..3] == [0, 0, 0]),
        "some pixel took march samples past the LOD threshold"
    );
}

fn mean_abs_difference(a: &image::RgbaImage, b: &image::RgbaImage) -> f32 {
    let total: u64 = a
        .as_raw()
        .iter()
        .zip(b.as_raw())
        .map(|(x, y)| u64::from(x.abs_diff(*y)))
        .sum();
    total as f32 / a.as_raw().len() as f32
}

/// Lit renders as the LOD threshold falls from 4 to 3 in eight steps past a constant mip level
/// of 3; returns how much of the total change the largest step holds.
fn largest_step_share(band: f32) -> f32 {
    // 4 repeats of 128 texels on 64 pixels: mip level 3 everywhere in this orthographic view.
    let view = PreviewView {
        view_angle: 50.0,
        light_angle: 50.0,
        light_azimuth: 40.0,
        tiling: 4.0,
        ..PreviewView::default()
    };
    let frames: Vec<image::RgbaImage> = (0..=8)
        .map(|step| {
            // With band 1, fade = (mip − (threshold − 1)) / 1 = step / 8.
            let threshold = 4.0 - step as f32 / 8.0;
            render(&view, |material| ParallaxOcclusionMaterial {
                lod_threshold: threshold,
                lod_band: band,
                ..material
            })
        })
        .collect();
    let total = mean_abs_difference(&frames[0], &frames[8]);
    assert!(
        total > 1.0,
        "POM and normal mapping should differ here ({total})"
    );
    let largest = frames
        .windows(2)
        .map(|pair| mean_abs_difference(&pair[0], &pair[1]))
        .fold(0.0, f32::max);
    largest / total
}

#[test]
fn the_lod_band_fades_without_a_seam() {
    let smooth = largest_step_share(1.0);
    eprintln!(
        "largest of 8 steps through the band: {:.0} % of the change",
        smooth * 100.0
    );
    assert!(
        smooth < 0.35,
        "one step holds {smooth} of the change: a seam"
    );
    // The same measure catches a hard switch, so it can fail.
    let hard = largest_step_share(0.01);
    eprintln!("with a 0.01-level band: {:.0} %", hard * 100.0);
    assert!(hard > 0.9);
}

/// A perspective view of the cobblestones at `tiling` repeats, with the `mip` debug view in
/// floats: whether the draw was switched to the normal-mapping pipeline, and the lowest mip
/// level any surface pixel computed.
fn switched_and_lowest_mip(tiling: f32, distance: f32) -> (bool, f32) {
    let view = PreviewView {
        view_angle: 60.0,
        projection: pom::preview::PreviewProjection::Perspective,
        tiling,
        distance,
        ..PreviewView::default()
    };
    let mut app = preview_app(
        64,
        TargetFormat::Float32,
        &cobblestones(),
        &view,
        |material| ParallaxOcclusionMaterial {
            lod_threshold: 2.0,
            debug_view: DebugView::Mip,
            ..material
        },
    )
    .unwrap();
    for camera in app.world.query_mut::<&mut pom::Camera>() {
        // Alpha 0 marks the background.
        camera.clear_color = pom::Color {
            a: 0.0,
            ..pom::Color::BLACK
        };
    }
    let image = pom_tests::render_and_capture_f32(&mut app).unwrap();
    let keys = pom::material::drawn_keys::<ParallaxOcclusionMaterial>(&app.resources);
    let normal_mapping = pom::parallax::PomPipelineKey::of(&ParallaxOcclusionMaterial {
        method: ParallaxMethod::NormalMapping,
        ..ParallaxOcclusionMaterial::default()
    })
    .method;
    let switched = keys[0].method == normal_mapping;
    // The view shows mip / (levels − 1); a 128² map has 8 levels.
    let lowest = image
        .pixels()
        .filter(|p| p.0[3] > 0.0)
        .map(|p| p.0[0] * 7.0)
        .fold(f32::INFINITY, f32::min);
    (switched, lowest)
}

#[test]
fn a_draw_switches_to_normal_mapping_only_where_every_pixel_is_past_the_threshold() {
    let mut seen = Vec::new();
    for (tiling, distance) in [
        (1.0, 1.0),
        (4.0, 1.0),
        (16.0, 1.0),
        (64.0, 2.0),
        (256.0, 4.0),
    ] {
        let (switched, lowest) = switched_and_lowest_mip(tiling, distance);
        if switched {
            assert!(
                lowest >= 2.0 - 1e-3,
                "tiling {tiling} at distance {distance}: switched, yet a pixel is at mip {lowest}"
            );
        }
        eprintln!("tiling {tiling}, distance {distance}: switched {switched}, lowest mip {lowest}");
        seen.push(switched);
    }
    assert!(!seen[0], "a close plane keeps its march");
    assert!(seen[4], "a far, densely tiled plane drops it");
}
