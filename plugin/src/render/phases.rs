//! The phases of a frame, in the one order they run, and the work plugins add to them.
//!
//! ```text
//! prepass      depth of opaque geometry (forward: depth-offset materials write their
//!              displaced depth)
//! shadows      a depth pass per shadow map (cascade, spot map, cube face) into which every
//!              material draws its casters from the light's view
//! opaque       materials test the prepass depth without writing it: a pixel shades once
//! resolve      deferred path: the candidate pass (depth-offset polygons, by their polygons'
//!              depth), then materials shade their pixels of the visibility buffer in compute
//!              (the resolves that settle candidates first), then the settled depth (an image
//!              in the same compute pass, or the candidates' polygons for passes that test it)
//! transparent  blended draws of every material in one list, farthest first; depth read-only;
//!              then TAA's object motion pass (moving draws write which motion each pixel
//!              follows)
//! post         the post chain: HDR effects (TAA), tonemapping from the HDR scene to the
//!              display image (compute where allowed; the scene is pre-exposed: the lights
//!              carry the camera's exposure), display effects (FXAA where the camera asks)
//! overlay      UI drawn over the result by the application (the sandbox's egui)
//! ```
//! Each phase that has work is timed in [`crate::gpu::GpuTimings`] under [`RenderPhase::name`].

use std::any::TypeId;

use crate::Resources;

/// One phase of a frame. `ALL` lists them in the order they run.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
#[non_exhaustive]
pub enum RenderPhase {
    /// Depth of opaque geometry, so the opaque phase shades only visible pixels.
    Prepass,
    /// Shadow maps per light.
    Shadows,
    /// Opaque materials, into the HDR scene target.
    Opaque,
    /// The deferred path's compute resolve: materials shade the pixels the visibility pass
    /// gave them (see [`super::RenderPath`]).
    Resolve,
    /// Blended draws of every material in one list, farthest first.
    Transparent,
    /// The post chain: HDR effects (TAA), tonemapping into the display image, display effects
    /// (the post filter).
    PostProcess,
    /// The application's UI over the finished image.
    Overlay,
}

impl RenderPhase {
    /// Every phase, in the order a frame runs them.
    pub const ALL: [RenderPhase; 7] = [
        RenderPhase::Prepass,
        RenderPhase::Shadows,
        RenderPhase::Opaque,
        RenderPhase::Resolve,
        RenderPhase::Transparent,
        RenderPhase::PostProcess,
        RenderPhase::Overlay,
    ];

    /// The name the phase is timed under in [`crate::gpu::GpuTimings`].
    pub const fn name(self) -> &'static str {
        match self {
            RenderPhase::Prepass => "prepass",
            RenderPhase::Shadows => "shadows",
            RenderPhase::Opaque => "opaque",
            RenderPhase::Resolve => "resolve",
            RenderPhase::Transparent => "transparent",
            RenderPhase::PostProcess => "post",
            RenderPhase::Overlay => "overlay",
        }
    }
}

/// The phases that are one render pass the core opens, into which plugins record draws.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum DrawPhase {
    /// Depth only (plus the visibility id on the deferred path); skipped when
    /// [`super::RenderPlugin::depth_prepass`] is off.
    Prepass,
    /// Colour into the HDR scene target; depth tested (and written only without a prepass).
    Opaque,
    /// Deferred frames, after the opaque phase: the polygons of draws whose visible depth lies
    /// behind them (parallax depth offset) merge into the candidate keys, depth tested against
    /// the visibility pass and written; the resolve settles them.
    Candidates,
    /// Deferred frames, after the resolve, where a later pass tests against the depth: the
    /// candidates' polygons write each pixel's settled depth.
    SettledDepth,
    /// Colour blended over the opaque result; depth tested, never written.
    Transparent,
    /// TAA frames in which a draw moved, after the transparent phase: each moving draw writes
    /// its motion's number where it shows; depth tested, never written.
    Motion,
}

impl From<DrawPhase> for RenderPhase {
    fn from(phase: DrawPhase) -> Self {
        match phase {
            DrawPhase::Prepass => RenderPhase::Prepass,
            DrawPhase::Opaque => RenderPhase::Opaque,
            DrawPhase::Candidates | DrawPhase::SettledDepth => RenderPhase::Resolve,
            DrawPhase::Transparent => RenderPhase::Transparent,
            DrawPhase::Motion => RenderPhase::Transparent,
        }
    }
}

/// The format of the [`DrawPhase::Motion`] pass's colour target: 0 for a pixel no moving draw
/// shows, else its motion's number (its index in the frame's list of moving draws, plus one).
pub const MOTION_ID_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::R32Uint;

/// Records draws into a phase's open render pass, given the resources.
pub type PhaseDraw = fn(&Resources, &mut wgpu::RenderPass<'_>);

/// Records some of its owner's draws into a phase's open render pass, given the resources and
/// the draws' numbers (as the owner gave them to the frame's sorted list of the phase), in the
/// order to draw them.
pub type SortedDraw = fn(&Resources, &mut wgpu::RenderPass<'_>, &[u32]);

/// Records shadow casters into one shadow map's open render pass, given the resources and
/// the frame-uniform slot that holds the map's view (bind it with
/// the frame uniform buffer's `offset`).
pub type ShadowDraw = fn(&Resources, &mut wgpu::RenderPass<'_>, u32);

/// Records the dispatches of the deferred resolve into its open compute pass, given the
/// resources.
pub type ResolveDispatch = fn(&Resources, &mut wgpu::ComputePass<'_>);

/// Records whole passes of its own into the frame's encoder.
pub type PhaseWork = fn(&Resources, &mut wgpu::CommandEncoder);

/// Whether a registered draw has anything to draw this frame (a phase none of whose draws has
/// is skipped, pass and timing included).
pub type HasDraws = fn(&Resources) -> bool;

/// The work of every phase, in the order plugins added it; one entry per owner type and phase,
/// so a plugin added twice draws once. A resource.
#[derive(Debug, Default)]
pub struct RenderPhases {
    draws: Vec<(DrawPhase, TypeId, PhaseDraw, HasDraws)>,
    sorted_draws: Vec<(DrawPhase, TypeId, SortedDraw)>,
    shadow_draws: Vec<(TypeId, ShadowDraw)>,
    resolves: Vec<(TypeId, ResolveDispatch, HasDraws)>,
    settling_resolves: Vec<(TypeId, ResolveDispatch)>,
    work: Vec<(RenderPhase, TypeId, PhaseWork)>,
    /// Each declared owner's name and whether its prepass draws write visibility keys (the
    /// deferred path needs every owner's to).
    owners: Vec<(TypeId, &'static str, bool)>,
}

impl RenderPhases {
    /// Declares `Owner` (a material type, say) by `name`, and whether its prepass draws also
    /// write the deferred path's visibility keys; a later call replaces the earlier.
    pub fn declare_owner<Owner: 'static>(&mut self, name: &'static str, writes_visibility: bool) {
        let owner = TypeId::of::<Owner>();
        match self.owners.iter_mut().find(|(id, _, _)| *id == owner) {
            Some(entry) => *entry = (owner, name, writes_visibility),
            None => self.owners.push((owner, name, writes_visibility)),
        }
    }

    /// The first declared owner whose draws cannot take part in the deferred path.
    pub(crate) fn owner_without_visibility(&self) -> Option<&'static str> {
        self.owners
            .iter()
            .find(|(_, _, writes)| !writes)
            .map(|(_, name, _)| *name)
    }

    /// Whether `owner` is declared and its prepass draws write visibility keys.
    pub(crate) fn writes_visibility(&self, owner: TypeId) -> bool {
        self.owners
            .iter()
            .any(|(id, _, writes)| *id == owner && *writes)
    }

    /// Adds `draw` to `phase` for `Owner` (a material type, say) unless `Owner` has one there.
    pub fn add_draw<Owner: 'static>(&mut self, phase: DrawPhase, draw: PhaseDraw) {
        self.add_draw_when::<Owner>(phase, draw, |_| true);
    }

    /// Like [`RenderPhases::add_draw`], for a draw that has work only in some frames, as
    /// `has_draws` tells.
    pub fn add_draw_when<Owner: 'static>(
        &mut self,
        phase: DrawPhase,
        draw: PhaseDraw,
        has_draws: HasDraws,
    ) {
        let entry = (phase, TypeId::of::<Owner>(), draw, has_draws);
        push_once(&mut self.draws, entry, |(p, id, _, _)| (*p, *id));
    }

    /// Adds `draw` as `Owner`'s drawer of its draws in `phase`'s sorted list unless `Owner` has
    /// one there: the frame sorts every owner's draws of the phase in one list (the transparent
    /// phase farthest first, the prepass and the candidates nearest first) and calls `draw` for
    /// each run of `Owner`'s, before the phase's [`RenderPhases::add_draw`] draws. The opaque
    /// phase draws after a prepass and keeps no sorted list.
    pub fn add_sorted<Owner: 'static>(&mut self, phase: DrawPhase, draw: SortedDraw) {
        let entry = (phase, TypeId::of::<Owner>(), draw);
        push_once(&mut self.sorted_draws, entry, |(p, id, _)| (*p, *id));
    }

    /// The drawer of `owner`'s sorted draws in `phase`, if it has one.
    pub(crate) fn sorted_draw(&self, phase: DrawPhase, owner: TypeId) -> Option<SortedDraw> {
        self.sorted_draws
            .iter()
            .find(|(p, id, _)| *p == phase && *id == owner)
            .map(|(_, _, draw)| *draw)
    }

    /// How many owners draw into `phase`'s sorted list.
    pub fn sorted_draw_count(&self, phase: DrawPhase) -> usize {
        self.sorted_draws
            .iter()
            .filter(|(p, _, _)| *p == phase)
            .count()
    }

    /// Adds `draw` to every shadow map of the shadows phase for `Owner` unless `Owner` has one:
    /// the core opens one pass per map (a cascade, a spot's map, a cube face) and calls it.
    pub fn add_shadow_draw<Owner: 'static>(&mut self, draw: ShadowDraw) {
        push_once(
            &mut self.shadow_draws,
            (TypeId::of::<Owner>(), draw),
            |(id, _)| *id,
        );
    }

    /// Adds `dispatch` to the deferred resolve for `Owner` unless `Owner` has one: the core
    /// opens one compute pass (on deferred frames where some `has_work` says so) and calls it.
    pub fn add_resolve<Owner: 'static>(&mut self, dispatch: ResolveDispatch, has_work: HasDraws) {
        let entry = (TypeId::of::<Owner>(), dispatch, has_work);
        push_once(&mut self.resolves, entry, |(id, _, _)| *id);
    }

    /// Adds `dispatch` to the first round of the deferred resolve for `Owner` unless `Owner`
    /// has one there: every owner's first round runs before any [`RenderPhases::add_resolve`]
    /// dispatch, so the candidates it settles (`settle_candidate`) are settled before the
    /// other resolves read which pixels they shade. An owner classifies its tiles here.
    pub fn add_settling_resolve<Owner: 'static>(&mut self, dispatch: ResolveDispatch) {
        let entry = (TypeId::of::<Owner>(), dispatch);
        push_once(&mut self.settling_resolves, entry, |(id, _)| *id);
    }

    /// The deferred resolve's dispatches in the order they run: every first round (the
    /// settling resolves), then the others, each in the order they were added.
    pub fn resolves(&self) -> impl Iterator<Item = ResolveDispatch> + '_ {
        let settling = self.settling_resolves.iter().map(|(_, dispatch)| *dispatch);
        settling.chain(self.resolves.iter().map(|(_, dispatch, _)| *dispatch))
    }

    /// Whether any deferred resolve has pixels to shade this frame.
    pub fn has_resolves(&self, resources: &Resources) -> bool {
        self.resolves
            .iter()
            .any(|(_, _, has_work)| has_work(resources))
    }

    /// The shadow-map draws, in the order they were added.
    pub fn shadow_draws(&self) -> impl Iterator<Item = ShadowDraw> + '_ {
        self.shadow_draws.iter().map(|(_, draw)| *draw)
    }

    /// Adds encoder `work` to `phase` for `Owner` unless `Owner` has some there; it runs after
    /// the phase's own pass (shadow maps: before the opaque phase).
    pub fn add_work<Owner: 'static>(&mut self, phase: RenderPhase, work: PhaseWork) {
        let entry = (phase, TypeId::of::<Owner>(), work);
        push_once(&mut self.work, entry, |(p, id, _)| (*p, *id));
    }

    /// The draws of `phase`, in the order they were added.
    pub fn draws(&self, phase: DrawPhase) -> impl Iterator<Item = PhaseDraw> + '_ {
        self.draws
            .iter()
            .filter(move |(p, _, _, _)| *p == phase)
            .map(|(_, _, draw, _)| *draw)
    }

    /// The owners (a material type, say) of the draws of `phase`, sorted or not.
    pub(crate) fn draw_owners(&self, phase: DrawPhase) -> impl Iterator<Item = TypeId> + '_ {
        let draws = self.draws.iter().filter(move |(p, _, _, _)| *p == phase);
        let sorted = self
            .sorted_draws
            .iter()
            .filter(move |(p, _, _)| *p == phase);
        draws
            .map(|(_, owner, _, _)| *owner)
            .chain(sorted.map(|(_, owner, _)| *owner))
    }

    /// Whether any draw of `phase` has work this frame.
    pub fn has_draws(&self, phase: DrawPhase, resources: &Resources) -> bool {
        self.draws
            .iter()
            .any(|(p, _, _, has_draws)| *p == phase && has_draws(resources))
    }

    /// The encoder work of `phase`, in the order it was added.
    pub fn work(&self, phase: RenderPhase) -> impl Iterator<Item = PhaseWork> + '_ {
        self.work
            .iter()
            .filter(move |(p, _, _)| *p == phase)
            .map(|(_, _, work)| *work)
    }

    /// How many draws `phase` has.
    pub fn draw_count(&self, phase: DrawPhase) -> usize {
        self.draws(phase).count()
    }
}

/// Appends `entry` unless `list` holds one with the same `key` (an owner, or an owner and a
/// phase): a plugin added twice adds its work once.
fn push_once<T, K: PartialEq>(list: &mut Vec<T>, entry: T, key: impl Fn(&T) -> K) {
    if !list.iter().any(|held| key(held) == key(&entry)) {
        list.push(entry);
    }
}
