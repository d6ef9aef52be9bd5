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
