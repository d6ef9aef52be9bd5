//! The post chain: full-screen [`PostEffect`]s on the HDR scene, the one effect that turns it
//! into the display image (tonemapping), then effects on the display image, each reading what
//! the one before wrote. The chain owns the images between effects (made when first needed,
//! one pair per stage at most) and hands the last display effect the target's display texture.

use std::sync::atomic::{AtomicU64, Ordering};

use super::RenderError;
use super::RenderTarget;
use super::frame_nodes::FrameView;
use crate::Resources;
use crate::gpu::{GpuContext, PassTimestamps};

/// Where in the post chain an effect runs.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum PostStage {
    /// On the HDR image before tonemapping, in the target's scene format: linear, pre-exposed
    /// colour, or after TAA its history's tonemapped colour ([`PostIo::holds`] says which). A
    /// negative alpha marks a display-referred pixel (the clear colour, a debug view's data),
    /// which tonemapping passes through: leave such pixels as they are.
    Hdr,
    /// From the HDR scene to the display image: one effect per frame (tonemapping).
    ToDisplay,
    /// On the display image (the target's format, sRGB-encoded for 8-bit targets), after
    /// tonemapping.
    Display,
}

/// Where a full-screen pass runs on this adapter ([`super::Renderer::full_screen_stage`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FullScreenStage {
    /// A compute pass, writing its output as a storage texture.
    Compute,
    /// A full-screen triangle.
    Fragment,
}

/// An image of the post chain: a texture view and an id that is new whenever the texture is, so
/// effects can keep bind groups by the ids they bind.
#[derive(Clone, Debug)]
pub struct PostImage {
    /// The id (unique in the process).
    pub id: u64,
    /// The view, 2D, one mip.
    pub view: wgpu::TextureView,
}

static NEXT_IMAGE_ID: AtomicU64 = AtomicU64::new(1);

impl PostImage {
    /// `view` under a new id.
    pub fn new(view: wgpu::TextureView) -> Self {
        Self {
            id: Self::new_id(),
            view,
        }
    }

    /// An id no image has had, for an image made elsewhere.
    pub fn new_id() -> u64 {
        NEXT_IMAGE_ID.fetch_add(1, Ordering::Relaxed)
    }
}

/// What one effect reads and writes.
#[derive(Clone, Copy, Debug)]
pub struct PostIo<'a> {
    /// The image the effect reads: the scene, or what the effect before it wrote.
    pub input: &'a PostImage,
    /// The image it writes: an image of the chain, or the target's display texture for the
    /// last effect; `None` for effects that write images of their own
    /// ([`PostEffect::writes_own_image`]).
    pub output: Option<&'a PostImage>,
    /// What an HDR effect's input holds: the scene colour, or colour an HDR effect before it
    /// (TAA) has tonemapped already; display effects always read display values.
    pub holds: HdrInput,
}

/// What the input of the chain's display conversion holds.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum HdrInput {
    /// The pre-exposed scene colour, to be tonemapped.
    SceneColour,
    /// Colour an HDR effect has tonemapped already ([`PostEffect::output_is_tonemapped`]).
    Tonemapped,
}

/// A full-screen effect of the post chain, added with [`super::FrameNodes::add_post_effect`]
/// and timed under its node's name. An effect writes every pixel of its output, in compute or
/// as a full-screen triangle (see [`super::Renderer::full_screen_stage`]); the image it reads
/// is never the one it writes.
pub trait PostEffect: 'static {
    /// Where it runs.
    fn stage(&self) -> PostStage;

    /// Whether it has work this frame; when false it records nothing, makes nothing and is not
    /// timed, and the chain passes its input on.
    fn runs(&self, frame: FrameView<'_>) -> bool;

    /// Makes or uploads what this frame needs, before any effect records; `input` says what
    /// the display conversion will read. Returns the bytes uploaded.
    fn prepare(
        &mut self,
        _resources: &mut Resources,
        _input: HdrInput,
    ) -> Result<u64, RenderError> {
        Ok(0)
    }

    /// Whether it writes an image of its own (a history, say) instead of the output the chain
    /// gives it; only HDR effects may.
    fn writes_own_image(&self) -> bool {
        false
    }

    /// Whether the image it writes holds tonemapped colour already (the display conversion
    /// then applies no operator).
    fn output_is_tonemapped(&self) -> bool {
        false
    }

    /// Whether it reads the target's scene itself rather than its input (TAA, which keeps a
    /// history of the scene): it must then run before every other HDR effect.
    fn reads_the_scene(&self) -> bool {
        false
    }

    /// Whether it reads the target's depth ([`RenderTarget::depth_view`]): the core then keeps
    /// it, with the depth a deferred resolve settled drawn into it.
    fn reads_scene_depth(&self) -> bool {
        false
    }

    /// Whether it reads the scene's depth only by sampling [`FrameView::scene_depth`] in a
    /// shader (see [`super::FrameNode::samples_scene_depth`]).
    fn samples_scene_depth(&self) -> bool {
        false
    }

    /// Records the effect: `io.input` into `io.output`. An effect that writes its own image
    /// returns it (`None`: it wrote nothing, and its input is passed on).
    fn record(
        &mut self,
        frame: FrameView<'_>,
        io: PostIo<'_>,
        encoder: &mut wgpu::CommandEncoder,
        time: Option<&PassTimestamps>,
    ) -> Result<Option<PostImage>, RenderError>;
}

/// Why the post chain cannot run.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum PostChainError {
    /// No effect, or more than one, turns the HDR scene into the display image this frame.
    #[error(
        "{0} post effects turn the HDR scene into the display image this frame; exactly one must (the tonemapping plugin adds it)"
    )]
    DisplayConversions(usize),
    /// An effect after the HDR stage wrote an image of its own.
    #[error("post effect {0:?} writes an image of its own; only HDR effects may")]
    OwnImageAfterHdr(&'static str),
    /// A post effect's WGSL does not compile.
    #[error(
        "post effect {effect:?}: its WGSL does not compile (line {line} of the effect): {message}"
    )]
    EffectShader {
        /// The effect's label.
        effect: String,
        /// The line in the effect's own WGSL (0: in the code composed around it).
        line: u32,
        /// What naga says.
        message: String,
    },
    /// An effect that reads the scene itself runs after another HDR effect, whose work it
    /// would drop.
    #[error(
        "post effect {reader:?} reads the scene itself, so HDR effect {before:?} must run after it (place it with NodePlace::after({reader:?}))"
    )]
    SceneReaderNotFirst {
        /// The effect reading the scene.
        reader: &'static str,
        /// The HDR effect placed before it.
        before: &'static str,
    },
}

/// Targets whose chain images are kept: a split view renders two each frame.
const KEPT_TARGETS: usize = 2;

/// The chain's images of the targets among the last [`KEPT_TARGETS`] rendered, so a frame that
/// renders two targets makes none again, while a target no longer rendered (a window's, before
/// a resize) is let go with its textures, which the images hold views of.
#[derive(Debug, Default)]
pub(crate) struct PostImages {
    targets: Vec<TargetImages>,
    /// Counts the chains recorded.
    renders: u64,
}

impl PostImages {
    /// The images of `target`, made when it is new.
    fn of_target(&mut self, target: &RenderTarget) -> Option<&mut TargetImages> {
        self.renders += 1;
        let renders = self.renders;
        let mut images = match self
            .targets
            .iter()
            .position(|images| images.target == target.id())
        {
            Some(at) => self.targets.remove(at),
            None => TargetImages::new(target),
        };
        images.rendered = renders;
        self.targets
            .retain(|kept| renders - kept.rendered < KEPT_TARGETS as u64);
        self.targets.push(images);
        self.targets.last_mut()
    }
}

/// The images between effects for one target: two of the scene's format and two of the
/// display's, each made when first needed.
#[derive(Debug)]
struct TargetImages {
    target: u64,
    /// The chain that last used them ([`PostImages`] counts).
    rendered: u64,
    scene: PostImage,
    display: PostImage,
    hdr: [Option<PostImage>; 2],
    between: [Option<PostImage>; 2],
}

impl TargetImages {
    fn new(target: &RenderTarget) -> Self {
        Self {
            target: target.id(),
            rendered: 0,
            scene: PostImage::new(target.scene_view.clone()),
            display: PostImage::new(target.color_view.clone()),
            hdr: Default::default(),
            between: Default::default(),
        }
    }

    /// An image of the chain of `stage`'s format that is not `avoid`.
    fn spare(
        &mut self,
        gpu: &GpuContext,
        target: &RenderTarget,
        stage: PostStage,
        avoid: u64,
    ) -> PostImage {
        let (slots, format, label) = match stage {
            PostStage::Hdr => (&mut self.hdr, target.scene_format(), "post chain (HDR)"),
            _ => (&mut self.between, target.format(), "post chain (display)"),
        };
        let free = usize::from(slots[0].as_ref().is_some_and(|image| image.id == avoid));
        slots[free]
            .get_or_insert_with(|| {
                let storage = if gpu.can_store(format) {
                    wgpu::TextureUsages::STORAGE_BINDING
                } else {
                    wgpu::TextureUsages::empty()
                };
                let texture = super::plain_texture(
                    gpu,
                    label,
                    target.size(),
                    format,
                    wgpu::TextureUsages::TEXTURE_BINDING
                        | wgpu::TextureUsages::RENDER_ATTACHMENT
                        | storage,
                );
                PostImage::new(texture.create_view(&wgpu::TextureViewDescriptor::default()))
            })
            .clone()
    }
}

/// One effect of this frame's chain, with its timestamps.
pub(crate) struct ChainLink<'a> {
    pub(crate) name: &'static str,
    pub(crate) effect: &'a mut dyn PostEffect,
    pub(crate) time: Option<PassTimestamps>,
}

/// The order of the stages in the chain.
pub(crate) fn stage_rank(stage: PostStage) -> u8 {
    match stage {
        PostStage::Hdr => 0,
        PostStage::ToDisplay => 1,
        PostStage::Display => 2,
    }
}

/// What the display conversion will read, given the effects that run this frame.
pub(crate) fn hdr_input<'a>(running: impl Iterator<Item = &'a dyn PostEffect>) -> HdrInput {
    let mut running = running;
    if running.any(|effect| effect.stage() == PostStage::Hdr && effect.output_is_tonemapped()) {
        HdrInput::Tonemapped
    } else {
        HdrInput::SceneColour
    }
}

/// Records `links` (the effects that run, in stage order) into `encoder`: the scene through every HDR
/// effect, the conversion, and the display effects, the last of which writes the target's
/// display texture.
pub(crate) fn record_chain(
    images: &mut PostImages,
    frame: FrameView<'_>,
    links: Vec<ChainLink<'_>>,
    encoder: &mut wgpu::CommandEncoder,
) -> Result<(), RenderError> {
    let conversions = links
        .iter()
        .filter(|link| link.effect.stage() == PostStage::ToDisplay)
        .count();
    if conversions != 1 {
        return Err(PostChainError::DisplayConversions(conversions).into());
    }
    let Some(images) = images.of_target(frame.target) else {
        return Ok(());
    };
    let (scene, display) = (images.scene.clone(), images.display.clone());
    let first_hdr = links
        .first()
        .filter(|link| link.effect.stage() == PostStage::Hdr);
    if let Some(reader) = links
        .iter()
        .skip(1)
        .find(|link| link.effect.reads_the_scene())
        && let Some(before) = first_hdr
    {
        return Err(PostChainError::SceneReaderNotFirst {
            reader: reader.name,
            before: before.name,
        }
        .into());
    }
    let last = links.len().saturating_sub(1);
    let mut current = scene;
    let mut holds = HdrInput::SceneColour;
    for (index, link) in links.into_iter().enumerate() {
        let stage = link.effect.stage();
        let output = if index == last {
            Some(display.clone())
        } else if link.effect.writes_own_image() {
            None
        } else {
            let spare_stage = match stage {
                PostStage::Hdr => PostStage::Hdr,
                _ => PostStage::Display,
            };
            Some(images.spare(frame.gpu, frame.target, spare_stage, current.id))
        };
        let io = PostIo {
            input: &current,
            output: output.as_ref(),
            holds,
        };
        let own = link.effect.record(frame, io, encoder, link.time.as_ref())?;
        let wrote = own.is_some() || output.is_some();
        current = match (own, output) {
            (Some(_), _) if stage != PostStage::Hdr => {
                return Err(PostChainError::OwnImageAfterHdr(link.name).into());
            }
            (Some(own), _) => own,
            (None, Some(output)) => output,
            (None, None) => current,
        };
        if wrote && stage == PostStage::Hdr && link.effect.output_is_tonemapped() {
            holds = HdrInput::Tonemapped;
        }
    }
    Ok(())
}
