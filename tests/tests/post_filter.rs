//! The post filter (FXAA): its four shader variants, and the mip bias it reads textures with,
//! which must never move the relief. Its edge error sits beside TAA's in anti_aliasing.rs.

use glam::Vec2;
use image::{Rgba32FImage, RgbaImage};
use pom::preview::{PreviewProjection, PreviewView};
use pom::{
    AntiAliasing, HeightUnits, ParallaxMethod, PostProcessPath, RenderPlugin, TargetFormat,
    patterns,
};
use pom_tests::anti_aliasing::{set_anti_aliasing, settled, turned_square, turned_square_with};
use pom_tests::edge_error::{edge_pixels, mean_error};
use pom_tests::pom_scene::{HeightMaterial, set_material, uv_app, wrapped};
use pom_tests::{render_and_capture, render_and_capture_f32};

#[test]
fn the_post_filter_runs_alike_in_compute_and_fragment_on_8_bit_and_float_displays() {
    // An 8-bit display's image is read through a bilinear sampler, a float one with loads;
    // each in a compute pass and as a full-screen triangle. A float display blends linear
    // values, an 8-bit one encoded values, so the two formats differ from each other.
    let size = 64;
    let off = settled(&mut turned_square(size, size), AntiAliasing::Off);
    let edges = edge_pixels(&off);
    for format in [TargetFormat::Srgb8, TargetFormat::Float32] {
        let [compute, fragment] =
            [PostProcessPath::Fastest, PostProcessPath::Fragment].map(|post| {
                let render = RenderPlugin::new(size, size)
                    .with_format(format)
                    .with_post_process(post);
                let mut app = turned_square_with(render);
                set_anti_aliasing(&mut app, AntiAliasing::Fxaa);
                if format == TargetFormat::Srgb8 {
                    return render_and_capture(&mut app).unwrap();
                }
                let linear = render_and_capture_f32(&mut app).unwrap();
                assert!(linear.pixels().all(|p| p.0.iter().all(|v| v.is_finite())));
                let encode =
                    |v: f32| (pom::linear_to_srgb(v.clamp(0.0, 1.0)) * 255.0).round() as u8;
                RgbaImage::from_fn(size, size, |x, y| {
                    let p = linear.get_pixel(x, y).0;
                    image::Rgba([encode(p[0]), encode(p[1]), encode(p[2]), 255])
                })
            });
        let filtered = mean_error(&compute, &off, &edges);
        let apart = mean_error(&fragment, &compute, &edges);
        eprintln!(
            "FXAA, {format:?}: {filtered:.4} from off on the edges; fragment {apart:.4} from compute"
        );
        assert!(
            filtered > 0.02,
            "{format:?}: FXAA changed little on the edges ({filtered})"
        );
        assert!(apart < 0.002, "{format:?}: fragment {apart} from compute");
    }
}

#[test]
fn the_mip_bias_reads_finer_levels_but_never_moves_the_relief() {
    // The post filter scales every texture footprint by its mip bias, as TAA does by its own.
    // Relief measured in world units comes from the footprint too: the march must find the
    // same points, bar the finer heights it reads. The uv view skips the post filter.
    let textures = HeightMaterial {
        field: patterns::cobblestones(256, 6),
        height_scale: 0.06,
    };
    let view = PreviewView {
        view_angle: 60.0,
        projection: PreviewProjection::Orthographic,
        tiling: 3.0,
        ..PreviewView::default()
    };
    let uv = |method, aa| {
        let mut app = uv_app(96, &textures, &view, method).unwrap();
        set_material(&mut app, |material| {
            material.height_units = HeightUnits::World;
            material.height_scale = 0.05;
        });
        set_anti_aliasing(&mut app, aa);
        render_and_capture_f32(&mut app).unwrap()
    };
    // The mean parallax shift: where the finer levels change which stone a pixel meets,
    // single pixels jump, but the mean follows the depth of the relief.
    let mean_shift = |image: &Rgba32FImage, entry: &Rgba32FImage| {
        let total = image
            .pixels()
            .zip(entry.pixels())
            .fold(Vec2::ZERO, |sum, (p, q)| {
                sum + Vec2::new(wrapped(p.0[0] - q.0[0]), wrapped(p.0[1] - q.0[1]))
            });
        total / (image.width() * image.height()) as f32
    };
    let entry = uv(ParallaxMethod::NormalMapping, AntiAliasing::Off);
    let off = mean_shift(&uv(ParallaxMethod::Occlusion, AntiAliasing::Off), &entry);
    let post_filter = mean_shift(&uv(ParallaxMethod::Occlusion, AntiAliasing::Fxaa), &entry);
    let moved = (post_filter - off).length() / off.length();
    eprintln!("world-unit relief: mean parallax shift {off}, under the post filter {post_filter}");
    assert!(off.length() > 0.005, "the relief shifts by {off} only");
    // The finer heights alone change it by about a tenth (a coarser level flattens the
    // crests the rays meet first); a relief taken at half
    // its depth, as the bias once made it, changes it by half.
    assert!(
        moved < 0.25,
        "the post filter moved the relief by {moved} of its shift"
    );
}
