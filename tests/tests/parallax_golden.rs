//! Reference contact sheets of the parallax material: every method and every debug view on the
//! bricks, cobblestone and cone height maps. Each sheet is a grid of 128² tiles, four a row, in
//! reading order: normal mapping, parallax offset, steep, POM, relief, POM with hard shadows,
//! then POM's debug views lod, mip, samples, uv, shadow, normal, then max-mip and its samples
//! view (texel fetches).

use image::RgbaImage;
use pom::preview::{PreviewProjection, PreviewView};
use pom::{
    DebugView, HeightField, ParallaxMethod, ParallaxOcclusionMaterial, ShadowMode, TargetFormat,
    patterns,
};
use pom_tests::pom_scene::{HeightMaterial, preview_app};
use pom_tests::{FlipTolerance, check_golden, render_both_paths};

const TILE: u32 = 128;

fn tiles() -> Vec<(ParallaxMethod, ShadowMode, DebugView)> {
    let soft = ShadowMode::Soft;
    let pom = ParallaxMethod::Occlusion;
    let mut tiles = vec![
        (ParallaxMethod::NormalMapping, soft, DebugView::None),
        (ParallaxMethod::ParallaxOffset, soft, DebugView::None),
        (ParallaxMethod::Steep, soft, DebugView::None),
        (pom, soft, DebugView::None),
        (ParallaxMethod::Relief, soft, DebugView::None),
        (pom, ShadowMode::Hard, DebugView::None),
    ];
    for view in [
        DebugView::Lod,
        DebugView::Mip,
        DebugView::Samples,
        DebugView::Uv,
        DebugView::Shadow,
        DebugView::Normal,
    ] {
        tiles.push((pom, soft, view));
    }
    tiles.push((ParallaxMethod::MaxMip, soft, DebugView::None));
    tiles.push((ParallaxMethod::MaxMip, soft, DebugView::Samples));
    tiles
}

fn contact_sheet(field: HeightField, height_scale: f32) -> RgbaImage {
    let textures = HeightMaterial {
        field,
        height_scale,
    };
    // A perspective view at a grazing angle, so the far part of the plane crosses the LOD band.
    let view = PreviewView {
        view_angle: 58.0,
        light_angle: 60.0,
        light_azimuth: 35.0,
        projection: PreviewProjection::Perspective,
        distance: 0.45,
        tiling: 3.0,
        ..PreviewView::default()
    };
    let tiles = tiles();
    let rows = tiles.len().div_ceil(4) as u32;
    let mut sheet = RgbaImage::new(TILE * 4, TILE * rows);
    for (index, (method, shadows, debug_view)) in tiles.into_iter().enumerate() {
        let mut app = preview_app(TILE, TargetFormat::Srgb8, &textures, &view, |material| {
            ParallaxOcclusionMaterial {
                method,
                shadows,
                debug_view,
                ..material
            }
        })
        .unwrap();
        let name = format!("tile_{method:?}_{shadows:?}_{debug_view:?}");
        let tile = render_both_paths(&mut app, &name).unwrap();
        let (x, y) = (index as u32 % 4 * TILE, index as u32 / 4 * TILE);
        image::imageops::replace(&mut sheet, &tile, i64::from(x), i64::from(y));
    }
    sheet
}

#[test]
fn bricks_contact_sheet() {
    let sheet = contact_sheet(patterns::bricks(128, 2.0, 4.0), 0.06);
    check_golden("pom_bricks", &sheet, FlipTolerance::default()).unwrap();
}

#[test]
fn cobblestone_contact_sheet() {
    let sheet = contact_sheet(patterns::cobblestones(128, 4), 0.05);
    check_golden("pom_cobblestone", &sheet, FlipTolerance::default()).unwrap();
}

#[test]
fn cones_contact_sheet() {
    let sheet = contact_sheet(patterns::cones(128, 3.0), 0.06);
    check_golden("pom_cones", &sheet, FlipTolerance::default()).unwrap();
}
