//! Textures the GPU derives from an uploaded image (the parallax material's maximum pyramid of
//! its height map, say), cached per image and derivation and rebuilt whenever the image is
//! re-uploaded (a dynamic height field's every change). What is derived, and how, is the
//! material's: it names a [`TextureDeriver`] of its own; the core compiles each deriver once
//! per device, keeps the textures and records the builds. The Prepare stage makes the builds
//! ready; the frame records them in one compute pass before its phases
//! ([`DERIVED_TEXTURES_PASS`]).

use std::any::Any;
use std::collections::HashMap;
use std::fmt;
use std::hash::{Hash, Hasher};

use super::assets::{GpuImage, solid_texture};
use super::{GpuContext, PassTimestamps};
use crate::{AssetId, Image};

/// The name under which [`crate::GpuTimings`] reports the frame's builds of derived textures
/// (present only in frames that build one).
pub const DERIVED_TEXTURES_PASS: &str = "derived textures";

/// Most derived textures one material binds.
pub const MAX_DERIVED_TEXTURES: usize = 2;

/// The derived texture in each of a draw's derived slots; `None` binds the default (one texel
/// of 1.0: the pyramid of a field at the top everywhere).
pub type DerivedTextures = [Option<DerivedTexture>; MAX_DERIVED_TEXTURES];

/// A texture the GPU derives from an image.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct DerivedTexture {
    /// The image it is derived from.
    pub source: AssetId<Image>,
    /// What is derived.
    pub derivation: TextureDerivation,
}

/// What a [`DerivedTexture`] holds: a deriver's output for two parameters of its own (a height
/// map's channel and convention, say). Equal when the deriver's name and the parameters are.
#[derive(Clone, Copy)]
pub struct TextureDerivation {
    /// How it is derived.
    pub deriver: &'static dyn TextureDeriver,
    /// What the deriver is told besides the source (their meaning is the deriver's).
    pub parameters: [u32; 2],
}

impl TextureDerivation {
    fn key(&self) -> (&'static str, [u32; 2]) {
        (self.deriver.name(), self.parameters)
    }
}

impl fmt::Debug for TextureDerivation {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("TextureDerivation")
            .field("deriver", &self.deriver.name())
            .field("parameters", &self.parameters)
            .finish()
    }
}

impl PartialEq for TextureDerivation {
    fn eq(&self, other: &Self) -> bool {
        self.key() == other.key()
    }
}

impl Eq for TextureDerivation {}

impl Hash for TextureDerivation {
    fn hash<H: Hasher>(&self, state: &mut H) {
        self.key().hash(state);
    }
}

impl PartialOrd for TextureDerivation {
    fn partial_cmp(&self, other: &Self) -> Option<std::cmp::Ordering> {
        Some(self.cmp(other))
    }
}

impl Ord for TextureDerivation {
    fn cmp(&self, other: &Self) -> std::cmp::Ordering {
        self.key().cmp(&other.key())
    }
}

/// A way to derive a texture from an image on the GPU, named by the materials that bind its
/// output ([`crate::gpu::DerivedTextures`]): a `static` of the material's own.
pub trait TextureDeriver: Sync {
    /// A name unique among derivers, for labels and the cache.
    fn name(&self) -> &'static str;
    /// Compiles what its builds need on `gpu`: once per device, when something is first
    /// derived with it.
    fn compile(&self, gpu: &GpuContext) -> Box<dyn DerivedTextureBuilder>;
}

/// A [`TextureDeriver`] compiled on one device.
pub trait DerivedTextureBuilder: Send + Sync {
    /// An empty derived texture for a `width` × `height` source, bound as an unfilterable float
    /// texture (`textureLoad`), and what every build into it shares.
    fn create(&self, gpu: &GpuContext, size: (u32, u32), parameters: [u32; 2]) -> DerivedStorage;
    /// The build of `storage` from `source`, recorded by the frame before any phase reads it.
    fn build(
        &self,
        gpu: &GpuContext,
        source: &wgpu::Texture,
        storage: &DerivedStorage,
    ) -> ComputeDispatches;
}

/// A derived texture and what its builds share (bind groups of levels that never change, say).
pub struct DerivedStorage {
    /// The texture (with every mip level the deriver wants).
    pub texture: wgpu::Texture,
    /// The deriver's own state, given back to each build.
    pub shared: Box<dyn Any + Send + Sync>,
}

impl fmt::Debug for DerivedStorage {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("DerivedStorage")
            .field("texture", &self.texture)
            .finish_non_exhaustive()
    }
}

/// One compute dispatch of a build.
#[derive(Clone, Debug)]
pub struct ComputeDispatch {
    /// The pipeline.
    pub pipeline: wgpu::ComputePipeline,
    /// Its group 0 (it keeps the textures it binds alive until the build is recorded).
    pub bind_group: wgpu::BindGroup,
    /// Workgroups along x, y and z.
    pub workgroups: [u32; 3],
}

/// A build's dispatches, recorded in order in one compute pass: wgpu puts a barrier between
/// dispatches where one writes what the next reads.
#[derive(Clone, Debug, Default)]
pub struct ComputeDispatches(pub Vec<ComputeDispatch>);

impl ComputeDispatches {
    fn record(&self, pass: &mut wgpu::ComputePass<'_>) {
        for dispatch in &self.0 {
            pass.set_pipeline(&dispatch.pipeline);
            pass.set_bind_group(0, &dispatch.bind_group, &[]);
            let [x, y, z] = dispatch.workgroups;
            pass.dispatch_workgroups(x, y, z);
        }
    }
}

/// A derived texture on the GPU.
#[derive(Debug)]
pub(crate) struct GpuDerivedTexture {
    /// The texture and what its builds share.
    storage: DerivedStorage,
    /// A view of every level.
    pub view: wgpu::TextureView,
    /// Upload serial of the source it was built from.
    source_serial: u64,
    /// The last sweep before which a draw used it.
    last_used: u64,
    /// Distinguishes rebuilds, so bind groups that use it are rebuilt.
    pub serial: u64,
}

impl GpuDerivedTexture {
    /// The texture (tests read it back; the view keeps it alive otherwise).
    #[cfg_attr(not(feature = "scene-tests"), allow(dead_code))]
    pub(crate) fn texture(&self) -> &wgpu::Texture {
        &self.storage.texture
    }
}

/// Frames a derived texture no draw used is kept before its memory is freed (a 4096² pyramid
/// holds 89 MB). Every draw is prepared every frame, so one frame without a user means no
/// material uses it any more; switching back rebuilds it (a few dispatches).
const UNUSED_FRAMES_KEPT: u64 = 1;

/// The derived textures of every image, and the default bound where a draw has none.
pub(crate) struct DerivedTextureCache {
    /// Each deriver used so far, compiled, by name.
    builders: HashMap<&'static str, Box<dyn DerivedTextureBuilder>>,
    textures: HashMap<DerivedTexture, GpuDerivedTexture>,
    /// Builds prepared and not yet submitted in a frame.
    pending: DerivedTextureBuilds,
    /// Sweeps so far: one per frame.
    sweeps: u64,
    /// One texel of 1.0 in `R32Float`.
    pub(crate) default_view: wgpu::TextureView,
}

impl std::fmt::Debug for DerivedTextureCache {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("DerivedTextureCache")
            .field("textures", &self.textures.len())
            .finish()
    }
}

impl DerivedTextureCache {
    /// An empty cache; a deriver is compiled when something is first derived with it.
    pub(crate) fn new(gpu: &GpuContext) -> Self {
        Self {
            builders: HashMap::new(),
            textures: HashMap::new(),
            pending: DerivedTextureBuilds::default(),
            sweeps: 0,
            default_view: solid_texture(
                gpu,
                "default derived texture",
                1.0_f32.to_le_bytes(),
                wgpu::TextureFormat::R32Float,
            ),
        }
    }

    /// Queues the build of `derived` from `source` if it is missing or older than the source's
    /// upload (the frame records it); `next_serial` numbers a new texture. Returns whether it
    /// queued one.
    pub(crate) fn prepare(
        &mut self,
        gpu: &GpuContext,
        derived: DerivedTexture,
        source: &GpuImage,
        next_serial: u64,
    ) -> bool {
        if let Some(cached) = self.textures.get_mut(&derived)
            && cached.source_serial == source.upload_serial
        {
            cached.last_used = self.sweeps;
            return false;
        }
        let derivation = derived.derivation;
        let builder = self
            .builders
            .entry(derivation.deriver.name())
            .or_insert_with(|| derivation.deriver.compile(gpu));
        let size = (source.texture.width(), source.texture.height());
        let reusable = self.textures.get_mut(&derived).filter(|cached| {
            (
                cached.storage.texture.width(),
                cached.storage.texture.height(),
            ) == size
        });
        // A rewritten source of the same size (a dynamic height field's every change) is built
        // into the same texture: nothing reallocated, only the bind groups reading it remade.
        let cached = match reusable {
            Some(cached) => cached,
            None => {
                let storage = builder.create(gpu, size, derivation.parameters);
                let view = storage.texture.create_view(&Default::default());
                let fresh = GpuDerivedTexture {
                    storage,
                    view,
                    source_serial: 0,
                    last_used: 0,
                    serial: next_serial,
                };
                self.textures.entry(derived).insert_entry(fresh).into_mut()
            }
        };
        self.pending.queue(
            derived,
            builder.build(gpu, &source.texture, &cached.storage),
        );
        cached.source_serial = source.upload_serial;
        cached.last_used = self.sweeps;
        true
    }

    /// The builds queued and not yet submitted, for the frame to record.
    pub(crate) fn pending_builds(&self) -> &DerivedTextureBuilds {
        &self.pending
    }

    /// Forgets the queued builds once the frame that recorded them is submitted: a frame that
    /// fails before that leaves them for the next.
    pub(crate) fn builds_submitted(&mut self) {
        self.pending.0.clear();
    }

    /// The derived texture, if built.
    pub(crate) fn get(&self, derived: &DerivedTexture) -> Option<&GpuDerivedTexture> {
        self.textures.get(derived)
    }

    /// Once a frame: drops what was derived from images that are gone, and what no draw has
    /// used for [`UNUSED_FRAMES_KEPT`] frames.
    pub(crate) fn sweep(&mut self, mut source_exists: impl FnMut(AssetId<Image>) -> bool) {
        self.sweeps += 1;
        let oldest_kept = self.sweeps.saturating_sub(UNUSED_FRAMES_KEPT);
        self.textures.retain(|derived, texture| {
            source_exists(derived.source) && texture.last_used >= oldest_kept
        });
    }

    /// How many derived textures are held.
    pub(crate) fn len(&self) -> usize {
        self.textures.len()
    }
}

/// Builds of derived textures made ready in the Prepare stage, recorded by the frame before
/// any phase reads them; at most one per derived texture.
#[derive(Default)]
pub(crate) struct DerivedTextureBuilds(Vec<(DerivedTexture, ComputeDispatches)>);

impl DerivedTextureBuilds {
    /// Queues `build` of `derived` in place of one queued before and not yet submitted (a
    /// build writes the whole texture): frames that fail before submitting, while a source
    /// changes every frame, do not pile builds up.
    fn queue(&mut self, derived: DerivedTexture, build: ComputeDispatches) {
        match self.0.iter_mut().find(|(queued, _)| *queued == derived) {
            Some((_, queued)) => *queued = build,
            None => self.0.push((derived, build)),
        }
    }

    /// Whether there is nothing to build.
    pub(crate) fn is_empty(&self) -> bool {
        self.0.is_empty()
    }

    /// Records every build in one compute pass, timed by `timestamps`.
    pub(crate) fn record(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        timestamps: Option<&PassTimestamps>,
    ) {
        if self.is_empty() {
            return;
        }
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some(DERIVED_TEXTURES_PASS),
            timestamp_writes: timestamps.map(PassTimestamps::compute),
        });
        for (_, build) in &self.0 {
            build.record(&mut pass);
        }
    }

    /// Records and submits the builds on their own, outside a frame.
    #[cfg(feature = "scene-tests")]
    pub(crate) fn submit(&self, gpu: &GpuContext) {
        let mut encoder = gpu
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some(DERIVED_TEXTURES_PASS),
            });
        self.record(&mut encoder, None);
        gpu.queue.submit([encoder.finish()]);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::parallax::MaxHeightPyramid;
    use crate::{Assets, Channel, HeightConvention, TextureKind};

    #[test]
    fn a_texture_has_one_build_queued_however_often_its_source_changes() {
        let mut images = Assets::default();
        let mut derived = |convention| DerivedTexture {
            source: images
                .add(Image::from_rgba8(1, 1, vec![0; 4], TextureKind::Height).unwrap())
                .id(),
            derivation: MaxHeightPyramid::derivation(Channel::Red, convention),
        };
        let (first, second) = (
            derived(HeightConvention::Height),
            derived(HeightConvention::Depth),
        );
        let mut builds = DerivedTextureBuilds::default();
        for _ in 0..100 {
            builds.queue(first, ComputeDispatches(Vec::new()));
            builds.queue(second, ComputeDispatches(Vec::new()));
        }
        assert_eq!(builds.0.len(), 2);
    }
}
