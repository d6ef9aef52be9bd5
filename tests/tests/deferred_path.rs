//! The deferred path (visibility pass, compute resolve) against the forward path: the same
//! image, the same texture coordinates, the same depth-offset contacts, no NaN. The golden
//! scenes and scene scripts are rendered both ways where they are checked (`render_both_paths`,
//! tests/tests/scene_scripts.rs).

use glam::Vec3;
use pom::gpu::PassTimestamps;
use pom::preview::{PreviewProjection, PreviewView};
use pom::render::{
    FrameNode, FrameNodes, FrameView, NodePlace, RenderError, RenderPhase, Renderer, SettledDepth,
};
use pom::{
    AntiAliasing, Assets, Camera, Color, DebugView, LitMaterial, Mesh, ParallaxOcclusionMaterial,
    RenderPath, TargetFormat, Transform, patterns,
};
use pom_tests::anti_aliasing::settled;
use pom_tests::pom_scene::{HeightMaterial, preview_app, wrapped};
use pom_tests::{render_both_paths, render_on_path, render_on_path_f32, set_path};

/// Side of the test height map in texels.
const TEXELS: u32 = 256;

fn cobblestones() -> HeightMaterial {
    HeightMaterial {
        field: patterns::cobblestones(TEXELS, 6),
        height_scale: 0.08,
    }
}

fn perspective(view_angle: f32) -> PreviewView {
    PreviewView {
        view_angle,
        projection: PreviewProjection::Perspective,
        ..PreviewView::default()
    }
}

#[test]
fn a_parallax_plane_looks_the_same_on_both_paths() {
    let mut app = preview_app(
        128,
        TargetFormat::Srgb8,
        &cobblestones(),
        &perspective(45.0),
        |m| m,
    )
    .unwrap();
    render_both_paths(&mut app, "parallax_plane").unwrap();
}

#[test]
fn the_uv_view_agrees_within_a_twentieth_of_a_texel_over_the_angle_sweep() {
    let textures = cobblestones();
    let texels = TEXELS as f32;
    let mut report = Vec::new();
    for angle in [0.0_f32, 15.0, 30.0, 45.0, 60.0, 75.0, 85.0, 89.9] {
        let mut app = preview_app(
            96,
            TargetFormat::Float32,
            &textures,
            &perspective(angle),
            |m| ParallaxOcclusionMaterial {
                debug_view: DebugView::Uv,
                ..m
            },
        )
        .unwrap();
        let forward = render_on_path_f32(&mut app, RenderPath::Forward).unwrap();
        let deferred = render_on_path_f32(&mut app, RenderPath::Deferred).unwrap();
        assert!(app.resources.get::<Renderer>().unwrap().runs_deferred());
        let (mut total, mut count, mut other_region) = (0.0_f64, 0_u32, 0_u32);
        for (f, d) in forward.pixels().zip(deferred.pixels()) {
            assert!(
                f.0.iter().chain(&d.0).all(|v| v.is_finite()),
                "{angle}°: a NaN or infinite pixel"
            );
            // Blue: 1 marched, ½ in the LOD band, 0 normal mapping only; the background has
            // the clear colour's blue (0.025 linear), which no region has.
            let region = f.0[2];
            if ![0.0, 0.5, 1.0].contains(&region) {
                continue;
            }
            if d.0[2] != region {
                other_region += 1;
                continue;
            }
            let du = wrapped(f.0[0] - d.0[0]) * texels;
            let dv = wrapped(f.0[1] - d.0[1]) * texels;
            total += f64::from((du * du + dv * dv).sqrt());
            count += 1;
        }
        let mean = total / f64::from(count.max(1));
        report.push(format!(
            "{angle:>5}°: mean |Δuv| {mean:.4} texel over {count} pixels, {other_region} in another LOD region"
        ));
        assert!(count > 1000, "{angle}°: only {count} pixels of the plane");
        assert!(mean <= 0.05, "{angle}°: mean |Δuv| {mean} texel");
        assert!(
            other_region * 100 <= count,
            "{angle}°: {other_region} pixels changed LOD region"
        );
    }
    eprintln!("{}", report.join("\n"));
}

#[test]
fn a_cube_in_depth_offset_relief_meets_it_the_same_way_on_both_paths() {
    let view = PreviewView {
        view_angle: 55.0,
        projection: PreviewProjection::Perspective,
        distance: 1.2,
        ..PreviewView::default()
    };
    let mut app = preview_app(128, TargetFormat::Srgb8, &cobblestones(), &view, |m| {
        ParallaxOcclusionMaterial {
            depth_offset: true,
            height_scale: 0.15,
            ..m
        }
    })
    .unwrap();
    // A cube sunk into the relief: where it meets the stones is decided by the displaced depth.
    let cube = app
        .resources
        .get_mut::<Assets<Mesh>>()
        .unwrap()
        .add(Mesh::cube(0.3));
    let transform = Transform::from_translation(Vec3::new(0.05, 0.0, 0.1));
    app.world.spawn((cube, transform, LitMaterial::default()));
    render_both_paths(&mut app, "depth_offset_contact").unwrap();
}

/// Depth-offset relief clipped at its silhouette under the sky, seen at a grazing 70°, in a
/// `side`-pixel square image: the sky shows where the silhouette clips the plane's far edge.
fn silhouetted_relief_under_the_sky(side: u32) -> pom::App {
    let view = PreviewView {
        view_angle: 70.0,
        projection: PreviewProjection::Perspective,
        distance: 1.4,
        ..PreviewView::default()
    };
    let mut app = preview_app(side, TargetFormat::Srgb8, &cobblestones(), &view, |m| {
        ParallaxOcclusionMaterial {
            depth_offset: true,
            silhouette: pom::Silhouette::UvBounds,
            height_scale: 0.15,
            ..m
        }
    })
    .unwrap();
    app.insert_resource(pom::EnvironmentLight::sky());
    app
}

#[test]
fn the_sky_meets_depth_offset_relief_at_its_settled_depth_on_both_paths() {
    // The deferred path settles depth offset in the resolve and writes the settled depth only
    // for the passes after it: the sky is drawn where the depth is still the far plane, so
    // where the silhouette clips the relief (the plane's far edge) the sky shows only if the
    // candidate's polygon depth was taken back there.
    let mut app = silhouetted_relief_under_the_sky(128);
    render_both_paths(&mut app, "depth_offset_silhouette_sky").unwrap();
}

/// A frame node that reads the target's depth (and draws nothing).
struct DepthTester;

impl FrameNode for DepthTester {
    fn runs(&self, _: FrameView<'_>) -> bool {
        true
    }

    fn reads_scene_depth(&self) -> bool {
        true
    }

    fn record(
        &mut self,
        _: FrameView<'_>,
        _: &mut pom::wgpu::CommandEncoder,
        _: Option<&PassTimestamps>,
    ) -> Result<(), RenderError> {
        Ok(())
    }
}

#[test]
fn under_taa_the_settled_depth_is_an_image_that_reads_as_the_depth_pass_would() {
    // TAA and the sky read the scene's depth in compute alone: the resolve's settled depth is
    // written into an image by a compute pass. A pass that tests against the depth gets it
    // drawn into the depth attachment by the candidates' polygons. Both give the same depth:
    // TAA reprojects through it and the sky shows where it is the far plane (the silhouette
    // clips the relief at the plane's far edge), so the settled images match to the bit.
    let settle = |tested: bool| {
        let mut app = silhouetted_relief_under_the_sky(96);
        let image = settled_deferred_under_taa(&mut app, tested);
        (
            image,
            app.resources.get::<Renderer>().unwrap().settled_depth(),
        )
    };
    let (in_image, how) = settle(false);
    assert_eq!(how, SettledDepth::Image);
    let (in_depth_pass, how) = settle(true);
    assert_eq!(how, SettledDepth::DepthPass);
    assert!(in_image == in_depth_pass, "the settled depths differ");
}

#[test]
fn the_polygon_pass_finds_what_the_visibility_pass_would_rasterize() {
    // A plane of two large triangles: its visibility keys come from compute (the polygon pass)
    // unless a pass tests against the depth attachment, which that pass does not write; then
    // the visibility pass rasterizes it. Under TAA and the sky, both read the scene's depth:
    // the same outline against the sky, the same relief, the same reprojection.
    let view = PreviewView {
        view_angle: 70.0,
        projection: PreviewProjection::Perspective,
        distance: 1.4,
        ..PreviewView::default()
    };
    let render = |tested: bool| {
        let mut app = preview_app(96, TargetFormat::Srgb8, &cobblestones(), &view, |m| m).unwrap();
        app.insert_resource(pom::EnvironmentLight::sky());
        let image = settled_deferred_under_taa(&mut app, tested);
        let renderer = app.resources.get::<Renderer>().unwrap();
        let ran = (renderer.ran_polygon_pass(), renderer.ran_depth_prepass());
        (image, ran, renderer.settled_depth())
    };
    // Found, the plane leaves the visibility pass nothing to rasterize: no depth pass runs,
    // and the settled depth holds the far plane wherever no key is.
    let (found, ran, how) = render(false);
    assert_eq!(ran, (true, false), "(polygon pass, depth prepass)");
    assert_eq!(how, SettledDepth::Image);
    let (rasterized, ran, _) = render(true);
    assert_eq!(
        ran,
        (false, true),
        "(polygon pass, depth prepass) under a pass that tests the depth"
    );
    pom_tests::anti_aliasing::save_for_looking("polygon_pass", &found);
    pom_tests::anti_aliasing::save_for_looking("polygon_pass_rasterized", &rasterized);
    // The pass snaps the corners and breaks ties on edges as the rasterizer does: the same
    // pixels, to the bit.
    let differing = pom_tests::differing_pixels(&found, &rasterized);
    assert_eq!(differing, 0, "pixels differ");
}

#[test]
fn a_frame_after_depth_offset_is_turned_off_keeps_no_candidate_of_the_last() {
    // Every resolve reads the candidate keys: a frame without candidates must not find the
    // last frame's there (a pixel would show the last frame's candidate).
    let view = PreviewView {
        view_angle: 40.0,
        ..PreviewView::default()
    };
    let mut app = preview_app(96, TargetFormat::Srgb8, &cobblestones(), &view, |m| {
        ParallaxOcclusionMaterial {
            depth_offset: true,
            ..m
        }
    })
    .unwrap();
    render_both_paths(&mut app, "depth_offset_on").unwrap();
    // The plane moves half off the image too: stale candidates would shade it where it was.
    let planes = app
        .world
        .query_mut::<(&mut ParallaxOcclusionMaterial, &mut Transform)>();
    for (material, transform) in planes {
        material.depth_offset = false;
        transform.translation.x += 0.6;
    }
    render_both_paths(&mut app, "depth_offset_turned_off").unwrap();
}

#[test]
fn without_a_depth_prepass_a_deferred_request_runs_forward_and_says_why() {
    let mut app = pom::App::new();
    app.add_plugin(
        pom::RenderPlugin::new(32, 32)
            .with_depth_prepass(false)
            .with_path(RenderPath::Deferred),
    )
    .add_plugin(pom::PomPlugin);
    let material = cobblestones().material(&mut app);
    pom::preview::spawn_preview(&mut app, material, &perspective(30.0)).unwrap();
    pom_tests::render_and_capture(&mut app).unwrap();
    let renderer = app.resources.get::<Renderer>().unwrap();
    assert!(!renderer.runs_deferred());
    assert_eq!(
        renderer.deferred_unavailable(),
        Some(pom::render::DeferredUnavailable::NoDepthPrepass)
    );
}

/// The cube colour a pixel shows: the index of its one strong channel (red, green or blue, at
/// least 1.5 times each other one and not near black), or `None` for the grey plane and the
/// black background.
fn tint_of(pixel: &image::Rgba<u8>) -> Option<usize> {
    let channel = |c: usize| f32::from(pixel.0[c]);
    (0..3).find(|&c| {
        channel(c) >= 16.0 && (0..3).all(|other| other == c || channel(c) >= 1.5 * channel(other))
    })
}

/// Checks that each of `cubes` (entity, index of its tint) shows its tint where a CPU ray cast
/// through each pixel's centre against the entities' known transforms meets it, and that no
/// other pixel shows a cube's tint.
fn check_instance_placement(
    app: &pom::App,
    image: &image::RgbaImage,
    cubes: &[(pom::hecs::Entity, usize)],
    name: &str,
) {
    let viewport = pom::glam::Vec2::new(image.width() as f32, image.height() as f32);
    // Per cube: the pixels the ray cast gives it, and how many of them show its tint.
    let mut covered = vec![(0_u32, 0_u32); cubes.len()];
    let mut stray = Vec::new();
    for (x, y, pixel) in image.enumerate_pixels() {
        let centre = pom::glam::Vec2::new(x as f32 + 0.5, y as f32 + 0.5);
        let hit = pom::pick_at(&app.world, &app.resources, viewport, centre);
        let cube = hit.and_then(|hit| cubes.iter().position(|(entity, _)| *entity == hit.entity));
        match (cube, tint_of(pixel)) {
            (Some(cube), tint) => {
                covered[cube].0 += 1;
                covered[cube].1 += u32::from(tint == Some(cubes[cube].1));
            }
            (None, Some(tint)) => stray.push(format!("({x}, {y}) shows tint {tint}")),
            (None, None) => {}
        }
    }
    for ((_, tint), (cast, tinted)) in cubes.iter().zip(covered) {
        eprintln!("{name}: cube of tint {tint}: {tinted} of its {cast} pixels show it");
        assert!(
            cast >= 100,
            "{name}: cube of tint {tint} covers only {cast} pixels"
        );
        // Shadowed crevices may be too dark to classify.
        assert!(
            tinted * 10 >= cast * 9,
            "{name}: the cube of tint {tint} shows it on {tinted} of the {cast} pixels where its \
             transform puts it"
        );
    }
    // Silhouette pixels whose centre the ray cast and the rasterizer may round differently.
    assert!(
        stray.len() <= 8,
        "{name}: {} pixels show a cube where none is, e.g. {:?}",
        stray.len(),
        &stray[..stray.len().min(10)]
    );
}

#[test]
fn instanced_parallax_cubes_resolve_each_instance_and_triangle() {
    // Three cubes of one mesh and material: one batch whose instances own consecutive runs of
    // visibility ids (12 triangles each), beside the plane's batch. Each has its own colour
    // (a per-draw uniform, so still one batch) to tell them apart on screen.
    let view = PreviewView {
        view_angle: 50.0,
        projection: PreviewProjection::Perspective,
        distance: 1.4,
        ..PreviewView::default()
    };
    let textures = cobblestones();
    let mut app = preview_app(128, TargetFormat::Srgb8, &textures, &view, |m| m).unwrap();
    let material = textures.material(&mut app);
    let cube = app
        .resources
        .get_mut::<Assets<Mesh>>()
        .unwrap()
        .add(Mesh::cube(0.2));
    let tints = [
        pom::Color::linear_rgb(1.0, 0.12, 0.12),
        pom::Color::linear_rgb(0.12, 1.0, 0.12),
        pom::Color::linear_rgb(0.12, 0.12, 1.0),
    ];
    // Spawned farthest first (the camera is on the −X side), so the batch's nearest-first
    // instance order is the reverse of the world's.
    let mut cubes = Vec::new();
    for (i, x) in [-0.3_f32, 0.0, 0.3].into_iter().enumerate().rev() {
        let transform = Transform {
            translation: Vec3::new(x, 0.1, x * (i as f32 - 0.5)),
            rotation: pom::glam::Quat::from_rotation_y(0.4 * i as f32),
            ..Transform::IDENTITY
        };
        let tinted = ParallaxOcclusionMaterial {
            base_color: tints[i],
            ..material.clone()
        };
        cubes.push((app.world.spawn((cube.clone(), transform, tinted)), i));
    }
    // Where each instance is, first (agreeing paths could both be wrong), then the paths agree.
    let forward = render_on_path(&mut app, RenderPath::Forward).unwrap();
    check_instance_placement(&app, &forward, &cubes, "forward");
    let deferred = render_on_path(&mut app, RenderPath::Deferred).unwrap();
    assert!(app.resources.get::<Renderer>().unwrap().runs_deferred());
    check_instance_placement(&app, &deferred, &cubes, "deferred");
    render_both_paths(&mut app, "instanced_cubes").unwrap();
}

#[test]
fn a_prepass_draw_of_no_material_keeps_frames_forward_and_a_fragment_counter_does_not() {
    use pom::gpu::FragmentInvocationCounter;
    use pom::render::{DeferredUnavailable, DrawPhase, RenderPhases};
    let deferred_frame = |app: &mut pom::App| {
        render_on_path(app, RenderPath::Deferred).unwrap();
        let renderer = app.resources.get::<Renderer>().unwrap();
        (renderer.runs_deferred(), renderer.deferred_unavailable())
    };
    let mut app = preview_app(
        32,
        TargetFormat::Srgb8,
        &cobblestones(),
        &perspective(30.0),
        |m| m,
    )
    .unwrap();
    assert_eq!(deferred_frame(&mut app), (true, None));
    // Counting fragment invocations: on the deferred path the counter counts the visibility
    // pass's merges (tests/tests/render_phases.rs).
    let counter = FragmentInvocationCounter::new(app.resources.get::<pom::GpuContext>().unwrap());
    app.insert_resource(counter);
    assert_eq!(deferred_frame(&mut app), (true, None));
    app.resources.remove::<FragmentInvocationCounter>();
    // A plugin's own prepass draw writes depth but no visibility key.
    struct OwnDraw;
    app.resources
        .get_mut::<RenderPhases>()
        .unwrap()
        .add_draw::<OwnDraw>(DrawPhase::Prepass, |_, _| {});
    assert_eq!(
        deferred_frame(&mut app),
        (
            false,
            Some(DeferredUnavailable::PrepassDrawWithoutVisibility)
        )
    );
}

/// `app` settled on the deferred path under TAA, with a node that tests against the depth
/// attachment where `tested` (so the depth must be drawn there).
fn settled_deferred_under_taa(app: &mut pom::App, tested: bool) -> image::RgbaImage {
    if tested {
        app.resources
            .get_or_default::<FrameNodes>()
            .add(NodePlace::new("depth tester", RenderPhase::Resolve), || {
                DepthTester
            });
    }
    set_path(app, RenderPath::Deferred);
    let image = settled(app, AntiAliasing::Taa);
    assert!(app.resources.get::<Renderer>().unwrap().runs_deferred());
    image
}

#[test]
fn the_resolve_writes_the_background_where_no_draw_shows() {
    // The background pass reads every key to write the clear colour where none holds a draw.
    // A resolve dispatched over the whole target (one batch) reads them anyway, and so does the
    // tile classification (two batches of one material): they write it where neither key
    // holds a draw, and the pass does not run. A depth-offset candidate clipped at its
    // silhouette loses over empty pixels: its resolve writes the background there. The clear
    // colour changes between the deferred frames, so a background left from the frame before
    // shows.
    let cases = [
        ("one batch", 1, None),
        ("two batches", 2, None),
        ("depth offset", 1, Some(pom::Silhouette::Off)),
        ("depth offset, two batches", 2, Some(pom::Silhouette::Off)),
        ("depth offset clipped", 1, Some(pom::Silhouette::UvBounds)),
        (
            "depth offset clipped, two batches",
            2,
            Some(pom::Silhouette::UvBounds),
        ),
    ];
    for (name, planes, depth_offset) in cases {
        let mut app = preview_app(
            96,
            TargetFormat::Srgb8,
            &cobblestones(),
            &perspective(60.0),
            |m| ParallaxOcclusionMaterial {
                depth_offset: depth_offset.is_some(),
                silhouette: depth_offset.unwrap_or(m.silhouette),
                ..m
            },
        )
        .unwrap();
        if planes == 2 {
            let material = app
                .world
                .query_mut::<&ParallaxOcclusionMaterial>()
                .into_iter()
                .next()
                .unwrap()
                .clone();
            let mesh = app
                .resources
                .get_mut::<Assets<Mesh>>()
                .unwrap()
                .add(Mesh::plane(0.4));
            let beside = Transform::from_xyz(0.3, 0.1, 0.2);
            app.world.spawn((mesh, material, beside));
        }
        let clear_to = |app: &mut pom::App, color: Color| {
            for camera in app.world.query_mut::<&mut Camera>() {
                camera.clear_color = color;
            }
        };
        let (first, second) = (
            Color::linear_rgb(0.9, 0.2, 0.1),
            Color::linear_rgb(0.1, 0.3, 0.8),
        );
        // Each colour's forward frame, then each one's deferred frame: a background left from
        // the frame before would be the other colour.
        let forward: Vec<_> = [first, second]
            .map(|color| {
                clear_to(&mut app, color);
                render_on_path(&mut app, RenderPath::Forward).unwrap()
            })
            .into();
        for (color, forward) in [first, second].into_iter().zip(&forward) {
            clear_to(&mut app, color);
            let deferred = render_on_path(&mut app, RenderPath::Deferred).unwrap();
            let renderer = app.resources.get::<Renderer>().unwrap();
            assert!(renderer.runs_deferred(), "{name}: ran forward");
            assert!(
                !renderer.ran_background_pass(),
                "{name}: the background pass ran"
            );
            // The forward frame's corner is the clear colour as the opaque pass clears it.
            let background = *forward.get_pixel(0, 0);
            let (mut empty, mut differing) = (0, 0);
            for (f, d) in forward.pixels().zip(deferred.pixels()) {
                if *f == background {
                    empty += 1;
                    differing += usize::from(d != f);
                }
            }
            assert!(
                empty > 96 * 96 / 10,
                "{name}: only {empty} background pixels"
            );
            assert_eq!(differing, 0, "{name}: background pixels differ of {empty}");
        }
    }
}

#[test]
fn the_resolve_rebuilds_the_texture_footprint_the_fragment_stage_differences() {
    // The fragment stage takes a pixel's texture footprint from the differences across its
    // 2 × 2 quad; the resolve from the rays through the same neighbours (each its pixel's ray
    // stepped by a pixel). The mip level each gives agrees to a five-hundredth of a level at
    // every angle, perspective or orthographic: a footprint a tenth short along one axis moves
    // it by a tenth of a level.
    let textures = cobblestones();
    let levels = (TEXELS.ilog2()) as f32;
    let mut report = Vec::new();
    let orthographic = |view_angle| PreviewView {
        view_angle,
        projection: PreviewProjection::Orthographic,
        ..PreviewView::default()
    };
    let views = [0.0_f32, 30.0, 60.0, 80.0]
        .map(|angle| (angle, perspective(angle)))
        .into_iter()
        .chain([30.0, 70.0].map(|angle| (angle, orthographic(angle))));
    for (angle, view) in views {
        let mut app = preview_app(96, TargetFormat::Float32, &textures, &view, |m| {
            ParallaxOcclusionMaterial {
                debug_view: DebugView::Mip,
                ..m
            }
        })
        .unwrap();
        let forward = render_on_path_f32(&mut app, RenderPath::Forward).unwrap();
        let deferred = render_on_path_f32(&mut app, RenderPath::Deferred).unwrap();
        assert!(app.resources.get::<Renderer>().unwrap().runs_deferred());
        let background = *forward.get_pixel(0, 0);
        let (mut largest, mut count) = (0.0_f32, 0_u32);
        for (f, d) in forward.pixels().zip(deferred.pixels()) {
            if *f == background {
                continue;
            }
            largest = largest.max((f.0[0] - d.0[0]).abs() * levels);
            count += 1;
        }
        report.push(format!(
            "{angle:>4}° {:?}: largest mip difference {largest:.5} level over {count} pixels",
            view.projection
        ));
        assert!(count > 1000, "{angle}°: only {count} pixels of the plane");
        assert!(largest <= 0.002, "{angle}°: mip levels differ by {largest}");
    }
    eprintln!("{}", report.join("\n"));
}
