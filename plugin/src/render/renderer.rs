//! [`Renderer`]: the renderer's GPU state between frames (uploaded assets, the frame uniform,
//! shadow maps, the deferred path's buffers, the post chain's images), the choice of path, and what a
//! material's group 0 binds of it ([`PhaseBindings`]).

use super::post_chain::PostImages;
use super::{
    DeferredBackground, DeferredUnavailable, EnvironmentMaps, FrameUniformBuffer, FullScreenStage,
    LightBuffers, RenderPath, RenderTarget, SettledDepth, ShadowMaps, SortedDraws,
    VisibilityBuffer, VisibilityIds, VisiblePolygons, render_path,
};
use crate::gpu::{GpuAssets, GpuContext, UploadStats};
use crate::{Image, Mesh};

/// The renderer's GPU state: uploaded assets, the frame uniform, the post chain's images. A
/// resource.
#[derive(Debug)]
pub struct Renderer {
    /// GPU copies of meshes and images.
    pub(crate) assets: GpuAssets,
    /// Camera and lights, shared by every material pipeline.
    pub(crate) frame: FrameUniformBuffer,
    /// Whether frames run the depth prepass.
    pub(crate) depth_prepass: bool,
    /// A 1 × 1 depth texture bound where the real one is being written.
    pub(crate) dummy_depth: wgpu::TextureView,
    /// A one-key visibility buffer bound where the real one is not written.
    pub(crate) dummy_visibility: wgpu::Buffer,
    /// Every light's shadow maps.
    pub(crate) shadow_maps: ShadowMaps,
    /// The environment light's maps.
    pub(crate) environment: EnvironmentMaps,
    /// The point lights and their clusters.
    pub(crate) lights: LightBuffers,
    /// The path asked for.
    pub(super) path: RenderPath,
    /// Whether this frame runs deferred (decided in the Prepare stage).
    pub(crate) deferred: bool,
    /// Whether the last rendered frame ran the opaque render pass (a deferred frame whose
    /// opaque draws all resolve in compute does not).
    pub(crate) ran_opaque_pass: bool,
    /// How the last frame gave the depth its resolve settled to the passes after it.
    pub(crate) settled_depth: SettledDepth,
    /// Why the last frame that asked for deferred ran forward, as logged.
    pub(super) deferred_unavailable: Option<DeferredUnavailable>,
    /// The deferred path's visibility buffer, once a frame has needed it.
    pub(crate) visibility: Option<VisibilityBuffer>,
    /// The deferred path's background pass, once a frame has needed it.
    pub(super) background: Option<DeferredBackground>,
    /// This frame's visibility ids, handed to the materials' batches as they prepare.
    pub(crate) visibility_ids: VisibilityIds,
    /// This frame's prepass draws of every material, drawn nearest first.
    pub(crate) prepass_order: SortedDraws,
    /// This frame's draws whose visibility the polygon pass may find instead of the
    /// visibility pass.
    pub(crate) polygons: VisiblePolygons,
    /// This frame's depth-offset draws whose candidate keys the polygon pass may find instead
    /// of the candidate pass.
    pub(crate) candidate_polygons: VisiblePolygons,
    /// Whether deferred frames may run the polygon pass.
    pub(crate) polygon_pass: bool,
    /// Whether the last rendered frame ran the polygon pass.
    pub(crate) ran_polygon_pass: bool,
    /// Whether the last rendered frame's depth prepass (the visibility pass) rasterized.
    pub(crate) ran_depth_prepass: bool,
    /// Whether a material's resolve writes this frame's background (its tile classification,
    /// or a dispatch over the whole target, where neither key holds a draw; a settling resolve
    /// where its candidate loses over no draw), as the materials prepare.
    pub(crate) resolves_write_background: bool,
    /// Whether the last rendered frame ran the deferred background pass.
    pub(crate) ran_background_pass: bool,
    /// This frame's candidate draws of every material, drawn nearest first.
    pub(crate) candidate_order: SortedDraws,
    /// This frame's blended draws of every material, drawn farthest first.
    pub(crate) transparent: SortedDraws,
    /// No frame has chosen its path yet (the first choice is always logged).
    pub(super) first_frame: bool,
    /// Where full-screen passes run on this adapter (post effects follow it).
    pub(super) full_screen_stage: FullScreenStage,
    /// The images between the post chain's effects.
    pub(super) post_images: PostImages,
    /// What the last Prepare stage uploaded (the core's frame data and every material's).
    pub last_upload: UploadStats,
}

impl Renderer {
    /// Whether frames run the depth prepass.
    pub fn depth_prepass(&self) -> bool {
        self.depth_prepass
    }

    /// Whether post-processing runs as a compute pass (else as a full-screen triangle).
    pub fn post_process_is_compute(&self) -> bool {
        self.full_screen_stage == FullScreenStage::Compute
    }

    /// Where full-screen passes run on this adapter: compute where it can write the display
    /// format from compute (and the render plugin allows it), else a full-screen triangle.
    pub fn full_screen_stage(&self) -> FullScreenStage {
        self.full_screen_stage
    }

    /// The path asked for (see [`Renderer::runs_deferred`] for the one that runs).
    pub fn path(&self) -> RenderPath {
        self.path
    }

    /// Asks for `path` from the next frame on (the choice is logged).
    pub fn set_path(&mut self, path: RenderPath) {
        self.path = path;
    }

    /// Whether the last prepared frame ran the deferred path.
    pub fn runs_deferred(&self) -> bool {
        self.deferred
    }

    /// Whether the last rendered frame ran the opaque render pass: a deferred frame whose
    /// opaque draws all shade in the compute resolve runs none (its GPU timings then have no
    /// "opaque" phase).
    pub fn ran_opaque_pass(&self) -> bool {
        self.ran_opaque_pass
    }

    /// How the last frame gave the depth its deferred resolve settled (depth offset) to the
    /// passes after it.
    pub fn settled_depth(&self) -> SettledDepth {
        self.settled_depth
    }

    /// Whether deferred frames may find the visibility of large few-triangle draws in compute
    /// ([`super::RenderPlugin::polygon_pass`]).
    pub fn polygon_pass(&self) -> bool {
        self.polygon_pass
    }

    /// Turns the polygon pass on or off from the next frame on.
    pub fn set_polygon_pass(&mut self, on: bool) {
        self.polygon_pass = on;
    }

    /// Whether the last rendered frame found the visibility of its large few-triangle draws
    /// in compute (the polygon pass) rather than rasterizing them.
    pub fn ran_polygon_pass(&self) -> bool {
        self.ran_polygon_pass
    }

    /// Whether the last rendered frame ran a depth prepass render pass (on the deferred path
    /// the visibility pass): none where the polygon pass found every draw (nor any cleared
    /// depth: nothing after reads it on such a frame).
    pub fn ran_depth_prepass(&self) -> bool {
        self.ran_depth_prepass
    }

    /// Whether the last rendered frame wrote the deferred background (the clear colour where no
    /// draw shows) in a compute pass of its own: none where a material's resolve wrote it.
    pub fn ran_background_pass(&self) -> bool {
        self.ran_background_pass
    }

    /// The scene's depth as shaders read it this frame ([`super::FrameView::scene_depth`]).
    pub(crate) fn scene_depth<'a>(&'a self, target: &'a RenderTarget) -> &'a wgpu::TextureView {
        let settled = self
            .visibility
            .as_ref()
            .filter(|_| self.settled_depth == SettledDepth::Image)
            .and_then(VisibilityBuffer::settled_depth_view);
        settled.unwrap_or(&target.depth_view)
    }

    /// Why the last frame runs forward although its path asked for deferred, if it does.
    pub fn deferred_unavailable(&self) -> Option<DeferredUnavailable> {
        self.deferred_unavailable
    }

    /// Decides whether this frame runs deferred, logging when the decision changes, and makes
    /// the visibility buffer on the first deferred frame of a target.
    /// `blocker` is what of the app stops the deferred path (a material, a draw, a counter).
    pub(super) fn choose_path(
        &mut self,
        gpu: &GpuContext,
        target: &RenderTarget,
        blocker: Option<DeferredUnavailable>,
    ) {
        let wants = match self.path {
            RenderPath::Forward => false,
            RenderPath::Deferred => true,
            RenderPath::Auto => render_path::auto_picks_deferred(gpu),
        };
        let unavailable = if wants {
            render_path::deferred_support(gpu, self.depth_prepass, target)
                .and_then(|()| blocker.map_or(Ok(()), Err))
                .err()
        } else {
            None
        };
        let deferred = wants && unavailable.is_none();
        if (deferred, unavailable) != (self.deferred, self.deferred_unavailable) || self.first_frame
        {
            match unavailable {
                Some(reason) => {
                    log::warn!("render path {}: runs forward, since {reason}", self.path)
                }
                None => log::info!(
                    "render path {}: runs {}",
                    self.path,
                    if deferred { "deferred" } else { "forward" }
                ),
            }
        }
        self.first_frame = false;
        self.deferred = deferred;
        self.deferred_unavailable = unavailable;
        if deferred {
            match &mut self.visibility {
                Some(visibility) => visibility.follow(gpu, target),
                None => self.visibility = Some(VisibilityBuffer::new(gpu, target)),
            }
        }
        if deferred && self.background.is_none() {
            self.background = Some(DeferredBackground::new(gpu, target.scene_format()));
        }
    }
}

/// What materials bind as the prepass depth, shadow maps and visibility keys for `target`: its
/// depth after a prepass, else the dummy; the target's visibility buffer once made, else a
/// stand-in (fields apart, so the renderer's assets stay borrowable).
pub(crate) fn phase_bindings<'a>(
    depth_prepass: bool,
    dummy: &'a wgpu::TextureView,
    (shadow_maps, environment, lights): (&'a ShadowMaps, &'a EnvironmentMaps, &'a LightBuffers),
    (visibility, dummy_visibility): (Option<&'a VisibilityBuffer>, &'a wgpu::Buffer),
    target: &'a RenderTarget,
) -> PhaseBindings<'a> {
    let visibility = visibility.filter(|visibility| visibility.target == target.id());
    PhaseBindings {
        visibility: visibility.map_or(dummy_visibility, |visibility| &visibility.keys),
        dummy_visibility,
        opaque: if depth_prepass {
            &target.depth_view
        } else {
            dummy
        },
        dummy,
        shadow_maps: shadow_maps.array_view(),
        dummy_shadow_maps: shadow_maps.dummy_view(),
        shadow_views: shadow_maps.views_buffer(),
        shadow_sampler: shadow_maps.sampler(),
        environment,
        lights,
        bound: BoundResources {
            target: target.id(),
            shadow_maps: shadow_maps.generation(),
            environment: environment.generation(),
            lights: lights.generation(),
            has_visibility_buffer: visibility.is_some(),
        },
    }
}

impl Renderer {
    /// The texture an image was uploaded to, for reading it back ([`read_rgba8`](crate::gpu::read_rgba8)); `None`
    /// until the Prepare stage has uploaded it.
    pub fn gpu_texture(&self, image: crate::AssetId<Image>) -> Option<&wgpu::Texture> {
        self.assets.image(image).map(|image| &image.texture)
    }

    /// Whether a mesh is uploaded and valid (an invalid mesh is logged once and not drawn).
    pub fn has_gpu_mesh(&self, mesh: crate::AssetId<Mesh>) -> bool {
        self.assets.mesh(mesh).is_some()
    }

    /// How many textures derived from images (maximum pyramids) the GPU holds: one per image
    /// and derivation some draw used in the last frame.
    pub fn derived_texture_count(&self) -> usize {
        self.assets.derived_count()
    }
}

/// What a material's group 0 binds that changes from phase to phase: the prepass depth (binding 3) and the shadow
/// maps (bindings 5 to 7) in the phases that shade, dummies wherever they are being written
/// (the prepass and the shadow maps themselves); and the visibility keys (binding 8) the other
/// way round: the real ones in the prepass, which writes them, a stand-in elsewhere (the
/// deferred resolve reads them through a binding of its own).
pub(crate) struct PhaseBindings<'a> {
    /// What the opaque phase binds (the target's depth after a prepass, else the dummy).
    pub(crate) opaque: &'a wgpu::TextureView,
    /// The 1 × 1 dummy.
    pub(crate) dummy: &'a wgpu::TextureView,
    /// Every shadow map, for receivers.
    pub(crate) shadow_maps: &'a wgpu::TextureView,
    /// Their 1 × 1 × 1 stand-in.
    pub(crate) dummy_shadow_maps: &'a wgpu::TextureView,
    /// What receivers read of each map.
    pub(crate) shadow_views: &'a wgpu::Buffer,
    /// The shadow maps' comparison sampler.
    pub(crate) shadow_sampler: &'a wgpu::Sampler,
    /// The environment light's maps.
    pub(crate) environment: &'a EnvironmentMaps,
    /// The point lights and their clusters.
    pub(crate) lights: &'a LightBuffers,
    /// The visibility keys the deferred path's prepass merges into (or the stand-in).
    pub(crate) visibility: &'a wgpu::Buffer,
    /// The one-key stand-in, bound where the keys are not written.
    pub(crate) dummy_visibility: &'a wgpu::Buffer,
    /// What the views belong to: bind groups follow when it changes.
    pub(crate) bound: BoundResources,
}

/// What a material's frame bind groups were made for; a new one is made when it changes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct BoundResources {
    /// The target ([`crate::render::RenderTarget::id`]).
    pub(crate) target: u64,
    /// The shadow-map texture's generation.
    pub(crate) shadow_maps: u64,
    /// The environment maps' generation.
    pub(crate) environment: u64,
    /// The light buffers' generation.
    pub(crate) lights: u64,
    /// Whether the target's visibility buffer exists.
    pub(crate) has_visibility_buffer: bool,
}
