//! The Extract stage's part of anti-aliasing: which kind the active camera uses this frame,
//! and under TAA the frame of its history, whose sub-pixel jitter moves the frame uniform's
//! projection (and seeds the jittered march). Textures are read finer as the kind asks.

use super::fxaa::FastApproximateAntiAliasing;
use super::temporal::{
    AntiAliasing, TemporalAntiAliasing, TemporalFrame, TemporalHistory, TemporalView, jittered,
};
use crate::render::{ExtractedFrame, RenderTarget};
use crate::{AppError, Camera, Resources};

/// This frame's anti-aliasing as the Extract stage found it. A resource of the anti-aliasing
/// plugin.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct AntiAliasingFrame {
    /// The active camera's kind (its component, else the app's resource, else off).
    pub kind: AntiAliasing,
    /// This frame's temporal anti-aliasing, on TAA frames with a camera (the frame uniform's
    /// projection is then jittered by its offset).
    pub temporal: Option<TemporalFrame>,
    /// The active camera's FXAA parameters (its component, else the defaults), as given.
    pub fxaa: FastApproximateAntiAliasing,
}

/// The Extract stage's system, after the renderer's: jitters the frame's projection under TAA
/// and scales its texture footprints by the kind's mip bias.
pub(super) fn extract_anti_aliasing(
    world: &mut hecs::World,
    resources: &mut Resources,
) -> Result<(), AppError> {
    let target = resources.require::<RenderTarget>()?;
    let (target_id, target_size) = (target.id(), target.size());
    let camera = world
        .query::<(
            hecs::Entity,
            &Camera,
            Option<&AntiAliasing>,
            Option<&TemporalAntiAliasing>,
            Option<&FastApproximateAntiAliasing>,
        )>()
        .iter()
        .find(|(_, camera, ..)| camera.active)
        .map(|(entity, camera, kind, settings, fxaa)| {
            (
                entity,
                *camera,
                kind.copied(),
                settings.copied(),
                fxaa.copied(),
            )
        });
    let kind = camera
        .and_then(|(_, _, kind, _, _)| kind)
        .or_else(|| resources.get::<AntiAliasing>().copied())
        .unwrap_or_default();
    let frame = resources.require::<ExtractedFrame>()?.frame;
    let history = resources.get_or_default::<TemporalHistory>();
    let temporal = match camera {
        Some((entity, camera, _, settings, _)) if kind == AntiAliasing::Taa => {
            Some(history.next_frame(
                target_id,
                entity,
                camera.projection,
                TemporalView {
                    view_projection: glam::Mat4::from_cols_array_2d(&frame.view_projection),
                    position: glam::Vec4::from(frame.camera_position).truncate(),
                    direction: glam::Vec4::from(frame.view_direction).truncate(),
                },
                &settings.unwrap_or_default(),
            ))
        }
        _ => {
            history.skip();
            None
        }
    };
    let extracted = resources.require_mut::<ExtractedFrame>()?;
    let uniform = &mut extracted.frame;
    if let Some(temporal) = temporal {
        let projection = glam::Mat4::from_cols_array_2d(&uniform.view_projection);
        uniform.view_projection =
            jittered(projection, temporal.jitter, target_size).to_cols_array_2d();
        // z: the seed of per-frame noise (the jittered march); w: TAA averages that noise (the
        // soft shadow's samples move only then).
        uniform.target_size[2] = temporal.frame_index;
        uniform.target_size[3] = 1;
    }
    uniform.texture_lod[0] = kind.texture_footprint_scale(temporal.map(|f| f.settings));
    let fxaa = camera.and_then(|(.., fxaa)| fxaa).unwrap_or_default();
    resources.insert(AntiAliasingFrame {
        kind,
        temporal,
        fxaa,
    });
    Ok(())
}
