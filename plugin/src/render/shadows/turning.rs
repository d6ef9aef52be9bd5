//! Cascades that follow a turning sun in turns. While the camera and a sun's shadow settings
//! stay and only the sun turns, one cascade a frame is fitted to the sun's new direction; the
//! others keep the view they were drawn with (so kept.rs keeps their maps, and receivers read
//! each map with the view it was drawn with). A cascade lags the sun by at most
//! `DIRECTIONAL_CASCADES - 1` frames and [`LAG_LIMIT_RADIANS`]: past that it follows at once,
//! as every cascade does where the camera moved or the sun jumped.

use std::collections::HashMap;

use glam::Vec3;

use super::views::CascadeCamera;
use crate::render::ShadowViewPlan;
use crate::{DIRECTIONAL_CASCADES, LightShadows};

/// How far a kept cascade's light direction may lag the sun's: a tenth of a degree a frame
/// (6° a second at 60 frames a second, a day in a minute) stays within it over the cascades'
/// turns.
pub(super) const LAG_LIMIT_RADIANS: f32 = 0.5 * std::f32::consts::PI / 180.0;

/// One sun's cascades as last planned, and what they were fitted to.
#[derive(Debug)]
struct SunCascades {
    camera: CascadeCamera,
    settings: LightShadows,
    views: [ShadowViewPlan; DIRECTIONAL_CASCADES],
    /// The cascade whose turn it is to follow the sun.
    next: usize,
    /// The frame that last planned them (suns gone since are forgotten).
    frame: u64,
}

/// Every shadowed sun's cascades, by light entity. The shadows plugin's Extract state.
#[derive(Debug, Default)]
pub(super) struct TurningSuns {
    suns: HashMap<hecs::Entity, SunCascades>,
    frame: u64,
}

impl TurningSuns {
    /// Starts a frame's planning.
    pub(super) fn begin_frame(&mut self) {
        self.frame += 1;
    }

    /// The cascades sun `light` uses this frame, given the ones freshly fitted to `camera`:
    /// all of them where the camera or the settings changed, else the kept ones with the
    /// cascade whose turn it is and those lagging past the limit replaced.
    pub(super) fn follow(
        &mut self,
        light: hecs::Entity,
        (camera, settings): (&CascadeCamera, &LightShadows),
        fresh: [ShadowViewPlan; DIRECTIONAL_CASCADES],
    ) -> [ShadowViewPlan; DIRECTIONAL_CASCADES] {
        let frame = self.frame;
        let sun = self.suns.entry(light).or_insert_with(|| SunCascades {
            camera: *camera,
            settings: *settings,
            views: fresh,
            next: 0,
            frame,
        });
        sun.frame = frame;
        if sun.camera != *camera || sun.settings != *settings {
            (sun.camera, sun.settings, sun.views) = (*camera, *settings, fresh);
            return fresh;
        }
        for (index, (kept, fresh)) in sun.views.iter_mut().zip(fresh).enumerate() {
            // A NaN lag (a non-finite transform kept or now) follows at once.
            let lag = lag_radians(kept.forward, fresh.forward);
            let lags = lag.is_nan() || lag > LAG_LIMIT_RADIANS;
            if index == sun.next || lags {
                *kept = fresh;
            }
        }
        sun.next = (sun.next + 1) % DIRECTIONAL_CASCADES;
        sun.views
    }

    /// Forgets the suns this frame did not plan.
    pub(super) fn end_frame(&mut self) {
        let frame = self.frame;
        self.suns.retain(|_, sun| sun.frame == frame);
    }
}

/// The angle between two unit light directions.
fn lag_radians(kept: Vec3, now: Vec3) -> f32 {
    kept.dot(now).clamp(-1.0, 1.0).acos()
}

#[cfg(test)]
mod tests {
    use super::super::views::directional_views;
    use super::super::views::tests::camera;
    use super::*;

    /// The sun `turn` radians about +Z from straight down and a little sideways.
    fn sun(turn: f32) -> Vec3 {
        glam::Quat::from_rotation_z(turn) * Vec3::new(0.3, -1.0, 0.2).normalize()
    }

    #[test]
    fn a_slowly_turning_sun_refits_one_cascade_a_frame_in_turn() {
        let (camera, settings) = (camera(), LightShadows::default());
        let light = hecs::World::new().spawn(());
        let mut suns = TurningSuns::default();
        let step = 0.1_f32.to_radians();
        let mut used = Vec::new();
        for frame in 0..7 {
            suns.begin_frame();
            let fresh = directional_views(&camera, sun(step * frame as f32), &settings);
            used.push((fresh, suns.follow(light, (&camera, &settings), fresh)));
            suns.end_frame();
        }
        assert_eq!(used[0].0, used[0].1, "the first frame fits every cascade");
        for (frame, (fresh, views)) in used.iter().enumerate().skip(1) {
            let refit: Vec<usize> = (0..DIRECTIONAL_CASCADES)
                .filter(|&i| views[i] == fresh[i])
                .collect();
            assert_eq!(refit, [frame % DIRECTIONAL_CASCADES], "frame {frame}");
            for (kept, fresh) in views.iter().zip(fresh) {
                assert!(lag_radians(kept.forward, fresh.forward) <= LAG_LIMIT_RADIANS);
            }
        }
    }

    #[test]
    fn a_jump_of_the_sun_or_a_moved_camera_refits_every_cascade() {
        let (camera, settings) = (camera(), LightShadows::default());
        let light = hecs::World::new().spawn(());
        let mut suns = TurningSuns::default();
        let mut plan = |camera: &CascadeCamera, turn: f32| {
            suns.begin_frame();
            let fresh = directional_views(camera, sun(turn), &settings);
            let views = suns.follow(light, (camera, &settings), fresh);
            suns.end_frame();
            (fresh, views)
        };
        plan(&camera, 0.0);
        let (fresh, views) = plan(&camera, 2.0_f32.to_radians());
        assert_eq!(fresh, views, "the sun jumped");
        let moved = CascadeCamera {
            position: camera.position + Vec3::X * 0.01,
            ..camera
        };
        let (fresh, views) = plan(&moved, 2.05_f32.to_radians());
        assert_eq!(fresh, views, "the camera moved");
    }
}
