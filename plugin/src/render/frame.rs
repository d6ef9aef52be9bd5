//! The renderer's Prepare and Render stage systems: [`prepare_frame`] uploads the frame's data,
//! [`render_frame`] decides what the core runs ([`FramePlan`]) and which feature nodes have
//! work, then runs each phase's core pass (frame_passes.rs) and nodes, in the order
//! `phases.rs` documents, and the post chain (post_chain.rs).

use super::frame_nodes::{FrameView, NodeWork};
use super::frame_passes::{FramePasses, clear_value};
use super::post_chain::{self, ChainLink};
use super::{
    DrawPhase, ExtractedFrame, FrameNodes, FrameUniform, RenderError, RenderPhase, RenderPhases,
    RenderTarget, Renderer, SettledDepth, render_path,
};
use crate::gpu::{DERIVED_TEXTURES_PASS, GpuContext, PassTimestamps, UploadStats, time_pass};
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
        renderer.resolves_write_background = false;
        if let (true, Some(background), Some(visibility)) = (
            renderer.deferred,
            &mut renderer.background,
            &renderer.visibility,
        ) {
            background.prepare(gpu, target, visibility, clear_value(extracted.clear_color));
        }
        renderer.assets.release_freed(meshes, images);
        // Scatters of a Prepare stage no frame recorded land before this frame's writes.
        renderer.assets.scatters().submit_unrecorded(gpu);
        renderer.shadow_maps.casters.begin_frame();
        renderer.last_upload = UploadStats {
            uniform_bytes: renderer
                .frame
                .upload(gpu, &extracted.frame, &light_views(extracted))
                + renderer.shadow_maps.prepare(gpu, &extracted.shadow_views)
                + renderer
                    .lights
                    .prepare(gpu, &extracted.point_lights, &extracted.light_clusters),
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
/// order, each phase's core pass followed by the feature nodes ([`FrameNodes`]) and the
/// materials' work of that phase (prepass, shadows, opaque, resolve, transparent; then the post
/// chain in a second submission; the overlay belongs to the application), each timed under its
/// name.
pub fn render_frame(_: &mut hecs::World, resources: &mut Resources) -> Result<(), RenderError> {
    // Every material has prepared its draws: order the sorted phases across materials.
    let renderer = resources.require_mut::<Renderer>()?;
    renderer.prepass_order.sort();
    renderer.candidate_order.sort();
    renderer.transparent.sort();
    resources
        .scope(|resources, nodes: &mut FrameNodes| render_nodes(resources, nodes))
        .unwrap_or_else(|| Err(AppError::missing::<FrameNodes>().into()))
}

/// [`render_frame`] once the frame's nodes are taken out of the resources (they record with
/// the resources borrowed).
fn render_nodes(resources: &mut Resources, nodes: &mut FrameNodes) -> Result<(), RenderError> {
    nodes.order()?;
    nodes.follow_device(&resources.require::<GpuContext>()?.device);
    let runs = running_nodes(resources, nodes)?;
    let nodes_use = |uses: fn(&NodeWork) -> bool| {
        nodes
            .iter()
            .zip(&runs)
            .any(|(node, runs)| *runs && uses(&node.work))
    };
    let depth_use = (
        nodes_use(NodeWork::reads_scene_depth),
        nodes_use(NodeWork::samples_scene_depth),
    );
    let plan = FramePlan::new(resources, depth_use)?;
    resources
        .require_scope(|resources, renderer: &mut Renderer| plan.prepare(resources, renderer))?;
    // After the plan: a node binds the scene's depth where this frame settles it.
    prepare_nodes(resources, nodes, &runs)?;
    let times = PhaseTimes::reserve(&plan, nodes, &runs, resources);
    // Taken out while the frame borrows the renderer; recorded first, or submitted alone where
    // the frame cannot start (what the Prepare stage uploaded must still land).
    let mut scatters = std::mem::take(resources.require_mut::<Renderer>()?.assets.scatters());
    let passes = match FramePasses::new(resources, &plan) {
        Ok(passes) => passes,
        Err(error) => {
            scatters.submit_unrecorded(resources.require::<GpuContext>()?);
            return Err(error.into());
        }
    };
    let view = passes.view();
    let record = |phase, nodes: &mut FrameNodes, encoder: &mut wgpu::CommandEncoder| {
        record_nodes(phase, (nodes, &runs, &times.nodes), view, encoder)
    };
    let mut encoder = passes.encoder("frame encoder");
    scatters.record(&mut encoder);
    // Textures derived in the Prepare stage are built before every phase that may read them.
    passes.derived_textures(&mut encoder, times.derived.as_ref());
    if plan.prepass {
        passes.prepass(&mut encoder, times.prepass.as_ref());
    }
    record(RenderPhase::Prepass, nodes, &mut encoder)?;
    passes.work(RenderPhase::Prepass, &mut encoder);
    record(RenderPhase::Shadows, nodes, &mut encoder)?;
    passes.work(RenderPhase::Shadows, &mut encoder);
    if plan.opaque_pass {
        passes.opaque(&mut encoder, times.opaque.as_ref());
    }
    record(RenderPhase::Opaque, nodes, &mut encoder)?;
    passes.work(RenderPhase::Opaque, &mut encoder);
    if plan.resolve {
        passes.resolve(&mut encoder, times.resolve.as_ref());
    }
    record(RenderPhase::Resolve, nodes, &mut encoder)?;
    passes.work(RenderPhase::Resolve, &mut encoder);
    if plan.transparent {
        passes.transparent(&mut encoder, times.transparent.as_ref());
    }
    record(RenderPhase::Transparent, nodes, &mut encoder)?;
    passes.work(RenderPhase::Transparent, &mut encoder);
    passes.submit(encoder);
    post_chain(resources, nodes, &runs, times.nodes)
}

/// Which of `nodes` have work this frame, in their order.
fn running_nodes(resources: &Resources, nodes: &FrameNodes) -> Result<Vec<bool>, RenderError> {
    let view = FrameView::of(resources)?;
    Ok(nodes.iter().map(|node| node.work.runs(view)).collect())
}

/// Prepares the nodes that run, adding what they upload to [`Renderer::last_upload`].
fn prepare_nodes(
    resources: &mut Resources,
    nodes: &mut FrameNodes,
    runs: &[bool],
) -> Result<(), RenderError> {
    let hdr_input = post_chain::hdr_input(
        nodes
            .iter()
            .zip(runs)
            .filter(|(_, runs)| **runs)
            .filter_map(|(node, _)| node.work.post_effect()),
    );
    let mut uploaded = 0;
    for (node, _) in nodes.iter_mut().zip(runs).filter(|(_, runs)| **runs) {
        uploaded += match &mut node.work {
            NodeWork::Frame(work) => work.prepare(resources)?,
            NodeWork::Post(effect) => effect.prepare(resources, hdr_input)?,
        };
    }
    resources
        .require_mut::<Renderer>()?
        .last_upload
        .uniform_bytes += uploaded;
    Ok(())
}

/// Records the nodes of `phase` that run, each with its timestamps.
fn record_nodes(
    phase: RenderPhase,
    (nodes, runs, times): (&mut FrameNodes, &[bool], &[Option<PassTimestamps>]),
    view: FrameView<'_>,
    encoder: &mut wgpu::CommandEncoder,
) -> Result<(), RenderError> {
    for ((node, runs), time) in nodes.iter_mut().zip(runs).zip(times) {
        if let (true, true, NodeWork::Frame(work)) =
            (node.place.phase == phase, *runs, &mut node.work)
        {
            work.record(view, encoder, time.as_ref())?;
        }
    }
    Ok(())
}

/// The post chain and the materials' work of the post phase, in a submission after the
/// frame's.
fn post_chain(
    resources: &mut Resources,
    nodes: &mut FrameNodes,
    runs: &[bool],
    times: Vec<Option<PassTimestamps>>,
) -> Result<(), RenderError> {
    let renderer = resources.require_mut::<Renderer>()?;
    renderer.assets.derived_builds_submitted();
    let mut images = std::mem::take(&mut renderer.post_images);
    let result = (|| {
        let view = FrameView::of(resources)?;
        // The chain's effects, and the frame nodes of the post and overlay phases, which
        // record after it.
        let mut links: Vec<ChainLink<'_>> = Vec::new();
        let mut late = Vec::new();
        for ((node, _), time) in nodes
            .iter_mut()
            .zip(runs)
            .zip(times)
            .filter(|((_, r), _)| **r)
        {
            let name = node.place.name;
            match &mut node.work {
                NodeWork::Post(effect) => links.push(ChainLink {
                    name,
                    effect: effect.as_mut(),
                    time,
                }),
                NodeWork::Frame(work) if node.place.phase >= RenderPhase::PostProcess => {
                    late.push((work, time));
                }
                NodeWork::Frame(_) => {}
            }
        }
        links.sort_by_key(|link| post_chain::stage_rank(link.effect.stage()));
        let mut encoder = view
            .gpu
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("post-process encoder"),
            });
        post_chain::record_chain(&mut images, view, links, &mut encoder)?;
        if let Some(phases) = resources.get::<RenderPhases>() {
            for work in phases.work(RenderPhase::PostProcess) {
                work(resources, &mut encoder);
            }
        }
        for (work, time) in late {
            work.record(view, &mut encoder, time.as_ref())?;
        }
        view.gpu.queue.submit([encoder.finish()]);
        Ok(())
    })();
    resources.require_mut::<Renderer>()?.post_images = images;
    result
}

/// What this frame runs of the core's own passes, decided once from the camera, the path and
/// what the materials queued.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct FramePlan {
    /// A camera sees the frame (without one, nothing is drawn; the target is still cleared).
    pub has_camera: bool,
    /// The frame runs the deferred path.
    pub deferred: bool,
    /// The depth prepass (the visibility pass, deferred) runs.
    pub prepass: bool,
    /// The opaque render pass runs: a deferred frame whose opaque phase draws nothing writes
    /// the background from compute instead of clearing the scene in an empty render pass.
    pub opaque_pass: bool,
    /// A pass after the opaque phase reads the depth: the opaque pass keeps what it writes.
    pub keep_depth: bool,
    /// How the passes after the resolve get its candidates' settled depth.
    pub settled_depth: SettledDepth,
    /// The deferred compute resolve runs.
    pub resolve: bool,
    /// The deferred background pass writes the background (where the opaque pass does not
    /// run): none where a material's resolve writes it (`Renderer::resolves_write_background`).
    pub background_pass: bool,
    /// The resolve has candidates to settle: the candidate pass runs before it.
    pub candidates: bool,
    /// The polygon pass finds the visibility of the draws listed for it, which the visibility
    /// pass then leaves out: only where no pass after it tests against the depth attachment
    /// (the polygon pass does not write it) or draws in the opaque phase.
    pub polygons: bool,
    /// The prepass (where it runs) rasterizes: on the deferred path, it has draws the polygon
    /// pass does not find. Without it the target's depth is not cleared until a candidate
    /// pass clears it (nothing else reads it on such a frame: see `polygons`).
    pub visibility_raster: bool,
    /// The transparent phase runs.
    pub transparent: bool,
    /// Textures derived from images are built this frame.
    pub derived_textures: bool,
}

impl FramePlan {
    /// The plan of this frame; `(nodes_read_depth, nodes_sample_depth)`: a feature node that
    /// runs reads the target's depth, samples the scene's depth only through
    /// [`FrameView::scene_depth`].
    fn new(
        resources: &Resources,
        (nodes_read_depth, nodes_sample_depth): (bool, bool),
    ) -> Result<Self, AppError> {
        let extracted = resources.require::<ExtractedFrame>()?;
        let renderer = resources.require::<Renderer>()?;
        let has_camera = extracted.has_camera;
        let phases = resources.get::<RenderPhases>();
        let has =
            |phase: DrawPhase| has_camera && phases.is_some_and(|p| p.has_draws(phase, resources));
        let prepass = renderer.depth_prepass
            && (has(DrawPhase::Prepass)
                || (has_camera
                    && phases.is_some_and(|p| p.sorted_draw_count(DrawPhase::Prepass) > 0)));
        let resolve = renderer.deferred
            && prepass
            && has_camera
            && phases.is_some_and(|p| p.has_resolves(resources));
        let background_in_compute = resolve && !has(DrawPhase::Opaque);
        let transparent =
            has(DrawPhase::Transparent) || (has_camera && !renderer.transparent.is_empty());
        let candidates = resolve && !renderer.candidate_order.is_empty();
        let polygons = renderer.polygon_pass
            && background_in_compute
            && !(transparent || nodes_read_depth)
            && !(renderer.polygons.is_empty() && renderer.candidate_polygons.is_empty());
        let visibility_raster =
            !polygons || has(DrawPhase::Prepass) || !renderer.prepass_order.all_polygons();
        let background_pass = background_in_compute && !renderer.resolves_write_background;
        let settled_depth = match (candidates, transparent || nodes_read_depth) {
            (true, true) => SettledDepth::DepthPass,
            (_, false) if (candidates || polygons) && nodes_sample_depth => SettledDepth::Image,
            _ => SettledDepth::Unsettled,
        };
        Ok(Self {
            has_camera,
            deferred: renderer.deferred,
            prepass,
            opaque_pass: !background_in_compute,
            keep_depth: transparent || nodes_read_depth || nodes_sample_depth,
            settled_depth,
            resolve,
            background_pass,
            candidates,
            polygons,
            visibility_raster,
            transparent,
            derived_textures: !renderer.assets.pending_derived_builds().is_empty(),
        })
    }

    /// Tells `renderer` what the frame runs and prepares the core's passes that depend on it:
    /// the settled depth image, the polygon pass.
    fn prepare(&self, resources: &Resources, renderer: &mut Renderer) -> Result<(), AppError> {
        renderer.ran_opaque_pass = self.opaque_pass;
        renderer.settled_depth = self.settled_depth;
        renderer.ran_polygon_pass = self.polygons;
        renderer.ran_depth_prepass = self.prepass && self.visibility_raster;
        renderer.ran_background_pass = self.background_pass;
        let gpu = resources.require::<GpuContext>()?;
        if let (SettledDepth::Image, Some(visibility)) =
            (self.settled_depth, &mut renderer.visibility)
        {
            visibility.prepare_settled_depth(gpu, resources.require::<RenderTarget>()?);
        }
        if let (true, Some(visibility)) = (self.polygons, &renderer.visibility) {
            let frame = &resources.require::<ExtractedFrame>()?.frame;
            let keys = &visibility.keys;
            renderer.polygons.prepare(gpu, frame, keys, None);
            let compiled = renderer.polygons.pipeline();
            renderer
                .candidate_polygons
                .prepare(gpu, frame, keys, compiled);
        }
        Ok(())
    }
}

/// The timestamps each phase and node writes, reserved before recording (the timer is
/// borrowed mutably).
struct PhaseTimes {
    prepass: Option<PassTimestamps>,
    opaque: Option<PassTimestamps>,
    resolve: Option<PassTimestamps>,
    transparent: Option<PassTimestamps>,
    /// Each node's, in the nodes' order (`None` for those that do not run).
    nodes: Vec<Option<PassTimestamps>>,
    derived: Option<PassTimestamps>,
}

impl PhaseTimes {
    fn reserve(
        plan: &FramePlan,
        nodes: &FrameNodes,
        runs: &[bool],
        resources: &mut Resources,
    ) -> Self {
        let mut time = |run: bool, name: &str| run.then(|| time_pass(resources, name)).flatten();
        let prepass = time(plan.prepass, RenderPhase::Prepass.name());
        let opaque = time(plan.opaque_pass, RenderPhase::Opaque.name());
        let resolve = time(plan.resolve, RenderPhase::Resolve.name());
        let transparent = time(plan.transparent, RenderPhase::Transparent.name());
        let nodes = nodes
            .iter()
            .zip(runs)
            .map(|(node, runs)| time(*runs, node.place.name))
            .collect();
        Self {
            prepass,
            opaque,
            resolve,
            transparent,
            nodes,
            // Reserved last: where a frame times more passes than the timer holds, the phases
            // keep theirs.
            derived: time(plan.derived_textures, DERIVED_TEXTURES_PASS),
        }
    }
}
