//! Measured behaviour of the parallax material: parallax size, shadow placement and penumbra.

use pom::preview::PreviewView;
use pom::{
    DebugView, ParallaxMethod, ParallaxOcclusionMaterial, ShadowMode, TargetFormat, patterns,
};
use pom_tests::pom_scene::{HeightMaterial, preview_app};
use pom_tests::render_and_capture_f32;

const SIZE: u32 = 128;
const HEIGHT_SCALE: f32 = 0.05;
/// The raised block covers u, v in 0.3..0.7.
const BLOCK_SIDE: f32 = 0.4;

fn block() -> HeightMaterial {
    HeightMaterial {
        field: patterns::raised_block(256, BLOCK_SIDE),
        height_scale: HEIGHT_SCALE,
    }
}

fn render(
    view: &PreviewView,
    configure: impl FnOnce(ParallaxOcclusionMaterial) -> ParallaxOcclusionMaterial,
) -> image::Rgba32FImage {
    let mut app = preview_app(SIZE, TargetFormat::Float32, &block(), view, configure).unwrap();
    render_and_capture_f32(&mut app).unwrap()
}

/// The u coordinate each row of the centre column shows, bottom row first (+u runs up).
fn centre_column_u(image: &image::Rgba32FImage) -> Vec<f32> {
    (0..SIZE)
        .rev()
        .map(|y| image.get_pixel(SIZE / 2, y).0[0])
        .collect()
}

#[test]
fn the_floor_behind_a_block_shifts_by_height_scale_times_tan_theta() {
    for angle in [30.0_f32, 60.0, 75.0] {
        let view = PreviewView {
            view_angle: angle,
            ..PreviewView::default()
        };
        let uv_view = |method| {
            render(&view, |material| ParallaxOcclusionMaterial {
                method,
                debug_view: DebugView::Uv,
                max_samples: 128,
                min_samples: 64,
                lod_threshold: 16.0,
                ..material
            })
        };
        let entry = centre_column_u(&uv_view(ParallaxMethod::NormalMapping));
        let parallax = centre_column_u(&uv_view(ParallaxMethod::Occlusion));
        // Rows whose ray reaches the floor past the block's far (+u) edge, clear of its blur.
        let far_edge = 0.5 + BLOCK_SIDE / 2.0;
        let shifts: Vec<f32> = entry
            .iter()
            .zip(&parallax)
            .filter(|(_, seen)| **seen > far_edge + 0.02 && **seen < 0.98)
            .map(|(entered, seen)| seen - entered)
            .collect();
        assert!(shifts.len() > 3, "{angle}°: too few floor rows");
        let measured = shifts.iter().sum::<f32>() / shifts.len() as f32;
        let expected = HEIGHT_SCALE * angle.to_radians().tan();
        let error = (measured - expected).abs() / expected;
        eprintln!(
            "{angle}°: floor shift {measured:.5}, expected {expected:.5} ({:.2} %)",
            error * 100.0
        );
        assert!(
            error < 0.05,
            "{angle}°: measured {measured}, expected {expected}"
        );
        // The block's top (height 1) shows no shift at all.
        let top: Vec<f32> = entry
            .iter()
            .zip(&parallax)
            .filter(|(entered, _)| (0.35..0.65).contains(*entered))
            .map(|(entered, seen)| (seen - entered).abs())
            .collect();
        assert!(
            top.iter().all(|shift| *shift < 1e-3),
            "{angle}°: the top moved"
        );
    }
}

/// Visibility along the centre column, bottom row (low u) first, seen from straight above with
/// the light `light_angle` degrees from the normal on the −u side.
fn visibility_profile(shadows: ShadowMode, softening: f32) -> Vec<f32> {
    let view = PreviewView {
        light_angle: 60.0,
        ..PreviewView::default()
    };
    let image = render(&view, |material| ParallaxOcclusionMaterial {
        shadows,
        shadow_softening: softening,
        debug_view: DebugView::Shadow,
        ..material
    });
    centre_column_u(&image)
}

fn row_u(row: usize) -> f32 {
    (row as f32 + 0.5) / SIZE as f32
}

#[test]
fn a_block_lit_from_the_side_shadows_the_floor_behind_it_only() {
    let shadow_length = HEIGHT_SCALE * 60_f32.to_radians().tan();
    for shadows in [ShadowMode::Hard, ShadowMode::Soft] {
        let profile = visibility_profile(shadows, 0.58);
        let mean = |from: f32, to: f32| {
            let values: Vec<f32> = (0..SIZE as usize)
                .filter(|row| (from..to).contains(&row_u(*row)))
                .map(|row| profile[row])
                .collect();
            values.iter().sum::<f32>() / values.len() as f32
        };
        let far_edge = 0.5 + BLOCK_SIDE / 2.0;
        let behind = mean(far_edge + 0.01, far_edge + shadow_length * 0.5);
        let lit_side = mean(0.1, 0.5 - BLOCK_SIDE / 2.0 - 0.01);
        let beyond = mean(far_edge + shadow_length + 0.03, 0.99);
        eprintln!("{shadows:?}: behind {behind:.3}, lit side {lit_side:.3}, beyond {beyond:.3}");
        assert!(
            behind < 0.3,
            "{shadows:?}: the floor behind the block is lit ({behind})"
        );
        assert!(
            lit_side > 0.99,
            "{shadows:?}: the lit side is darkened ({lit_side})"
        );
        assert!(
            beyond > 0.95,
            "{shadows:?}: the shadow is too long ({beyond})"
        );
    }
}

#[test]
fn more_softening_widens_the_penumbra() {
    let penumbra_rows = |softening| {
        visibility_profile(ShadowMode::Soft, softening)
            .iter()
            .filter(|v| **v > 0.02 && **v < 0.98)
            .count()
    };
    let widths: Vec<usize> = [0.2, 0.58, 2.0].into_iter().map(penumbra_rows).collect();
    eprintln!("penumbra rows at softening 0.2 / 0.58 / 2.0: {widths:?}");
    assert!(widths[0] < widths[1] && widths[1] < widths[2], "{widths:?}");
}
