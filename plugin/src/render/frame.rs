//! The renderer's Prepare and Render stage systems: [`prepare_frame`] uploads the frame's data,
//! [`render_frame`] decides what the frame runs ([`FramePlan`]) and runs one function per
//! phase (frame_passes.rs), in the order `phases.rs` documents.

use super::frame_passes::{FramePasses, PostTimes, clear_value, post_process};
use super::{
    DERIVED_TEXTURES_PASS, DrawPhase, ExtractedFrame, FrameUniform, GpuContext, PassTimestamps,
    PostSettings, RenderPhase, RenderPhases, RenderTarget, Renderer, UploadStats, render_path,
    time_pass,
};
use crate::{AppError, Assets, Image, Mesh, Resources};

/// The Prepare stage's system: frees GPU copies of dropped assets and uploads the frame uniform.
/// It runs before every material's Prepare system (materials need [`super::RenderPlugin`]
/// first), and starts this frame's [`Renderer::last_upload`] count.
pub fn prepare_frame(_: &mut hecs::World, resources: &mut Resources) -> Result<(), AppError> {
    resources.require_scope(|resources, renderer: &mut Renderer| {
        let gpu = resources.require::<GpuContext>()?;
        let extracted = resources.require::<ExtractedFrame>()?;
        let meshes = resources.require::<Assets<Mesh>>()?;
        let images = resources.require::<Assets<Image>>()?;
        let target = resources.require::<RenderTarget>()?;
        renderer.choose_path(gpu, target, render_path::deferred_blocker(resources));
        renderer.visibility_ids.reset();
        renderer.object_motions.reset();
        if let (true, Some(background), Some(visibility)) = (
            renderer.deferred,
            &mut renderer.background,
            &renderer.visibility,
        ) {
            background.prepare(gpu, target, visibility, clear_value(extracted.clear_color));
        }
        renderer.assets.release_freed(meshes, images);
        // TAA's history holds display values already.
        let tonemapping = match extracted.temporal {
            Some(_) => crate::Tonemapping::None,
            None => extracted.tonemapping,
        };
        let settings = PostSettings::new(tonemapping, target.target_format());
        renderer.last_upload = UploadStats {
            uniform_bytes: renderer
                .frame
                .upload(gpu, &extracted.frame, &light_views(extracted))
                + renderer.shadow_maps.prepare(gpu, &extracted.shadow_views)
                + renderer.post.upload(gpu, settings),
            ..UploadStats::default()
        };
        Ok(())
    })
}

/// The frame uniform each shadow map sees: the same lights, the light's eye, and textures read
/// at the light's own footprint (anti-aliasing's mip bias is the camera's).
fn light_views(extracted: &ExtractedFrame) -> Vec<FrameUniform> {
    extracted
        .shadow_views
        .iter()
        .map(|plan| FrameUniform {
            view_projection: plan.gpu.view_projection,
            camera_position: plan.eye.extend(1.0).into(),
            view_direction: plan
                .forward
                .extend(if plan.orthographic { 1.0 } else { 0.0 })
                .into(),
            texture_lod: [1.0, 0.0, 0.0, 0.0],
            ..extracted.frame
        })
        .collect()
}

/// The Render stage's system: builds the textures derived this frame, then runs the phases in
/// order (prepass, shadows, opaque, resolve, transparent; then post-processing in a second
/// submission; the overlay belongs to the application), each timed under its name.
pub fn render_frame(_: &mut hecs::World, resources: &mut Resources) -> Result<(), AppError> {
    // Every material has prepared its draws: order the sorted phases across materials.
    let renderer = resources.require_mut::<Renderer>()?;
    renderer.prepass_order.sort();
    renderer.transparent.sort();
    let plan = FramePlan::new(resources)?;
    if plan.object_motion {
        // The materials have numbered their moving draws.
        resources.require_scope(|resources, renderer: &mut Renderer| {
            let gpu = resources.require::<GpuContext>()?;
            let target = resources.require::<RenderTarget>()?;
            renderer.object_motions.prepare(gpu, target);
            Ok(())
        })?;
    }
    resources.require_mut::<Renderer>()?.ran_opaque_pass = plan.opaque_pass;
    let times = PhaseTimes::reserve(&plan, resources);
    let passes = FramePasses::new(resources, &plan)?;
    let mut encoder = passes.encoder("frame encoder");
    // Textures derived in the Prepare stage are built before every phase that may read them.
    passes.derived_textures(&mut encoder, times.derived.as_ref());
    if plan.prepass {
        passes.prepass(&mut encoder, times.prepass.as_ref());
    }
    if plan.shadow_maps {
        passes.shadow_maps(&mut encoder, times.shadows.as_ref());
    }
    if plan.shadow_work {
        passes.shadow_work(&mut encoder);
    }
    if plan.opaque_pass {
        passes.opaque(&mut encoder, times.opaque.as_ref());
    }
    passes.work(RenderPhase::Opaque, &mut encoder);
    if plan.resolve {
        passes.resolve(&mut encoder, times.resolve.as_ref());
    }
    passes.work(RenderPhase::Resolve, &mut encoder);
    if plan.transparent {
        passes.transparent(&mut encoder, times.transparent.as_ref());
    }
    passes.work(RenderPhase::Transparent, &mut encoder);
    if plan.object_motion {
        passes.object_motion(&mut encoder, times.object_motion.as_ref());
    }
    passes.submit(encoder);
    // Post-processing borrows the renderer mutably (its bind group follows the target).
    post_process(
        resources,
        &plan,
        PostTimes {
            taa: times.taa.as_ref(),
            post: times.post.as_ref(),
            post_filter: times.post_filter.as_ref(),
        },
    )
}

/// What this frame runs, decided once from the camera, the path and what the materials queued.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct FramePlan {
    /// A camera sees the frame (without one, nothing is drawn; the target is still cleared).
    pub has_camera: bool,
    /// The frame runs the deferred path.
    pub deferred: bool,
    /// The depth prepass (the visibility pass, deferred) runs.
    pub prepass: bool,
    /// Shadow maps are drawn.
    pub shadow_maps: bool,
    /// Materials' own work of the shadows phase runs.
    pub shadow_work: bool,
    /// The opaque render pass runs: a deferred frame whose opaque phase draws nothing writes
    /// the background from compute instead of clearing the scene in an empty render pass.
    pub opaque_pass: bool,
    /// The deferred compute resolve runs.
    pub resolve: bool,
    /// The resolve also writes the background.
    pub background_in_compute: bool,
    /// The transparent phase runs.
    pub transparent: bool,
    /// Textures derived from images are built this frame.
    pub derived_textures: bool,
    /// Temporal anti-aliasing runs before tonemapping.
    pub taa: bool,
    /// TAA's object motion pass runs (a draw moved since the last frame).
    pub object_motion: bool,
    /// The post filter runs after tonemapping.
    pub post_filter: bool,
}

impl FramePlan {
    fn new(resources: &Resources) -> Result<Self, AppError> {
        let extracted = resources.require::<ExtractedFrame>()?;
        let renderer = resources.require::<Renderer>()?;
        let has_camera = extracted.has_camera;
        let phases = resources.get::<RenderPhases>();
        let has =
            |phase: DrawPhase| has_camera && phases.is_some_and(|p| p.has_draws(phase, resources));
        let has_work = |phase: RenderPhase| {
            has_camera && phases.is_some_and(|p| p.work(phase).next().is_some())
        };
        let shadow_maps = !extracted.shadow_views.is_empty()
            && phases.is_some_and(|p| p.shadow_draws().next().is_some());
        let prepass = renderer.depth_prepass
            && (has(DrawPhase::Prepass)
                || (has_camera
                    && phases.is_some_and(|p| p.sorted_draw_count(DrawPhase::Prepass) > 0)));
        let resolve = renderer.deferred
            && prepass
            && has_camera
            && phases.is_some_and(|p| p.has_resolves(resources));
        let background_in_compute = resolve && !has(DrawPhase::Opaque);
        let anti_aliasing = extracted.anti_aliasing;
        let taa = has_camera && extracted.temporal.is_some();
        Ok(Self {
            taa,
            object_motion: taa && renderer.object_motions.any() && has(DrawPhase::Motion),
            post_filter: anti_aliasing == super::AntiAliasing::Fxaa,
            has_camera,
            deferred: renderer.deferred,
            prepass,
            shadow_maps,
            shadow_work: shadow_maps || has_work(RenderPhase::Shadows),
            opaque_pass: !background_in_compute,
            resolve,
            background_in_compute,
            transparent: has(DrawPhase::Transparent)
                || (has_camera && !renderer.transparent.is_empty()),
            derived_textures: !renderer.assets.pending_derived_builds().is_empty(),
        })
    }
}

/// The timestamps each phase writes, reserved before recording (the timer is borrowed
/// mutably).
struct PhaseTimes {
    prepass: Option<PassTimestamps>,
    shadows: Option<PassTimestamps>,
    opaque: Option<PassTimestamps>,
    resolve: Option<PassTimestamps>,
    transparent: Option<PassTimestamps>,
    object_motion: Option<PassTimestamps>,
    taa: Option<PassTimestamps>,
    post: Option<PassTimestamps>,
    post_filter: Option<PassTimestamps>,
    derived: Option<PassTimestamps>,
}

impl PhaseTimes {
    fn reserve(plan: &FramePlan, resources: &mut Resources) -> Self {
        let mut time = |run: bool, name: &str| run.then(|| time_pass(resources, name)).flatten();
        Self {
            prepass: time(plan.prepass, RenderPhase::Prepass.name()),
            shadows: time(plan.shadow_maps, RenderPhase::Shadows.name()),
            opaque: time(plan.opaque_pass, RenderPhase::Opaque.name()),
            resolve: time(plan.resolve, RenderPhase::Resolve.name()),
            transparent: time(plan.transparent, RenderPhase::Transparent.name()),
            object_motion: time(plan.object_motion, super::OBJECT_MOTION_PASS),
            taa: time(plan.taa, super::TAA_PASS),
            post: time(true, RenderPhase::PostProcess.name()),
            post_filter: time(plan.post_filter, super::POST_FILTER_PASS),
            // Reserved last: where a frame times more passes than the timer holds, the phases
            // keep theirs.
            derived: time(plan.derived_textures, DERIVED_TEXTURES_PASS),
        }
    }
}
