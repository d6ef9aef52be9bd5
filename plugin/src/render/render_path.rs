//! Forward or deferred: where the opaque materials that can resolve in compute are shaded.
//!
//! Forward: every opaque draw shades in the opaque phase's fragment stage, after the depth
//! prepass. Deferred: the prepass becomes the visibility pass (depth plus a draw and triangle id
//! per pixel, merged into a buffer of 64-bit keys), and materials that offer a compute resolve
//! ([`crate::Material::deferred_resolve`]) shade their pixels in a compute pass after the opaque
//! phase; the others still draw there.

use std::str::FromStr;

use super::{DrawPhase, RenderPhases, RenderTarget, visibility};
use crate::Resources;
use crate::gpu::{DEFERRED_FEATURES, GpuContext};

/// How opaque surfaces are shaded: [`super::RenderPlugin::path`], switchable at run time with
/// [`super::Renderer::set_path`].
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum RenderPath {
    /// Every opaque surface shades in a fragment shader.
    Forward,
    /// Materials that can resolve in compute shade there, from the visibility buffer; where the
    /// adapter or the app cannot (see [`DeferredUnavailable`]) the frame runs forward, said once
    /// in the log.
    Deferred,
    /// Deferred on a GPU that can run it, forward on a CPU rasterizer (lavapipe, where the two
    /// stages cost the same and forward is the reference) and wherever deferred cannot run.
    /// On a GPU the deferred frame is several times faster at 4K (sandbox/BENCHMARKS.md, "The
    /// cobblestone frame at 4K").
    #[default]
    Auto,
}

impl RenderPath {
    /// Every path, as the command line names them.
    pub const ALL: [RenderPath; 3] = [RenderPath::Forward, RenderPath::Deferred, RenderPath::Auto];

    /// The path's name on the command line and in logs.
    pub fn name(self) -> &'static str {
        match self {
            RenderPath::Forward => "forward",
            RenderPath::Deferred => "deferred",
            RenderPath::Auto => "auto",
        }
    }
}

impl std::fmt::Display for RenderPath {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// A render path name that is none of `forward`, `deferred`, `auto`.
#[derive(Debug, thiserror::Error)]
#[error("unknown render path {0:?}: expected forward, deferred or auto")]
pub struct UnknownRenderPath(pub String);

impl FromStr for RenderPath {
    type Err = UnknownRenderPath;

    fn from_str(name: &str) -> Result<Self, Self::Err> {
        RenderPath::ALL
            .into_iter()
            .find(|path| path.name() == name)
            .ok_or_else(|| UnknownRenderPath(name.to_owned()))
    }
}

/// Why a frame that asked for the deferred path runs forward.
#[derive(Clone, Copy, Debug, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum DeferredUnavailable {
    /// The visibility pass needs each pixel's triangle and 64-bit atomics.
    #[error(
        "the adapter lacks primitive_index or 64-bit atomic min/max (wgpu::Features::PRIMITIVE_INDEX, SHADER_INT64, SHADER_INT64_ATOMIC_MIN_MAX)"
    )]
    MissingFeatures,
    /// The visibility pass is the depth prepass.
    #[error("the depth prepass is off (RenderPlugin::depth_prepass)")]
    NoDepthPrepass,
    /// Every opaque draw must write the visibility buffer.
    #[error("material {0} has no deferred shader (Material::deferred_shader)")]
    MaterialWithoutDeferredShader(&'static str),
    /// A plugin draws into the prepass outside any material: it would write depth but no
    /// visibility key.
    #[error(
        "a prepass draw is no material's (RenderPhases::add_draw): it writes no visibility key"
    )]
    PrepassDrawWithoutVisibility,
    /// The target's visibility buffer would pass the device's buffer limits.
    #[error("the target's visibility buffer ({bytes} bytes) passes the device's buffer limits")]
    TargetTooLarge {
        /// Its size.
        bytes: u64,
    },
}

/// Whether the adapter, the renderer's settings and `target`'s size allow the deferred path.
pub(crate) fn deferred_support(
    gpu: &GpuContext,
    depth_prepass: bool,
    target: &RenderTarget,
) -> Result<(), DeferredUnavailable> {
    if !gpu.device.features().contains(DEFERRED_FEATURES) {
        return Err(DeferredUnavailable::MissingFeatures);
    }
    if !depth_prepass {
        return Err(DeferredUnavailable::NoDepthPrepass);
    }
    if !visibility::visibility_fits(gpu, target) {
        return Err(DeferredUnavailable::TargetTooLarge {
            bytes: 2 * visibility::visibility_bytes(target),
        });
    }
    Ok(())
}

/// What of the app keeps frames from the deferred path: a material without a deferred shader,
/// or a prepass draw that is no material's (it would write depth but no visibility key).
pub(crate) fn deferred_blocker(resources: &Resources) -> Option<DeferredUnavailable> {
    let phases = resources.get::<RenderPhases>()?;
    if let Some(name) = phases.owner_without_visibility() {
        return Some(DeferredUnavailable::MaterialWithoutDeferredShader(name));
    }
    phases
        .draw_owners(DrawPhase::Prepass)
        .any(|owner| !phases.writes_visibility(owner))
        .then_some(DeferredUnavailable::PrepassDrawWithoutVisibility)
}

/// Whether [`RenderPath::Auto`] picks deferred on this adapter: on any GPU, not on a CPU
/// rasterizer.
pub(crate) fn auto_picks_deferred(gpu: &GpuContext) -> bool {
    gpu.adapter_info().device_type != wgpu::DeviceType::Cpu
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn paths_read_back_their_names_and_an_unknown_one_is_an_error() {
        for path in RenderPath::ALL {
            assert_eq!(path.name().parse::<RenderPath>().unwrap(), path);
        }
        let error = "deferrd".parse::<RenderPath>().unwrap_err().to_string();
        assert!(
            error.contains("\"deferrd\"") && error.contains("forward"),
            "{error}"
        );
    }
}
