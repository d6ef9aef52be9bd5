//! The frame's phases: the depth prepass keeps hidden pixels from marching and changes no pixel,
//! post-processing maps HDR light to the display (exposure, tonemapping) the same in compute and
//! in its fragment fallback, and each phase is timed.

use glam::Vec3;
use pom::gpu::FragmentInvocationCounter;
use pom::hecs;
use pom::preview::PreviewView;
use pom::{
    App, Assets, Camera, Color, DirectionalLight, Exposure, GlobalTransform, GpuContext,
    LitMaterial, Mesh, ParallaxOcclusionMaterial, PomPlugin, PostProcessPath, RenderPath,
    RenderPlugin, ShadowMode, TargetFormat, Tonemapping, Transform, patterns,
};
use pom_tests::pom_scene::{HeightMaterial, preview_app};
use pom_tests::{HarnessError, in_error_scopes, render_and_capture};

const SIZE: u32 = 96;
const HEIGHT_SCALE: f32 = 0.05;

fn cobbles() -> HeightMaterial {
    HeightMaterial {
        field: patterns::raised_block(128, 0.4),
        height_scale: HEIGHT_SCALE,
    }
}

/// An app whose parallax shaders count their fragment invocations: the counter must exist
/// before the material plugins finish, so the GPU context is made first.
fn counting_app(plugin: RenderPlugin) -> App {
    let gpu = GpuContext::headless().unwrap();
    let counter = FragmentInvocationCounter::new(&gpu);
    let mut app = App::new();
    app.insert_resource(gpu).insert_resource(counter);
    app.add_plugin(plugin).add_plugin(PomPlugin);
    app.finish().unwrap();
    app
}

/// How the stacked planes reach the GPU.
#[derive(Clone, Copy, PartialEq)]
enum Stack {
    /// One mesh each, made deepest first: separate batches in mesh order, drawn back to front
    /// (the worst case).
    BackToFront,
    /// One shared mesh: one batch, whose instances the renderer sorts nearest first.
    Shared,
}

/// A started app: `plugin` and the parallax plugin (which brings the lit one).
fn started(plugin: RenderPlugin) -> App {
    let mut app = App::new();
    app.add_plugin(plugin).add_plugin(PomPlugin);
    app.finish().unwrap();
    app
}

/// A square plane mesh of side `size`, added to the app's meshes.
fn plane(app: &mut App, size: f32) -> pom::Handle<Mesh> {
    app.resources
        .get_mut::<Assets<Mesh>>()
        .unwrap()
        .add(Mesh::plane(size))
}

/// A frame of the test's size on the forward path, with or without the depth prepass.
fn forward(prepass: bool) -> RenderPlugin {
    RenderPlugin::new(SIZE, SIZE)
        .with_path(RenderPath::Forward)
        .with_depth_prepass(prepass)
}

/// `planes` parallax planes half a unit apart under a camera looking down at them and a sun,
/// spawned farthest first (`Stack::Shared`: copies of one mesh).
fn spawn_stack(app: &mut App, planes: usize, depth_offset: bool, stack: Stack) {
    let material = ParallaxOcclusionMaterial {
        depth_offset,
        ..cobbles().material(app)
    };
    let meshes = app.resources.get_mut::<Assets<Mesh>>().unwrap();
    let shared = meshes.add(Mesh::plane(40.0));
    // Deepest first (the control without prepass below shows the order holds). The planes are
    // 0.5 apart, ten times the relief's depth.
    let stacked: Vec<_> = (0..planes)
        .rev()
        .map(|index| {
            let mesh = match stack {
                Stack::BackToFront => meshes.add(Mesh::plane(40.0)),
                Stack::Shared => shared.clone(),
            };
            (mesh, Transform::from_xyz(0.0, -0.5 * index as f32, 0.0))
        })
        .collect();
    for (mesh, transform) in stacked {
        app.world.spawn((
            mesh,
            material.clone(),
            transform,
            GlobalTransform(transform.to_affine()),
        ));
    }
    app.world.spawn((
        Camera::perspective(50.0),
        Transform::from_xyz(0.0, 2.0, 1.5).looking_at(Vec3::ZERO, Vec3::Y),
    ));
    app.world.spawn((
        DirectionalLight::default(),
        Transform::from_xyz(1.0, 2.0, 1.0).looking_at(Vec3::ZERO, Vec3::Y),
    ));
}

/// Fragment-shader invocations of the parallax material's opaque pipeline (on the deferred
/// path: merges into the visibility buffer) for `planes` full screen planes stacked along the
/// view, rendered with `plugin`.
fn parallax_invocations(
    planes: usize,
    depth_offset: bool,
    plugin: RenderPlugin,
    stack: Stack,
) -> u32 {
    let mut app = counting_app(plugin);
    spawn_stack(&mut app, planes, depth_offset, stack);
    in_error_scopes(&mut app, "counted frame", |app| {
        let (gpu, counter) = (
            app.resources.require::<GpuContext>()?,
            app.resources.require::<FragmentInvocationCounter>()?,
        );
        counter.reset(gpu);
        app.update()?;
        let deferred = app
            .resources
            .require::<pom::render::Renderer>()?
            .runs_deferred();
        assert_eq!(
            deferred,
            plugin.path == RenderPath::Deferred,
            "the frame's path"
        );
        let (gpu, counter) = (
            app.resources.require::<GpuContext>()?,
            app.resources.require::<FragmentInvocationCounter>()?,
        );
        Ok(counter.read(gpu).expect("reading the counter"))
    })
    .unwrap()
}

#[test]
fn hidden_pixels_do_not_march() {
    for depth_offset in [false, true] {
        let one = parallax_invocations(1, depth_offset, forward(true), Stack::BackToFront);
        let four = parallax_invocations(4, depth_offset, forward(true), Stack::BackToFront);
        let four_without_prepass =
            parallax_invocations(4, depth_offset, forward(false), Stack::BackToFront);
        eprintln!(
            "depth offset {depth_offset}: one plane {one}, four planes drawn back to front {four} \
             with the prepass, {four_without_prepass} without"
        );
        // The planes fill the image: every pixel of the nearest one runs once.
        assert!(one as f32 >= 0.9 * (SIZE * SIZE) as f32, "{one}");
        assert!(
            (four as f32 - one as f32).abs() <= 0.01 * one as f32,
            "depth offset {depth_offset}: {four} invocations for four planes, {one} for one"
        );
        // Without the prepass each nearer plane drawn later shades again: the counter sees it.
        assert!(four_without_prepass as f32 >= 3.5 * one as f32);
    }
}

#[test]
fn hidden_planes_merge_nothing_into_the_visibility_buffer() {
    // On the deferred path the parallax material shades in compute: what the counter sees is
    // every fragment the visibility pass launches, and with depth offset every fragment of the
    // candidate pass (counted first thing: no fragment is dropped uncounted). The planes are
    // separate batches made deepest first; both passes draw them nearest first across batches
    // with an early depth test and write, so the hidden ones fail it before their fragments
    // run: four stacked planes launch no more than one plane and its polygon edges. (The
    // polygon pass would find these planes in compute: it is off to count the visibility
    // pass's own work, which draws what that pass cannot take.)
    let deferred = RenderPlugin::new(SIZE, SIZE)
        .with_path(RenderPath::Deferred)
        .with_polygon_pass(false);
    for depth_offset in [false, true] {
        let one = parallax_invocations(1, depth_offset, deferred, Stack::BackToFront);
        let four = parallax_invocations(4, depth_offset, deferred, Stack::BackToFront);
        eprintln!(
            "deferred, depth offset {depth_offset}: one plane {one} merges, four planes drawn \
             back to front {four}"
        );
        assert!(one as f32 >= 0.9 * (SIZE * SIZE) as f32, "{one}");
        assert!(
            four as f32 <= 1.05 * one as f32,
            "depth offset {depth_offset}: {four} visibility merges for four planes, {one} for one"
        );
    }
}

#[test]
fn the_polygon_pass_finds_large_planes_without_a_fragment() {
    // Four full-screen planes of two triangles each: the polygon pass finds their visibility
    // keys (with depth offset, their candidate keys) in compute, and neither the visibility
    // pass nor the candidate pass launches a fragment for them.
    let deferred = RenderPlugin::new(SIZE, SIZE).with_path(RenderPath::Deferred);
    for depth_offset in [false, true] {
        let four = parallax_invocations(4, depth_offset, deferred, Stack::BackToFront);
        assert_eq!(four, 0, "depth offset {depth_offset}");
    }
}

#[test]
fn overlapping_planes_found_nearest_first_show_what_the_rasterizer_shows() {
    // Four small planes, each a step lower and further along, spawned nearest first: the
    // polygon pass takes their triangles nearest first and stops where none can come nearer,
    // and every pixel shows the plane the rasterized visibility pass shows there.
    let render = |polygon_pass: bool| {
        let mut app = started(
            RenderPlugin::new(SIZE, SIZE)
                .with_format(TargetFormat::Srgb8)
                .with_path(RenderPath::Deferred)
                .with_polygon_pass(polygon_pass),
        );
        let material = cobbles().material(&mut app);
        for index in 0..4 {
            let step = index as f32;
            let mesh = plane(&mut app, 1.2);
            let transform = Transform::from_xyz(0.35 * step - 0.5, -0.3 * step, -0.35 * step);
            app.world.spawn((mesh, material.clone(), transform));
        }
        app.world.spawn((
            Camera::perspective(50.0),
            Transform::from_xyz(0.0, 2.0, 1.5).looking_at(Vec3::new(0.0, -0.5, -0.5), Vec3::Y),
        ));
        app.world.spawn((
            DirectionalLight::default(),
            Transform::from_xyz(1.0, 2.0, 1.0).looking_at(Vec3::ZERO, Vec3::Y),
        ));
        let image = render_and_capture(&mut app).unwrap();
        let renderer = app.resources.get::<pom::render::Renderer>().unwrap();
        assert_eq!(renderer.ran_polygon_pass(), polygon_pass);
        image
    };
    let found = render(true);
    let rasterized = render(false);
    pom_tests::anti_aliasing::save_for_looking("overlapping_planes_found", &found);
    let differing = pom_tests::differing_pixels(&found, &rasterized);
    assert_eq!(differing, 0, "pixels differ");
}

#[test]
fn copies_of_one_mesh_are_drawn_nearest_first() {
    // Without a prepass only the order saves work: nearest first, the hidden copies fail the
    // depth test before their fragments run.
    let one = parallax_invocations(1, false, forward(false), Stack::Shared);
    let four = parallax_invocations(4, false, forward(false), Stack::Shared);
    eprintln!("one plane {one}, four copies of one mesh {four}, no prepass");
    assert!(
        (four as f32 - one as f32).abs() <= 0.01 * one as f32,
        "{four} vs {one}"
    );
}

/// The red plane half way down the relief of the depth-offset test, with or without prepass.
fn depth_offset_scene(prepass: bool) -> image::RgbaImage {
    let view = PreviewView {
        view_angle: 20.0,
        ..PreviewView::default()
    };
    let mut app = started(
        RenderPlugin::new(128, 128)
            .with_format(TargetFormat::Srgb8)
            .with_depth_prepass(prepass),
    );
    let material = ParallaxOcclusionMaterial {
        depth_offset: true,
        shadows: ShadowMode::Soft,
        ..cobbles().material(&mut app)
    };
    pom::preview::spawn_preview(&mut app, material, &view).unwrap();
    let plane = plane(&mut app, 1.0);
    app.world.spawn((
        plane,
        LitMaterial {
            base_color: Color::linear_rgb(1.0, 0.0, 0.0),
            specular_strength: 0.0,
            ..LitMaterial::default()
        },
        Transform::from_xyz(0.0, -HEIGHT_SCALE * 0.5, 0.0),
    ));
    render_and_capture(&mut app).unwrap()
}

#[test]
fn the_prepass_changes_no_pixel_of_a_depth_offset_scene() {
    let without = depth_offset_scene(false);
    let with = depth_offset_scene(true);
    let flip = pom::flip_compare(&without, &with, 0.99).unwrap();
    // Speckle is a pixel where the two passes disagree about which surface is in front: it
    // shows as a pixel that differs. Count every pixel that differs at all.
    let differing = pom_tests::differing_pixels(&without, &with);
    let red = with
        .pixels()
        .filter(|p| p.0[0] > 100 && p.0[1] < 40 && p.0[2] < 40)
        .count();
    eprintln!(
        "depth offset scene: FLIP mean {:.5}, {differing} of {} pixels differ, red plane in {red}",
        flip.mean,
        128 * 128
    );
    assert!(red > 1000, "the red plane shows through the deep parts");
    assert!(flip.mean <= 0.005, "{}", flip.mean);
    assert_eq!(
        differing, 0,
        "speckle: pixels where prepass and opaque disagree"
    );
}

/// Linear display colour and scene colour at the centre of a lit orange plane whose brightest
/// channel reaches `level` × white, through `tonemapping` at the default exposure.
fn bright_surface(tonemapping: Tonemapping, level: f32) -> ([f32; 3], [f32; 3]) {
    let mut app = started(RenderPlugin::new(16, 16).with_format(TargetFormat::Float32));
    *app.resources.get_mut::<pom::AmbientLight>().unwrap() = pom::AmbientLight {
        color: Color::WHITE,
        intensity: 0.0,
    };
    let plane = plane(&mut app, 4.0);
    let albedo = [0.8, 0.4, 0.1];
    app.world.spawn((
        plane,
        LitMaterial {
            base_color: Color::linear_rgb(albedo[0], albedo[1], albedo[2]),
            specular_strength: 0.0,
            ..LitMaterial::default()
        },
        Transform::IDENTITY,
    ));
    // Straight down onto the plane: N·L = 1, so the red channel is 0.8 × the exposed
    // illuminance: `level` at the default exposure takes level / 0.8 × 100,000 lux.
    app.world.spawn((
        DirectionalLight {
            color: Color::WHITE,
            intensity: level / albedo[0] * 100_000.0,
        },
        Transform::from_xyz(0.0, 1.0, 0.0).looking_at(Vec3::ZERO, Vec3::Z),
    ));
    app.world.spawn((
        Camera::orthographic(2.0),
        tonemapping,
        Exposure::default(),
        Transform::from_xyz(0.0, 2.0, 0.0).looking_at(Vec3::ZERO, Vec3::Z),
    ));
    in_error_scopes(&mut app, "bright surface", |app| {
        app.update()?;
        let display = pom::capture_f32(app)?;
        let scene = pom::capture_scene(app)?;
        let rgb = |p: &image::Rgba<f32>| [p.0[0], p.0[1], p.0[2]];
        Ok::<_, HarnessError>((rgb(display.get_pixel(8, 8)), rgb(scene.get_pixel(8, 8))))
    })
    .unwrap()
}

/// Hue angle in degrees (the HSV hexcone).
fn hue(rgb: [f32; 3]) -> f32 {
    let [r, g, b] = rgb;
    let max = r.max(g).max(b);
    let min = r.min(g).min(b);
    let chroma = max - min;
    if chroma <= 0.0 {
        return 0.0;
    }
    let sector = if max == r {
        ((g - b) / chroma).rem_euclid(6.0)
    } else if max == g {
        (b - r) / chroma + 2.0
    } else {
        (r - g) / chroma + 4.0
    };
    sector * 60.0
}

#[test]
fn bright_colours_keep_their_hue_through_the_tonemappers_that_promise_it() {
    // Khronos PBR Neutral promises the hue (it only blends towards white); AgX and ACES promise
    // a path to white without clipping, and turn orange towards yellow on the way.
    for tonemapping in [Tonemapping::Neutral, Tonemapping::Agx, Tonemapping::Aces] {
        let (display, scene) = bright_surface(tonemapping, 4.0);
        let (scene_hue, display_hue) = (hue(scene), hue(display));
        eprintln!(
            "{tonemapping:?}: scene {scene:?} (hue {scene_hue:.1}°) → display {display:?} (hue {display_hue:.1}°)"
        );
        assert!((scene[0] - 4.0).abs() < 0.01, "{scene:?}");
        let max = display.iter().copied().fold(0.0, f32::max);
        let min = display.iter().copied().fold(1.0, f32::min);
        assert!(max <= 1.0 && min >= 0.0, "{display:?}");
        assert!(max < 1.0, "{tonemapping:?} clipped: {display:?}");
        assert!(
            max - min > 0.15,
            "{tonemapping:?} turned it white: {display:?}"
        );
        // Red stays the strongest channel, blue the weakest.
        assert!(
            display[0] > display[1] && display[1] > display[2],
            "{display:?}"
        );
        if tonemapping == Tonemapping::Neutral {
            assert!(
                (display_hue - scene_hue).abs() <= 0.5,
                "hue {scene_hue}° became {display_hue}°"
            );
        }
    }
    // Clamping is what the others avoid: red and green clip, the orange turns yellow.
    let (clamped, scene) = bright_surface(Tonemapping::None, 4.0);
    assert_eq!(clamped[..2], [1.0, 1.0], "{clamped:?}");
    assert!(hue(clamped) - hue(scene) > 20.0);
}

#[test]
fn one_stop_more_exposure_value_halves_the_light() {
    let display_at = |ev100: f32| {
        let mut app = started(RenderPlugin::new(8, 8).with_format(TargetFormat::Float32));
        let plane = plane(&mut app, 4.0);
        app.world
            .spawn((plane, LitMaterial::default(), Transform::IDENTITY));
        app.world.spawn((
            Camera::orthographic(2.0),
            Tonemapping::None,
            Exposure { ev100 },
            Transform::from_xyz(0.0, 2.0, 0.0).looking_at(Vec3::ZERO, Vec3::Z),
        ));
        in_error_scopes(&mut app, "exposure", |app| {
            app.update()?;
            let display = pom::capture_f32(app)?.get_pixel(4, 4).0;
            let scene = pom::capture_scene(app)?.get_pixel(4, 4).0;
            Ok::<_, HarnessError>((display[1], scene[1]))
        })
        .unwrap()
    };
    let (base, scene) = display_at(Exposure::DEFAULT_EV100);
    let (darker, _) = display_at(Exposure::DEFAULT_EV100 + 1.0);
    eprintln!("scene {scene}, display {base} at the default exposure, {darker} one stop darker");
    // Ambient light only (5,000 lux by default): well inside the range where "none" is linear.
    // The scene is pre-exposed: tonemapping "none" shows it as it is.
    assert!(scene > 0.01 && scene < 1.0, "{scene}");
    assert!(
        (base - scene).abs() < 1e-4 * scene.max(1.0),
        "{base} vs {scene}"
    );
    assert!((darker - 0.5 * base).abs() < 1e-4, "{darker} vs {base}");
}

/// A small lit parallax scene through the post-processing `path`.
fn post_processed(path: PostProcessPath) -> (image::RgbaImage, bool) {
    let view = PreviewView {
        view_angle: 40.0,
        ..PreviewView::default()
    };
    let mut app = started(RenderPlugin::new(64, 48).with_post_process(path));
    let material = cobbles().material(&mut app);
    pom::preview::spawn_preview(&mut app, material, &view).unwrap();
    // A light bright enough that tonemapping has highlights to compress.
    for light in app.world.query_mut::<&mut DirectionalLight>() {
        light.intensity = 300_000.0;
    }
    let compute = app
        .resources
        .get::<pom::render::Renderer>()
        .unwrap()
        .post_process_is_compute();
    (render_and_capture(&mut app).unwrap(), compute)
}

#[test]
fn compute_and_fragment_post_processing_write_the_same_pixels() {
    let (fastest, compute) = post_processed(PostProcessPath::Fastest);
    let (fragment, fragment_is_compute) = post_processed(PostProcessPath::Fragment);
    assert!(compute, "lavapipe can store rgba8unorm from compute");
    assert!(!fragment_is_compute);
    let largest = fastest
        .pixels()
        .zip(fragment.pixels())
        .flat_map(|(a, b)| (0..4).map(move |c| a.0[c].abs_diff(b.0[c])))
        .max()
        .unwrap();
    assert_eq!(largest, 0, "compute and fragment post-processing differ");
    assert!(
        fastest.pixels().any(|p| p.0[0] > 200),
        "no highlight to compare"
    );
}

#[test]
fn each_phase_is_timed_under_its_name() {
    let mut app =
        started(RenderPlugin::new(32, 32).with_gpu_timing(Some(pom::TimingMode::Blocking)));
    let material = cobbles().material(&mut app);
    pom::preview::spawn_preview(&mut app, material, &PreviewView::default()).unwrap();
    pom_tests::run_frames(&mut app, 3).unwrap();
    let timings = app.resources.get::<pom::GpuTimings>().unwrap();
    let pom::GpuTimings::Supported { passes, .. } = timings else {
        eprintln!("timestamps unsupported on this adapter: nothing to check");
        return;
    };
    let names: Vec<&str> = passes.keys().map(String::as_str).collect();
    eprintln!("timed: {passes:?}");
    for phase in [
        pom::RenderPhase::Prepass,
        pom::RenderPhase::Opaque,
        pom::RenderPhase::PostProcess,
    ] {
        assert!(
            names.contains(&phase.name()),
            "{} missing: {names:?}",
            phase.name()
        );
    }
}

#[test]
fn debug_views_bypass_exposure_and_tonemapping() {
    let view = PreviewView {
        view_angle: 30.0,
        ..PreviewView::default()
    };
    let uv_at = |ev100: f32, tonemapping: Tonemapping| {
        let mut app = preview_app(32, TargetFormat::Float32, &cobbles(), &view, |material| {
            ParallaxOcclusionMaterial {
                debug_view: pom::DebugView::Uv,
                ..material
            }
        })
        .unwrap();
        let camera = app
            .world
            .query::<(hecs::Entity, &Camera)>()
            .iter()
            .map(|(entity, _)| entity)
            .next()
            .unwrap();
        app.world
            .insert(camera, (Exposure { ev100 }, tonemapping))
            .unwrap();
        pom_tests::render_and_capture_f32(&mut app).unwrap()
    };
    let plain = uv_at(Exposure::DEFAULT_EV100, Tonemapping::None);
    let exposed = uv_at(8.0, Tonemapping::Aces);
    assert_eq!(plain.as_raw(), exposed.as_raw());
    // The data really is texture coordinates: fractions, the region code in blue.
    let centre = plain.get_pixel(16, 16).0;
    assert!(
        centre[0] > 0.0 && centre[0] < 1.0 && centre[3] == 1.0,
        "{centre:?}"
    );
}

/// A translucent full-screen triangle, drawn by a test plugin in the transparent phase.
struct TranslucentOverlay(pom::wgpu::RenderPipeline);

fn draw_translucent_overlay(resources: &pom::Resources, pass: &mut pom::wgpu::RenderPass<'_>) {
    if let Some(TranslucentOverlay(pipeline)) = resources.get::<TranslucentOverlay>() {
        pass.set_pipeline(pipeline);
        pass.draw(0..3, 0..1);
    }
}

#[test]
fn the_transparent_phase_blends_over_the_opaque_result_and_keeps_its_depth() {
    use pom::wgpu;
    // `overlay_depth`: where the translucent triangle lies (0 = at the near plane), if drawn.
    let render = |overlay_depth: Option<f32>| {
        // The 8-bit target: its Rgba16Float scene blends everywhere (Rgba32Float needs
        // FLOAT32_BLENDABLE).
        let mut app = started(RenderPlugin::new(16, 16));
        let plane = plane(&mut app, 4.0);
        app.world.spawn((
            plane,
            LitMaterial::from_color(Color::linear_rgb(0.0, 0.0, 0.5)),
            Transform::IDENTITY,
        ));
        app.world.spawn((
            Camera::orthographic(2.0),
            Tonemapping::None,
            Transform::from_xyz(0.0, 2.0, 0.0).looking_at(Vec3::ZERO, Vec3::Z),
        ));
        if let Some(depth) = overlay_depth {
            let gpu = app.resources.get::<GpuContext>().unwrap();
            let shader = gpu
                .device
                .create_shader_module(wgpu::ShaderModuleDescriptor {
                    label: Some("translucent overlay"),
                    source: wgpu::ShaderSource::Wgsl(
                        format!(
                            "@vertex fn vs(@builtin(vertex_index) i: u32) -> @builtin(position) vec4<f32> {{
                                 let uv = vec2<f32>(f32((i << 1u) & 2u), f32(i & 2u));
                                 return vec4<f32>(uv * 2.0 - 1.0, {depth:?}, 1.0);
                             }}
                             @fragment fn fs() -> @location(0) vec4<f32> {{ return vec4<f32>(1.0, 0.0, 0.0, 0.5); }}"
                        )
                        .into(),
                    ),
                });
            let pipeline = gpu
                .device
                .create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                    label: Some("translucent overlay"),
                    layout: None,
                    vertex: wgpu::VertexState {
                        module: &shader,
                        entry_point: Some("vs"),
                        compilation_options: Default::default(),
                        buffers: &[],
                    },
                    primitive: Default::default(),
                    // The transparent phase's depth is read-only: test, never write.
                    depth_stencil: Some(wgpu::DepthStencilState {
                        format: wgpu::TextureFormat::Depth32Float,
                        depth_write_enabled: Some(false),
                        depth_compare: Some(wgpu::CompareFunction::LessEqual),
                        stencil: Default::default(),
                        bias: Default::default(),
                    }),
                    multisample: Default::default(),
                    fragment: Some(wgpu::FragmentState {
                        module: &shader,
                        entry_point: Some("fs"),
                        compilation_options: Default::default(),
                        targets: &[Some(wgpu::ColorTargetState {
                            format: TargetFormat::Srgb8.scene_format(),
                            blend: Some(wgpu::BlendState {
                                color: wgpu::BlendComponent {
                                    src_factor: wgpu::BlendFactor::SrcAlpha,
                                    dst_factor: wgpu::BlendFactor::OneMinusSrcAlpha,
                                    operation: wgpu::BlendOperation::Add,
                                },
                                alpha: wgpu::BlendComponent::REPLACE,
                            }),
                            write_mask: wgpu::ColorWrites::ALL,
                        })],
                    }),
                    multiview_mask: None,
                    cache: None,
                });
            app.insert_resource(TranslucentOverlay(pipeline));
            app.resources
                .get_or_default::<pom::render::RenderPhases>()
                .add_draw::<TranslucentOverlay>(
                    pom::render::DrawPhase::Transparent,
                    draw_translucent_overlay,
                );
        }
        render_and_capture(&mut app).unwrap()
    };
    let linear = |byte: u8| pom::srgb_to_linear(f32::from(byte) / 255.0);
    let opaque = render(None);
    let blended = render(Some(0.0));
    // The plane lies at depth 0.01: a triangle behind it is hidden by the opaque phase's depth.
    let behind = render(Some(0.9));
    assert_eq!(behind.as_raw(), opaque.as_raw(), "drawn behind the plane");
    let (below, over) = (opaque.get_pixel(8, 8).0, blended.get_pixel(8, 8).0);
    eprintln!("opaque {below:?}, with a half-transparent red over it {over:?}");
    // Half red over the plane's colour: the opaque result was kept and blended over.
    assert!((linear(over[0]) - 0.5).abs() < 0.01, "{over:?}");
    assert!(linear(below[2]) > 0.01, "{below:?}");
    assert!(
        (linear(over[2]) - 0.5 * linear(below[2])).abs() < 0.01,
        "{over:?} over {below:?}"
    );
}
