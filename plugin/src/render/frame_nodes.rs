//! The frame as a list that features join: [`FrameNodes`] holds every render feature's work
//! as named nodes of a [`RenderPhase`], each placed before or after other nodes of its phase.
//! The core runs its own passes (prepass, opaque, resolve, transparent) and, after each phase's
//! pass, that phase's nodes in order; the post phase's effects form the post chain
//! (post_chain.rs), after which the post and overlay phases' other nodes record, in the same
//! submission. A node that has nothing to do in a frame says so and costs nothing: no
//! pass, no bind group, no timing.

use super::{PostEffect, RenderError, RenderPhase, RenderTarget};
use crate::Resources;
use crate::gpu::{GpuContext, PassTimestamps};

/// What a node reads of the frame it records into.
#[derive(Clone, Copy)]
pub struct FrameView<'a> {
    /// Every resource of the app (the renderer's, the features', the materials').
    pub resources: &'a Resources,
    /// The device and queue.
    pub gpu: &'a GpuContext,
    /// The target the frame renders into.
    pub target: &'a RenderTarget,
    /// Whether a camera sees the frame (without one, nothing is drawn).
    pub has_camera: bool,
    /// The scene's depth as shaders after the resolve phase sample it (bound as an unfilterable
    /// float texture; [`FrameNode::samples_scene_depth`]): the target's depth, or the image a
    /// deferred resolve settled its depth-offset candidates into
    /// ([`crate::render::SettledDepth::Image`]).
    pub scene_depth: &'a wgpu::TextureView,
}

impl<'a> FrameView<'a> {
    /// The frame as `resources` hold it: what an effect's `prepare` makes its GPU objects and
    /// uploads with (an error names a missing resource).
    pub fn of(resources: &'a Resources) -> Result<Self, RenderError> {
        let target = resources.require::<RenderTarget>()?;
        Ok(Self {
            resources,
            gpu: resources.require::<GpuContext>()?,
            target,
            has_camera: resources
                .require::<crate::render::ExtractedFrame>()?
                .has_camera,
            scene_depth: resources
                .require::<crate::render::Renderer>()?
                .scene_depth(target),
        })
    }
}

/// A feature's work in a phase of the frame, recorded into the frame's encoder after the
/// phase's own pass.
pub trait FrameNode: 'static {
    /// Makes what this frame's recording needs (after every material has prepared its draws
    /// and the core has planned the frame's passes); returns the bytes it uploaded. Runs only in
    /// frames where [`FrameNode::runs`] is true.
    fn prepare(&mut self, _resources: &mut Resources) -> Result<u64, RenderError> {
        Ok(0)
    }

    /// Whether the node has work this frame; when false it records nothing and is not timed.
    fn runs(&self, frame: FrameView<'_>) -> bool;

    /// Whether the node reads the target's depth ([`RenderTarget::depth_view`], as its depth
    /// attachment or in a shader) after the opaque phase: the core then keeps it, with the depth
    /// a deferred resolve settled drawn into it.
    fn reads_scene_depth(&self) -> bool {
        false
    }

    /// Whether the node reads the scene's depth after the resolve phase only by sampling
    /// [`FrameView::scene_depth`] in a shader: where a deferred resolve settled depth-offset
    /// candidates, the core may then hand it an image written in compute instead of drawing the
    /// settled depth into the target's depth, which costs a raster pass.
    fn samples_scene_depth(&self) -> bool {
        false
    }

    /// Records the node's passes; `time` spans them (the node's first pass begins it, its last
    /// ends it).
    fn record(
        &mut self,
        frame: FrameView<'_>,
        encoder: &mut wgpu::CommandEncoder,
        time: Option<&PassTimestamps>,
    ) -> Result<(), RenderError>;
}

/// Where a node sits: its name (also its timing name in [`crate::gpu::GpuTimings`]), its phase, and
/// the nodes of that phase it runs after and before.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct NodePlace {
    /// The node's name, unique in the frame; its passes are timed under it.
    pub name: &'static str,
    /// The phase it runs in.
    pub phase: RenderPhase,
    /// Nodes of the same phase that must run first.
    pub after: Vec<&'static str>,
    /// Nodes of the same phase that must run later.
    pub before: Vec<&'static str>,
}

impl NodePlace {
    /// A node named `name` in `phase`, unordered against the others (they run in the order
    /// they were added).
    pub fn new(name: &'static str, phase: RenderPhase) -> Self {
        Self {
            name,
            phase,
            after: Vec::new(),
            before: Vec::new(),
        }
    }

    /// The same place, after the node named `other`.
    pub fn after(mut self, other: &'static str) -> Self {
        self.after.push(other);
        self
    }

    /// The same place, before the node named `other`.
    pub fn before(mut self, other: &'static str) -> Self {
        self.before.push(other);
        self
    }
}

/// Why the frame's nodes cannot be put in order.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum NodeOrderError {
    /// A node is placed against a node its phase does not have.
    #[error(
        "frame node {node:?} is placed against {other:?}, which its phase {phase:?} has no node of"
    )]
    UnknownNode {
        /// The node placed.
        node: &'static str,
        /// The name it refers to.
        other: &'static str,
        /// Its phase.
        phase: RenderPhase,
    },
    /// The constraints of a phase's nodes form a cycle.
    #[error("the frame nodes {0:?} must each run before another: their order is a cycle")]
    Cycle(Vec<&'static str>),
}

/// What one entry of [`FrameNodes`] does.
pub(crate) enum NodeWork {
    /// Encoder work of any phase.
    Frame(Box<dyn FrameNode>),
    /// A full-screen effect of the post chain.
    Post(Box<dyn PostEffect>),
}

impl NodeWork {
    /// Whether the node has work this frame.
    pub(crate) fn runs(&self, frame: FrameView<'_>) -> bool {
        match self {
            NodeWork::Frame(node) => node.runs(frame),
            NodeWork::Post(effect) => effect.runs(frame),
        }
    }

    /// Whether the node reads the target's depth after the opaque phase.
    pub(crate) fn reads_scene_depth(&self) -> bool {
        match self {
            NodeWork::Frame(node) => node.reads_scene_depth(),
            NodeWork::Post(effect) => effect.reads_scene_depth(),
        }
    }

    /// Whether the node samples the scene's depth only through [`FrameView::scene_depth`].
    pub(crate) fn samples_scene_depth(&self) -> bool {
        match self {
            NodeWork::Frame(node) => node.samples_scene_depth(),
            NodeWork::Post(effect) => effect.samples_scene_depth(),
        }
    }

    /// The post effect, if the node is one.
    pub(crate) fn post_effect(&self) -> Option<&dyn PostEffect> {
        match self {
            NodeWork::Post(effect) => Some(effect.as_ref()),
            NodeWork::Frame(_) => None,
        }
    }
}

/// One node: where it sits, its work, and how to make its work afresh (on a new GPU device:
/// what it made on the old one is gone).
pub(crate) struct Node {
    pub(crate) place: NodePlace,
    pub(crate) work: NodeWork,
    make: Box<dyn Fn() -> NodeWork>,
    /// The type of its work, to tell a plugin added twice from two features sharing a name.
    kind: std::any::TypeId,
}

/// Every node of the frame, in order within each phase once [`FrameNodes::order`] has run. A
/// resource of the render plugin; feature plugins add to it as they build. Nodes are added as
/// functions that make them: when the GPU device is replaced (after a lost one), every node is
/// made again, so none keeps objects of the old device.
#[derive(Default)]
pub struct FrameNodes {
    nodes: Vec<Node>,
    ordered: bool,
    /// The device the nodes' work was made for (set by the first frame).
    device: Option<wgpu::Device>,
}

impl std::fmt::Debug for FrameNodes {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_list()
            .entries(self.nodes.iter().map(|node| &node.place))
            .finish()
    }
}

impl FrameNodes {
    /// Adds the node `make` makes at `place`, replacing a node of the same name (a plugin
    /// added twice adds its node once; another kind of node of that name is replaced with a
    /// warning).
    pub fn add<N: FrameNode>(&mut self, place: NodePlace, make: impl Fn() -> N + 'static) {
        let make = Box::new(move || NodeWork::Frame(Box::new(make())));
        self.insert(place, make, std::any::TypeId::of::<N>());
    }

    /// Adds the full-screen effect `make` makes to the post chain, as the node `name` of
    /// [`RenderPhase::PostProcess`] (see [`PostEffect`]).
    pub fn add_post_effect<E: PostEffect>(
        &mut self,
        name: &'static str,
        make: impl Fn() -> E + 'static,
    ) {
        self.add_post_effect_at(NodePlace::new(name, RenderPhase::PostProcess), make);
    }

    /// Like [`FrameNodes::add_post_effect`], placed against other effects of its stage.
    pub fn add_post_effect_at<E: PostEffect>(
        &mut self,
        place: NodePlace,
        make: impl Fn() -> E + 'static,
    ) {
        let place = NodePlace {
            phase: RenderPhase::PostProcess,
            ..place
        };
        let make = Box::new(move || NodeWork::Post(Box::new(make())));
        self.insert(place, make, std::any::TypeId::of::<E>());
    }

    /// Makes every node's work again when `device` is not the one it was made for.
    pub(crate) fn follow_device(&mut self, device: &wgpu::Device) {
        if self.device.as_ref() == Some(device) {
            return;
        }
        if self.device.is_some() {
            for node in &mut self.nodes {
                node.work = (node.make)();
            }
        }
        self.device = Some(device.clone());
    }

    fn insert(
        &mut self,
        place: NodePlace,
        make: Box<dyn Fn() -> NodeWork>,
        kind: std::any::TypeId,
    ) {
        self.ordered = false;
        let node = Node {
            place,
            work: make(),
            make,
            kind,
        };
        match self
            .nodes
            .iter_mut()
            .find(|old| old.place.name == node.place.name)
        {
            Some(old) => {
                if old.kind != node.kind {
                    log::warn!(
                        "frame node {:?} is replaced by another of that name: name yours apart from the renderer's nodes",
                        node.place.name
                    );
                }
                *old = node;
            }
            None => self.nodes.push(node),
        }
    }

    /// The names of the nodes in the order they run, phase by phase.
    pub fn names(&self) -> impl Iterator<Item = (RenderPhase, &'static str)> + '_ {
        self.nodes
            .iter()
            .map(|node| (node.place.phase, node.place.name))
    }

    /// Whether some node works in `phase`.
    pub fn has_phase(&self, phase: RenderPhase) -> bool {
        self.nodes.iter().any(|node| node.place.phase == phase)
    }

    /// Whether a node of that name is in the frame.
    pub fn contains(&self, name: &str) -> bool {
        self.nodes.iter().any(|node| node.place.name == name)
    }

    /// Puts the nodes in order: by phase, then as their places ask, otherwise in the order
    /// they were added. Done once after nodes change; on an error the nodes keep the order
    /// they were added in.
    pub fn order(&mut self) -> Result<(), NodeOrderError> {
        if self.ordered {
            return Ok(());
        }
        let places: Vec<&NodePlace> = self.nodes.iter().map(|node| &node.place).collect();
        let order = node_order(&places)?;
        let mut slots: Vec<Option<Node>> = self.nodes.drain(..).map(Some).collect();
        self.nodes = order.into_iter().filter_map(|i| slots[i].take()).collect();
        self.ordered = true;
        Ok(())
    }

    /// Every node, in order, to record.
    pub(crate) fn iter_mut(&mut self) -> impl Iterator<Item = &mut Node> {
        self.nodes.iter_mut()
    }

    /// Every node, in order.
    pub(crate) fn iter(&self) -> impl Iterator<Item = &Node> {
        self.nodes.iter()
    }
}

/// The indices of `places` phase by phase, each phase in an order that keeps every
/// constraint and otherwise the order of addition.
fn node_order(places: &[&NodePlace]) -> Result<Vec<usize>, NodeOrderError> {
    let mut order = Vec::with_capacity(places.len());
    for phase in RenderPhase::ALL {
        let in_phase: Vec<usize> = (0..places.len())
            .filter(|&i| places[i].phase == phase)
            .collect();
        let runs_after = predecessors(places, &in_phase)?;
        let mut placed = vec![false; in_phase.len()];
        for _ in 0..in_phase.len() {
            // The first node added whose predecessors have all been placed.
            let next = (0..in_phase.len())
                .find(|&i| !placed[i] && runs_after[i].iter().all(|&before| placed[before]));
            let Some(next) = next else {
                let cycle = (0..in_phase.len())
                    .filter(|&i| !placed[i])
                    .map(|i| places[in_phase[i]].name)
                    .collect();
                return Err(NodeOrderError::Cycle(cycle));
            };
            placed[next] = true;
            order.push(in_phase[next]);
        }
    }
    Ok(order)
}

/// For each node of a phase (`in_phase` indexes `places`), the positions in `in_phase` of the
/// nodes that must run before it.
fn predecessors(
    places: &[&NodePlace],
    in_phase: &[usize],
) -> Result<Vec<Vec<usize>>, NodeOrderError> {
    let position = |node: &NodePlace, name: &'static str| {
        in_phase
            .iter()
            .position(|&i| places[i].name == name)
            .ok_or(NodeOrderError::UnknownNode {
                node: node.name,
                other: name,
                phase: node.phase,
            })
    };
    let mut runs_after = vec![Vec::new(); in_phase.len()];
    for (at, &index) in in_phase.iter().enumerate() {
        let place = places[index];
        for &name in &place.after {
            runs_after[at].push(position(place, name)?);
        }
        for &name in &place.before {
            let later = position(place, name)?;
            runs_after[later].push(at);
        }
    }
    Ok(runs_after)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn places(list: &[NodePlace]) -> Result<Vec<&'static str>, NodeOrderError> {
        let refs: Vec<&NodePlace> = list.iter().collect();
        node_order(&refs).map(|order| order.into_iter().map(|i| list[i].name).collect())
    }

    #[test]
    fn nodes_run_by_phase_then_as_placed_then_as_added() {
        let post = RenderPhase::PostProcess;
        let order = places(&[
            NodePlace::new("fxaa", post),
            NodePlace::new("outline", post).before("fxaa"),
            NodePlace::new("shadow maps", RenderPhase::Shadows),
            NodePlace::new("grade", post).after("fxaa"),
            NodePlace::new("late", post),
        ]);
        assert_eq!(
            order,
            Ok(vec!["shadow maps", "outline", "fxaa", "grade", "late"])
        );
    }

    #[test]
    fn unknown_names_and_cycles_are_errors_naming_them() {
        let post = RenderPhase::PostProcess;
        assert_eq!(
            places(&[NodePlace::new("a", post).after("missing")]),
            Err(NodeOrderError::UnknownNode {
                node: "a",
                other: "missing",
                phase: post
            })
        );
        // A name of another phase does not place a node.
        assert!(
            places(&[
                NodePlace::new("a", post).after("b"),
                NodePlace::new("b", RenderPhase::Shadows)
            ])
            .is_err()
        );
        assert_eq!(
            places(&[
                NodePlace::new("a", post).after("b"),
                NodePlace::new("b", post).after("a"),
                NodePlace::new("c", post),
            ]),
            Err(NodeOrderError::Cycle(vec!["a", "b"]))
        );
    }
}
