//! The renderer's features join the frame as plugins: an app without anti-aliasing or scene
//! shadows runs none of their passes or timings and shows what the frame rendered; a game's
//! own post effect runs where its stage puts it; nodes that cannot be ordered are errors that
//! name them.

use std::path::Path;

use pom::gpu::PassTimestamps;
use pom::render::{
    FrameNode, FrameNodes, FrameView, FullScreenPass, NodePlace, PostEffect, PostImage, PostIo,
    PostStage, RenderError, RenderFeature, RenderPhase,
};
use pom::{AntiAliasing, App, GpuTimings, PomPlugin, RenderPlugin, TimingMode, load_gltf};
use pom_tests::anti_aliasing::{set_anti_aliasing, turned_square_with};
use pom_tests::{render_and_capture, run_frames};

/// The names of the passes the last read frame timed.
fn timed_passes(app: &App) -> Vec<String> {
    match app.resources.get::<GpuTimings>() {
        Some(GpuTimings::Supported { passes, .. }) => passes.keys().cloned().collect(),
        other => panic!("no timings: {other:?}"),
    }
}

fn blocking(render: RenderPlugin) -> RenderPlugin {
    render.with_gpu_timing(Some(TimingMode::Blocking))
}

#[test]
fn without_anti_aliasing_a_camera_asking_for_it_gets_the_frame_as_rendered() {
    let plain = |render: RenderPlugin, mode| {
        let mut app = turned_square_with(blocking(render));
        set_anti_aliasing(&mut app, mode);
        run_frames(&mut app, 3).unwrap();
        let image = render_and_capture(&mut app).unwrap();
        (image, timed_passes(&app), app)
    };
    let (off, _, _) = plain(RenderPlugin::new(48, 48), AntiAliasing::Off);
    for mode in [AntiAliasing::Taa, AntiAliasing::Fxaa] {
        let without = RenderPlugin::new(48, 48).without(RenderFeature::AntiAliasing);
        let (image, passes, app) = plain(without, mode);
        assert!(
            !passes
                .iter()
                .any(|pass| ["taa", "post_filter", "object_motion"].contains(&pass.as_str())),
            "{mode:?}: {passes:?}"
        );
        let nodes = app.resources.get::<FrameNodes>().unwrap();
        assert!(!nodes.contains("taa") && !nodes.contains("post_filter"));
        assert!(image == off, "{mode:?} without the plugin differs from off");
        // With the plugin the same camera's pass runs and is timed.
        let (_, passes, _) = plain(RenderPlugin::new(48, 48), mode);
        let name = if mode == AntiAliasing::Taa {
            "taa"
        } else {
            "post_filter"
        };
        assert!(passes.iter().any(|pass| pass == name), "{passes:?}");
    }
}

/// The street corner with its sun casting scene shadows, rendered by `render`.
fn shadowed_street_corner(render: RenderPlugin, shadows: bool) -> App {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets/street_corner.glb");
    let mut app = App::new();
    app.add_plugin(blocking(render)).add_plugin(PomPlugin);
    let scene = load_gltf(&mut app, &path).unwrap();
    if shadows {
        for &light in &scene.lights {
            app.world
                .insert_one(light, pom::LightShadows::default())
                .unwrap();
        }
    }
    app
}

#[test]
fn without_scene_shadows_lights_cast_none_and_no_shadow_pass_runs() {
    let render = RenderPlugin::new(96, 54);
    let mut without = shadowed_street_corner(render.without(RenderFeature::SceneShadows), true);
    run_frames(&mut without, 2).unwrap();
    let image = render_and_capture(&mut without).unwrap();
    let passes = timed_passes(&without);
    assert!(!passes.iter().any(|pass| pass == "shadows"), "{passes:?}");
    let mut unshadowed = shadowed_street_corner(render, false);
    assert!(image == render_and_capture(&mut unshadowed).unwrap());
    // A node of a game's own in the shadows phase does not make the frame plan maps that no
    // one draws (they would shadow every receiver).
    let mut own_node = shadowed_street_corner(render.without(RenderFeature::SceneShadows), true);
    own_node
        .resources
        .get_or_default::<FrameNodes>()
        .add(NodePlace::new("own", RenderPhase::Shadows), || Idle);
    run_frames(&mut own_node, 2).unwrap();
    assert!(render_and_capture(&mut own_node).unwrap() == image);
    let mut shadowed = shadowed_street_corner(render, true);
    run_frames(&mut shadowed, 2).unwrap();
    let with_shadows = render_and_capture(&mut shadowed).unwrap();
    assert!(timed_passes(&shadowed).iter().any(|pass| pass == "shadows"));
    assert!(with_shadows != image, "the shadows plugin changed nothing");
}

/// A frame node with nothing to do.
struct Idle;

impl FrameNode for Idle {
    fn runs(&self, _: FrameView<'_>) -> bool {
        false
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

/// An HDR effect that scales the scene's colour by its parameter.
struct Gain {
    gain: f32,
    pass: Option<FullScreenPass>,
}

#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct GainParams {
    gain: f32,
}

/// It leaves a display-referred pixel (the clear colour) alone.
const GAIN: &str = "
struct EffectParams { gain: f32 }
fn effect(pixel: vec2<u32>) -> vec4<f32> {
    let colour = textureLoad(input, pixel, 0);
    if is_display_referred(colour.a) {
        return colour;
    }
    return vec4<f32>(from_linear(to_linear(colour.rgb) * params.gain), colour.a);
}
";

impl PostEffect for Gain {
    fn stage(&self) -> PostStage {
        PostStage::Hdr
    }

    fn runs(&self, _: FrameView<'_>) -> bool {
        true
    }

    /// Makes the pass on the first frame and uploads the gain when it changed; the bytes count
    /// in the frame's uploads.
    fn prepare(
        &mut self,
        resources: &mut pom::Resources,
        _: pom::render::HdrInput,
    ) -> Result<u64, RenderError> {
        let frame = FrameView::of(resources)?;
        let pass = self.pass.get_or_insert_with(|| {
            FullScreenPass::with_params::<GainParams>(frame, PostStage::Hdr, "gain", GAIN)
        });
        Ok(pass.write_params(frame, &GainParams { gain: self.gain }))
    }

    fn record(
        &mut self,
        frame: FrameView<'_>,
        io: PostIo<'_>,
        encoder: &mut pom::wgpu::CommandEncoder,
        time: Option<&PassTimestamps>,
    ) -> Result<Option<PostImage>, RenderError> {
        if let Some(pass) = &mut self.pass {
            pass.record(frame, io, encoder, time)?;
        }
        Ok(None)
    }
}

/// The uniform bytes the app's last frame uploaded.
fn uploaded(app: &App) -> u64 {
    let renderer = app.resources.get::<pom::render::Renderer>().unwrap();
    renderer.last_upload.uniform_bytes
}

#[test]
fn an_hdr_effect_with_parameters_darkens_the_scene_but_not_the_clear_colour() {
    let render = |path| blocking(RenderPlugin::new(48, 48).with_post_process(path));
    for path in [
        pom::PostProcessPath::Fastest,
        pom::PostProcessPath::Fragment,
    ] {
        let mut plain = turned_square_with(render(path));
        plain.update().unwrap();
        let plain_upload = uploaded(&plain);
        let before = render_and_capture(&mut plain).unwrap();
        let mut app = turned_square_with(render(path));
        app.resources
            .get_or_default::<FrameNodes>()
            .add_post_effect("gain", || Gain {
                gain: 0.0,
                pass: None,
            });
        app.update().unwrap();
        // The gain's bytes count in the frame's uploads.
        assert_eq!(
            uploaded(&app),
            plain_upload + std::mem::size_of::<GainParams>() as u64,
            "{path:?}"
        );
        run_frames(&mut app, 1).unwrap();
        let after = render_and_capture(&mut app).unwrap();
        assert!(timed_passes(&app).iter().any(|pass| pass == "gain"));
        // The square turns black; the clear colour, display-referred, stays.
        let clear = *before.get_pixel(0, 0);
        let mut square = 0;
        for (x, y, pixel) in after.enumerate_pixels() {
            let was = *before.get_pixel(x, y);
            if was == clear {
                assert_eq!(*pixel, clear, "{path:?} ({x}, {y})");
            } else {
                square += 1;
                assert_eq!(&pixel.0[..3], &[0, 0, 0], "{path:?} ({x}, {y}) was {was:?}");
            }
        }
        assert!(square > 200, "{path:?}: only {square} pixels of the square");
    }
}

#[test]
fn nodes_placed_against_unknown_names_or_in_a_cycle_are_errors_naming_them() {
    let mut app = turned_square_with(RenderPlugin::new(16, 16));
    let place = NodePlace::new("grade", RenderPhase::PostProcess).after("bloom");
    app.resources
        .get_or_default::<FrameNodes>()
        .add_post_effect_at(place, || Gain {
            gain: 1.0,
            pass: None,
        });
    let error = app.update().unwrap_err().to_string();
    assert!(
        error.contains("\"grade\"") && error.contains("\"bloom\""),
        "{error}"
    );

    let mut app = turned_square_with(RenderPlugin::new(16, 16));
    let nodes = app.resources.get_or_default::<FrameNodes>();
    let a = NodePlace::new("a", RenderPhase::PostProcess).after("b");
    let b = NodePlace::new("b", RenderPhase::PostProcess).after("a");
    nodes.add_post_effect_at(a, || Gain {
        gain: 1.0,
        pass: None,
    });
    nodes.add_post_effect_at(b, || Gain {
        gain: 1.0,
        pass: None,
    });
    let error = app.update().unwrap_err().to_string();
    assert!(
        error.contains("cycle") && error.contains("\"a\""),
        "{error}"
    );
}

#[test]
fn a_frame_without_tonemapping_is_an_error_naming_it() {
    let mut app = turned_square_with(RenderPlugin::new(16, 16).without(RenderFeature::Tonemapping));
    let error = app.update().unwrap_err().to_string();
    assert!(error.contains("tonemapping"), "{error}");
}

/// An HDR effect that writes its input through and counts the frames whose input it was told
/// TAA had tonemapped.
struct Probe {
    pass: Option<FullScreenPass>,
    tonemapped_frames: std::rc::Rc<std::cell::Cell<u32>>,
}

impl PostEffect for Probe {
    fn stage(&self) -> PostStage {
        PostStage::Hdr
    }

    fn runs(&self, _: FrameView<'_>) -> bool {
        true
    }

    fn record(
        &mut self,
        frame: FrameView<'_>,
        io: PostIo<'_>,
        encoder: &mut pom::wgpu::CommandEncoder,
        time: Option<&PassTimestamps>,
    ) -> Result<Option<PostImage>, RenderError> {
        if io.holds == pom::render::HdrInput::Tonemapped {
            self.tonemapped_frames.set(self.tonemapped_frames.get() + 1);
        }
        let copy =
            "fn effect(pixel: vec2<u32>) -> vec4<f32> { return textureLoad(input, pixel, 0); }";
        self.pass
            .get_or_insert_with(|| FullScreenPass::new(frame, PostStage::Hdr, "probe", copy))
            .record(frame, io, encoder, time)?;
        Ok(None)
    }
}

#[test]
fn hdr_effects_run_after_taa_and_are_told_its_history_is_tonemapped() {
    let tonemapped_frames = std::rc::Rc::new(std::cell::Cell::new(0));
    let count = tonemapped_frames.clone();
    let probe = move || Probe {
        pass: None,
        tonemapped_frames: count.clone(),
    };
    let mut app = turned_square_with(RenderPlugin::new(32, 32));
    set_anti_aliasing(&mut app, AntiAliasing::Taa);
    app.resources
        .get_or_default::<FrameNodes>()
        .add_post_effect("probe", probe.clone());
    run_frames(&mut app, 3).unwrap();
    assert_eq!(tonemapped_frames.get(), 3);

    // Placed before TAA, which reads the scene itself, it would be lost: an error naming both.
    let mut app = turned_square_with(RenderPlugin::new(32, 32));
    set_anti_aliasing(&mut app, AntiAliasing::Taa);
    let place = NodePlace::new("probe", RenderPhase::PostProcess).before("taa");
    app.resources
        .get_or_default::<FrameNodes>()
        .add_post_effect_at(place, probe);
    let error = app.update().unwrap_err().to_string();
    assert!(
        error.contains("\"taa\"") && error.contains("\"probe\""),
        "{error}"
    );
}

/// A display effect whose WGSL names a variable it never declares, on line 3 of its own code.
struct Broken {
    pass: Option<FullScreenPass>,
}

const BROKEN: &str = "
fn effect(pixel: vec2<u32>) -> vec4<f32> {
    return textureLoad(input, pixel, 0) * missing_gain;
}
";

impl PostEffect for Broken {
    fn stage(&self) -> PostStage {
        PostStage::Display
    }

    fn runs(&self, _: FrameView<'_>) -> bool {
        true
    }

    fn record(
        &mut self,
        frame: FrameView<'_>,
        io: PostIo<'_>,
        encoder: &mut pom::wgpu::CommandEncoder,
        time: Option<&PassTimestamps>,
    ) -> Result<Option<PostImage>, RenderError> {
        self.pass
            .get_or_insert_with(|| FullScreenPass::new(frame, PostStage::Display, "broken", BROKEN))
            .record(frame, io, encoder, time)?;
        Ok(None)
    }
}

#[test]
fn an_effect_whose_wgsl_does_not_compile_is_an_error_naming_it_and_its_line() {
    let mut app = turned_square_with(RenderPlugin::new(16, 16));
    app.resources
        .get_or_default::<FrameNodes>()
        .add_post_effect("broken", || Broken { pass: None });
    // No wgpu validation error: the WGSL is checked before any GPU object is made of it.
    let error = pom_tests::in_error_scopes(&mut app, "broken effect", |app| {
        Ok(app.update().unwrap_err().to_string())
    })
    .unwrap();
    eprintln!("{error}");
    assert!(
        error.contains("\"broken\"") && error.contains("line 3") && error.contains("missing_gain"),
        "{error}"
    );
}
