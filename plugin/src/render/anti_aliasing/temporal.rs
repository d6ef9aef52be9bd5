//! Anti-aliasing of a camera's image: which kind ([`AntiAliasing`], a camera component), the
//! parameters of temporal anti-aliasing ([`TemporalAntiAliasing`], a camera component too),
//! and what the history of one frame to the next keeps on the CPU ([`TemporalHistory`]: the
//! sub-pixel jitter, the previous camera, and when the history is thrown away).
//!
//! The post phase runs TAA on the HDR scene before tonemapping (taa.rs), then tonemapping,
//! then the post filter (fxaa.rs) where a frame asks for it. Where a camera has no
//! [`AntiAliasing`], the app's resource of that type applies (the window runner inserts
//! `taa`), else `off`: headless renders and reference images stay unfiltered unless asked.
//!
//! TAA jitters the projection by a Halton (2, 3) offset each frame, reprojects the history
//! with the previous camera through each pixel's depth (a depth-offset surface's depth is the
//! displaced point's) and, where a draw moved, through its motion (object_motion.rs), samples it with a Catmull-Rom filter, clips it to the variance box of
//! the pixel's 3×3 neighbourhood (Salvi 2016) and drops it where the depth it kept says the
//! pixel was hidden (disocclusion). Each pixel's history counts the frames it holds, and a new
//! frame takes 1 / (count + 1) of it (a plain mean: a still scene settles to `jitter_samples`
//! sub-pixel positions exactly, a pixel just revealed gathers samples as fast) but never less
//! than a floor set by the pixel's motion: `still_weight` where it does not move, rising to
//! `current_weight` at half a pixel a frame. The Catmull-Rom read of a history moved by a
//! fraction f of a pixel blurs it by about f(1 − f), so a slowly drifting pixel loses little
//! detail a frame and keeps its history longer (Yang et al. 2009, "Amortized
//! supersampling", §4.1); faster ones keep `current_weight`, as their shading changes too.
//! Textures are sampled `mip_bias` levels finer under TAA (the frame uniform's texture_lod
//! scales the gradients of every texture read, never the geometry), so the settled image averages texture detail over the pixel as a
//! supersampled one does; under the post filter [`POST_FILTER_MIP_BIAS`] levels finer.
//! A reset comes with a new target (a resize), another camera, projection or TAA parameters,
//! another kind of anti-aliasing, or [`TemporalHistory::reset`] (a camera cut). The history
//! holds tonemapped colour, so edges between lit surfaces and the clear colour blend as shown;
//! debug views are averaged like any colour, and both kinds read textures finer (use `off` to
//! read their data exactly).

use glam::{Mat4, Vec2, Vec3};

use crate::parameters::{ClampWarnings, ParamSpec};

crate::choice_enum! {
    /// How a camera's image is anti-aliased.
    pub enum AntiAliasing: "AA" {
        /// None: every edge is whole pixels (what reference images use).
        Off = "off",
        /// FXAA after tonemapping: one frame, no history; softens edges, textures read a level finer.
        Fxaa = "fxaa",
        /// Temporal anti-aliasing: jittered frames accumulated in a history; sharpest when still.
        Taa = "taa",
    }
}

/// Mip levels finer than the pixel's footprint that textures are sampled at under the post
/// filter (TAA has its own, [`TemporalAntiAliasing::mip_bias`]). A trilinear read at the
/// footprint's level is blurrier than the supersampled pixel it stands for; one level finer
/// keeps the detail, and FXAA softens what that sharpens. On the street corner the post
/// filter's edge error against the 4× reference falls many times further with it than without,
/// and further with −1 than with −0.5, −1.5 or −2 (sandbox/BENCHMARKS.md, "Anti-aliasing").
pub const POST_FILTER_MIP_BIAS: f32 = -1.0;

impl AntiAliasing {
    /// What a frame of this kind scales every texture footprint by: 2 to the mip bias of TAA
    /// (`temporal`: its parameters, where the frame has a history) or of the post filter.
    pub fn texture_footprint_scale(self, temporal: Option<TemporalAntiAliasing>) -> f32 {
        match (self, temporal) {
            (_, Some(taa)) => taa.texture_footprint_scale(),
            (AntiAliasing::Fxaa, None) => POST_FILTER_MIP_BIAS.exp2(),
            _ => 1.0,
        }
    }
}

impl Default for AntiAliasing {
    /// Off: a headless render shows exactly what the materials drew.
    fn default() -> Self {
        AntiAliasing::Off
    }
}

crate::settings_parameters! {
    /// The parameters of temporal anti-aliasing, a component of the camera entity (the defaults
    /// where it has none). Each is declared once, in [`TemporalAntiAliasing::PARAMETERS`];
    /// values outside their limits are clamped, with one logged warning.
    #[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
    #[serde(default, deny_unknown_fields)]
    pub struct TemporalAntiAliasing {
        /// Share of the new frame in a pixel moving half a pixel or more a frame, once its
        /// history is long enough: lower is smoother and slower to follow a change.
        current_weight: f32 = 0.1, ParamSpec::float(0.02, 1.0);
        /// Half-width of the colour box the history is clipped to, in standard deviations of
        /// the pixel's 3×3 neighbourhood: lower ghosts less and flickers more.
        clip_gamma: f32 = 1.0, ParamSpec::float(0.25, 4.0);
        /// Sub-pixel positions of the Halton (2, 3) jitter before it repeats: a still image
        /// settles after this many frames.
        jitter_samples: u32 = 16, ParamSpec::integer(1, 64);
        /// How much nearer than expected (as a share of the depth) a pixel's remembered depth
        /// may be before its history counts as disoccluded and is dropped.
        depth_tolerance: f32 = 0.05, ParamSpec::float(0.0, 1.0);
        /// Mip levels finer than the pixel's footprint that textures are sampled at: the jitter
        /// averages the detail over the pixel, as a supersampled image would (0: as without
        /// TAA). The default, −2, is 4 × 4 supersampling's: the 16 positions of a settled
        /// still image, and about the (2 − w) / w = 19 samples a history of current weight
        /// w = 0.1 averages.
        mip_bias: f32 = -2.0, ParamSpec::float(-2.0, 0.0);
        /// Share of the new frame in a pixel that does not move, once its history is long
        /// enough (a pixel drifting slower than half a pixel a frame takes a share between the
        /// two).
        still_weight: f32 = 0.02, ParamSpec::float(0.01, 1.0);
    }
}

impl TemporalAntiAliasing {
    /// What every texture footprint is scaled by: 2 to the mip bias.
    pub fn texture_footprint_scale(&self) -> f32 {
        self.sanitized().mip_bias.exp2()
    }

    /// Frames a still image takes to settle under TAA with these parameters: one whole cycle
    /// of the jitter, after which the history is the plain mean of its sub-pixel positions
    /// (what `render --aa taa` and scripts' renders wait for).
    pub fn settling_frames(&self) -> u32 {
        self.sanitized().jitter_samples
    }
}

/// Puts `anti_aliasing` and `temporal` on every active camera of `world` (replacing what they
/// had); returns how many cameras that was.
pub fn set_camera_anti_aliasing(
    world: &mut hecs::World,
    anti_aliasing: AntiAliasing,
    temporal: TemporalAntiAliasing,
) -> usize {
    let cameras = crate::camera::active_cameras(world);
    for camera in &cameras {
        // The entity was just found, so inserting cannot fail.
        let _ = world.insert(*camera, (anti_aliasing, temporal));
    }
    cameras.len()
}

/// Element `index` (from 1) of the van der Corput sequence in `base`: the Halton sequence's
/// coordinates, evenly spread over 0..1 for any prefix.
fn radical_inverse(mut index: u32, base: u32) -> f32 {
    let (mut result, mut scale) = (0.0_f32, 1.0_f32);
    while index > 0 {
        scale /= base as f32;
        result += (index % base) as f32 * scale;
        index /= base;
    }
    result
}

/// The sub-pixel offset of frame `frame` of a jitter of `samples` positions, in pixels
/// (x right, y down, each in −½..½): Halton (2, 3), skipping its first point (0, 0); the
/// centre for a jitter of one position.
pub fn jitter_offset(frame: u32, samples: u32) -> Vec2 {
    // One position: the pixel's centre, as without TAA.
    if samples <= 1 {
        return Vec2::ZERO;
    }
    let index = frame % samples.max(1) + 1;
    Vec2::new(radical_inverse(index, 2), radical_inverse(index, 3)) - 0.5
}

/// The camera as one TAA frame reprojects from and to.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TemporalView {
    /// World to clip space, without the jitter.
    pub view_projection: Mat4,
    /// Eye position.
    pub position: Vec3,
    /// The direction it looks (depths are measured along it).
    pub direction: Vec3,
}

/// What one TAA frame needs: its jitter, the camera now and a frame ago, and the history's age.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TemporalFrame {
    /// This frame's sub-pixel offset of the projection, in pixels (x right, y down).
    pub jitter: Vec2,
    /// The camera now (its projection unjittered).
    pub current: TemporalView,
    /// The camera of the frame the history holds (the current one after a reset).
    pub previous: TemporalView,
    /// Frames accumulated in the history before this one (0: reset, the history is dropped).
    pub accumulated: u32,
    /// The parameters, within their limits.
    pub settings: TemporalAntiAliasing,
    /// Counts every TAA frame, never reset: the seed of per-frame noise (the jittered march).
    pub frame_index: u32,
}

/// What makes a history belong to the frames that follow it: a change of any is a reset.
#[derive(Clone, Copy, Debug, PartialEq)]
struct HistoryOwner {
    target: u64,
    camera: hecs::Entity,
    projection: crate::Projection,
    settings: TemporalAntiAliasing,
}

/// The CPU side of temporal anti-aliasing from one frame to the next: the previous camera, the
/// history's age, the jitter's frame. A resource of the render plugin.
#[derive(Debug, Default)]
pub struct TemporalHistory {
    owner: Option<HistoryOwner>,
    previous: Option<TemporalView>,
    accumulated: u32,
    frame_index: u32,
    reset_requested: bool,
    warnings: ClampWarnings<TemporalAntiAliasing>,
}

impl TemporalHistory {
    /// Drops the history at the next frame: call it on a camera cut, where the last frame's
    /// pixels say nothing about the next one's.
    pub fn reset(&mut self) {
        self.reset_requested = true;
    }

    /// Frames accumulated in the history of the last TAA frame, before it (0: it was reset).
    pub fn accumulated(&self) -> u32 {
        self.accumulated.saturating_sub(1)
    }

    /// The next TAA frame of `camera` (with `projection`) seeing `current` into target
    /// `target`, with `settings` (clamped here, with one warning per new out-of-range value).
    pub(crate) fn next_frame(
        &mut self,
        target: u64,
        camera: hecs::Entity,
        projection: crate::Projection,
        current: TemporalView,
        settings: &TemporalAntiAliasing,
    ) -> TemporalFrame {
        let settings = self.warnings.sanitized("temporal anti-aliasing", settings);
        let owner = HistoryOwner {
            target,
            camera,
            projection,
            settings,
        };
        if self.owner != Some(owner) || self.reset_requested {
            self.accumulated = 0;
            self.previous = None;
        }
        self.owner = Some(owner);
        self.reset_requested = false;
        let frame = TemporalFrame {
            jitter: jitter_offset(self.accumulated, settings.jitter_samples),
            current,
            previous: self.previous.unwrap_or(current),
            accumulated: self.accumulated,
            settings,
            frame_index: self.frame_index,
        };
        self.previous = Some(current);
        self.accumulated = self.accumulated.saturating_add(1);
        self.frame_index = self.frame_index.wrapping_add(1);
        frame
    }

    /// A frame without TAA: the next TAA frame starts a new history.
    pub(crate) fn skip(&mut self) {
        self.owner = None;
        self.previous = None;
        self.accumulated = 0;
    }
}

/// `projection` moved by `jitter` pixels (x right, y down) on a target of `(width, height)`:
/// the clip-space translation that shifts every projected point alike, perspective or not.
pub fn jittered(projection: Mat4, jitter: Vec2, (width, height): (u32, u32)) -> Mat4 {
    let ndc = Vec2::new(
        2.0 * jitter.x / width.max(1) as f32,
        -2.0 * jitter.y / height.max(1) as f32,
    );
    Mat4::from_translation(ndc.extend(0.0)) * projection
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_kind_scales_texture_footprints_by_its_own_mip_bias() {
        let taa = TemporalAntiAliasing::default();
        assert_eq!(AntiAliasing::Off.texture_footprint_scale(None), 1.0);
        assert_eq!(AntiAliasing::Fxaa.texture_footprint_scale(None), 0.5);
        assert_eq!(AntiAliasing::Taa.texture_footprint_scale(Some(taa)), 0.25);
        // TAA without a history (no camera to jitter) samples as without anti-aliasing.
        assert_eq!(AntiAliasing::Taa.texture_footprint_scale(None), 1.0);
    }

    #[test]
    fn the_jitter_covers_the_pixel_evenly_and_repeats() {
        let offsets: Vec<Vec2> = (0..16).map(|frame| jitter_offset(frame, 16)).collect();
        assert_eq!(jitter_offset(16, 16), offsets[0]);
        assert!(offsets.iter().all(|o| o.abs().max_element() < 0.5));
        let mean = offsets.iter().copied().sum::<Vec2>() / 16.0;
        assert!(mean.length() < 0.05, "{mean}");
        // Each quarter of the pixel holds four of the sixteen.
        for (sx, sy) in [(-1.0, -1.0), (-1.0, 1.0), (1.0, -1.0), (1.0, 1.0)] {
            let count = offsets
                .iter()
                .filter(|o| o.x * sx > 0.0 && o.y * sy > 0.0)
                .count();
            assert!((3..=5).contains(&count), "{count} in quarter ({sx}, {sy})");
        }
    }

    #[test]
    fn out_of_range_settings_are_named_and_clamped() {
        let wild = TemporalAntiAliasing {
            current_weight: 5.0,
            clip_gamma: f32::NAN,
            jitter_samples: 0,
            depth_tolerance: 0.5,
            mip_bias: 1.0,
            still_weight: 0.02,
        };
        let problems = wild.problems();
        assert_eq!(problems.len(), 4, "{problems:?}");
        assert_eq!(
            problems[0].to_string(),
            "current_weight is 5 but must be at most 1"
        );
        let clean = wild.sanitized();
        assert_eq!(clean.current_weight, 1.0);
        assert_eq!(clean.clip_gamma, TemporalAntiAliasing::default().clip_gamma);
        assert_eq!(clean.jitter_samples, 1);
        assert_eq!(clean.mip_bias, 0.0);
        assert!(clean.problems().is_empty());
    }

    #[test]
    fn a_new_target_camera_or_reset_drops_the_history() {
        let mut world = hecs::World::new();
        let (a, b) = (world.spawn(()), world.spawn(()));
        let view = TemporalView {
            view_projection: Mat4::IDENTITY,
            position: Vec3::ZERO,
            direction: Vec3::NEG_Z,
        };
        let projection = crate::Camera::default().projection;
        let settings = TemporalAntiAliasing::default();
        let mut history = TemporalHistory::default();
        let ages: Vec<u32> = [(1, a), (1, a), (1, a), (2, a), (2, a), (2, b)]
            .into_iter()
            .map(|(target, camera)| {
                history
                    .next_frame(target, camera, projection, view, &settings)
                    .accumulated
            })
            .collect();
        assert_eq!(ages, [0, 1, 2, 0, 1, 0]);
        history.reset();
        let frame = history.next_frame(2, b, projection, view, &settings);
        assert_eq!(frame.accumulated, 0);
        history.skip();
        let frame = history.next_frame(2, b, projection, view, &settings);
        assert_eq!(frame.accumulated, 0);
    }

    #[test]
    fn the_jitter_moves_projected_points_by_that_many_pixels() {
        let projection = crate::Camera::default().projection.matrix(2.0);
        let moved = jittered(projection, Vec2::new(0.25, -0.5), (200, 100));
        let point = glam::Vec4::new(0.3, -0.2, -5.0, 1.0);
        let (a, b) = (projection * point, moved * point);
        let pixels = |clip: glam::Vec4| Vec2::new(clip.x / clip.w * 100.0, -clip.y / clip.w * 50.0);
        let shift = pixels(b) - pixels(a);
        assert!((shift - Vec2::new(0.25, -0.5)).length() < 1e-4, "{shift}");
    }
}
