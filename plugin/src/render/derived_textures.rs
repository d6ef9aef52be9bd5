//! Textures the GPU derives from an uploaded image (a height map's maximum pyramid), cached
//! per image and derivation and rebuilt whenever the image is re-uploaded (a dynamic height
//! field's every change). The Prepare stage makes the builds ready; the frame records them in
//! one compute pass before its phases ([`DERIVED_TEXTURES_PASS`]).

use std::collections::HashMap;

use super::gpu_assets::{GpuImage, solid_texture};
use super::max_pyramid::{MaxPyramidBuilder, PyramidBuild, PyramidLevels, create_pyramid};
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

/// What a [`DerivedTexture`] holds.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
#[non_exhaustive]
pub enum TextureDerivation {
    /// The maximum-height pyramid (`R32Float`, read with `textureLoad`): level 0 holds, per cell
    /// between four texel centres (wrapping), the highest corner with 1 = top; each level above
    /// the maximum of 2 × 2 cells, while both sides stay even.
    MaxHeightPyramid {
        /// Channel of the source holding the height: 0 = red .. 3 = alpha.
        channel: u8,
        /// Whether white in the source means deepest (depth maps): the pyramid inverts it.
        depth_convention: bool,
    },
}

/// A derived texture on the GPU.
#[derive(Debug)]
pub(crate) struct GpuDerivedTexture {
    /// The texture (read back by `read_max_pyramid`; the view keeps it alive otherwise).
    #[cfg_attr(not(feature = "scene-tests"), allow(dead_code))]
    pub texture: wgpu::Texture,
    /// A view of every level.
    pub view: wgpu::TextureView,
    /// What every build into `texture` shares.
    levels: PyramidLevels,
    /// Upload serial of the source it was built from.
    source_serial: u64,
    /// The last sweep before which a draw used it.
    last_used: u64,
    /// Distinguishes rebuilds, so bind groups that use it are rebuilt.
    pub serial: u64,
}

/// Frames a derived texture no draw used is kept before its memory is freed (a 4096² pyramid
/// holds 89 MB). Every draw is prepared every frame, so one frame without a user means no
/// material uses it any more; switching back rebuilds it (a few dispatches).
const UNUSED_FRAMES_KEPT: u64 = 1;

/// The derived textures of every image, and the default bound where a draw has none.
pub(crate) struct DerivedTextureCache {
    builder: Option<MaxPyramidBuilder>,
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
    /// An empty cache; the builder is compiled when something is first derived.
    pub(crate) fn new(gpu: &GpuContext) -> Self {
        Self {
            builder: None,
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
        let TextureDerivation::MaxHeightPyramid {
            channel,
            depth_convention,
        } = derived.derivation;
        let builder = self
            .builder
            .get_or_insert_with(|| MaxPyramidBuilder::new(gpu));
        let (width, height) = (source.texture.width(), source.texture.height());
        let reusable = self
            .textures
            .get_mut(&derived)
            .filter(|cached| (cached.texture.width(), cached.texture.height()) == (width, height));
        // A rewritten source of the same size (a dynamic height field's every change) is built
        // into the same texture: nothing reallocated, only level 0's bind group remade.
        let cached = match reusable {
            Some(cached) => cached,
            None => {
                let texture = create_pyramid(gpu, width, height);
                let view = texture.create_view(&Default::default());
                let levels = builder.levels(gpu, &texture, (channel, depth_convention));
                let fresh = GpuDerivedTexture {
                    texture,
                    view,
                    levels,
                    source_serial: 0,
                    last_used: 0,
                    serial: next_serial,
                };
                self.textures.entry(derived).insert_entry(fresh).into_mut()
            }
        };
        self.pending
            .0
            .push(builder.build(gpu, &source.texture, &cached.texture, &cached.levels));
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
/// any phase reads them.
#[derive(Default)]
pub(crate) struct DerivedTextureBuilds(Vec<PyramidBuild>);

impl DerivedTextureBuilds {
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
        for build in &self.0 {
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
