//! The deferred path (visibility pass, compute resolve) against the forward path: the same
//! image, the same texture coordinates, no NaN.

use pom::preview::{PreviewProjection, PreviewView};
use pom::{ParallaxOcclusionMaterial, TargetFormat, patterns};
use pom_tests::pom_scene::{HeightMaterial, preview_app};
use pom_tests::render_both_paths;

#[test]
fn a_parallax_plane_looks_the_same_on_both_paths() {
    let textures = HeightMaterial {
        field: patterns::cobblestones(256, 6),
        height_scale: 0.08,
    };
    let view = PreviewView {
        view_angle: 45.0,
        projection: PreviewProjection::Perspective,
        ..PreviewView::default()
    };
    let mut app = preview_app(128, TargetFormat::Srgb8, &textures, &view, |material| {
        ParallaxOcclusionMaterial { ..material }
    })
    .unwrap();
    render_both_paths(&mut app, "parallax_plane").unwrap();
    panic!("look");
}
