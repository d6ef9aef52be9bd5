//! A sun's cascades kept while they still serve: a cascade is fitted again (and so drawn
//! again, kept.rs) only where the camera left it (its slice of the view no longer inside the
//! map with the filter's margin, or the casters towards the light outside its depth range) or
//! the sun turned. A turning sun refits one cascade a frame, in turn; the others keep the view
//! they were drawn with, which receivers read them with. A cascade lags the sun by at most
//! `DIRECTIONAL_CASCADES - 1` frames and [`LAG_LIMIT_RADIANS`]: past that it follows at once,
//! as every cascade does where the camera's lens or the shadow settings changed.

use std::collections::HashMap;

use glam::Vec3;

use super::views::{CascadeCamera, cascade_covers};
use crate::render::ShadowViewPlan;
use crate::{DIRECTIONAL_CASCADES, LightShadows, Projection};

/// How far a kept cascade's light direction may lag the sun's: a tenth of a degree a frame
/// (6° a second at 60 frames a second, a day in a minute) stays within it over the cascades'
/// turns.
pub(super) const LAG_LIMIT_RADIANS: f32 = 0.5 * std::f32::consts::PI / 180.0;

/// One sun's cascades as last planned, and what they were fitted with.
#[derive(Debug)]
struct SunCascades {
    /// The camera's projection and aspect (a cascade's size follows them).
    lens: (Projection, f32),
    settings: LightShadows,
    views: [ShadowViewPlan; DIRECTIONAL_CASCADES],
    /// The cascade whose turn it is to follow the sun.
    next: usize,
    /// The frame that last planned them (suns gone since are forgotten).
    frame: u64,
}

/// Every shadowed sun's cascades, by light entity. The shadows plugin's Extract state.
#[derive(Debug, Default)]
pub(super) struct KeptCascades {
    suns: HashMap<hecs::Entity, SunCascades>,
    frame: u64,
}

impl KeptCascades {
    /// Starts a frame's planning.
    pub(super) fn begin_frame(&mut self) {
        self.frame += 1;
    }

    /// The cascades sun `light` uses this frame, given the ones freshly fitted to `camera`:
    /// all of them where the lens or the settings changed, else the kept ones, with those
    /// the camera left, the one whose turn it is where the sun turned, and those lagging the
    /// sun past the limit replaced.
    pub(super) fn follow(
        &mut self,
        light: hecs::Entity,
        (camera, settings): (&CascadeCamera, &LightShadows),
        fresh: [ShadowViewPlan; DIRECTIONAL_CASCADES],
    ) -> [ShadowViewPlan; DIRECTIONAL_CASCADES] {
        let frame = self.frame;
        let lens = (camera.projection, camera.aspect);
        let sun = self.suns.entry(light).or_insert_with(|| SunCascades {
            lens,
            settings: *settings,
            views: fresh,
            next: 0,
            frame,
        });
        sun.frame = frame;
        if sun.lens != lens || sun.settings != *settings {
            (sun.lens, sun.settings, sun.views) = (lens, *settings, fresh);
            return fresh;
        }
        for (index, (kept, fresh)) in sun.views.iter_mut().zip(fresh).enumerate() {
            // A NaN lag (a non-finite transform kept or now) follows at once.
            let lag = lag_radians(kept.forward, fresh.forward);
            let lags = lag.is_nan() || lag > LAG_LIMIT_RADIANS;
            let turned = kept.forward != fresh.forward;
            if lags
                || (turned && index == sun.next)
                || !cascade_covers(camera, settings, index, kept)
            {
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
        let mut suns = KeptCascades::default();
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

    /// Plans one frame of `suns` for sun `light` turned by `turn` and seen by `camera`:
    /// (the freshly fitted cascades, the ones used).
    fn plan(
        suns: &mut KeptCascades,
        light: hecs::Entity,
        camera: &CascadeCamera,
        turn: f32,
    ) -> [[ShadowViewPlan; DIRECTIONAL_CASCADES]; 2] {
        let settings = LightShadows::default();
        suns.begin_frame();
        let fresh = directional_views(camera, sun(turn), &settings);
        let views = suns.follow(light, (camera, &settings), fresh);
        suns.end_frame();
        [fresh, views]
    }

    #[test]
    fn a_jump_of_the_sun_or_a_new_lens_refits_every_cascade() {
        let camera = camera();
        let light = hecs::World::new().spawn(());
        let mut suns = KeptCascades::default();
        plan(&mut suns, light, &camera, 0.0);
        let [fresh, views] = plan(&mut suns, light, &camera, 2.0_f32.to_radians());
        assert_eq!(fresh, views, "the sun jumped");
        let wider = CascadeCamera {
            aspect: 2.0,
            ..camera
        };
        let [fresh, views] = plan(&mut suns, light, &wider, 2.0_f32.to_radians());
        assert_eq!(fresh, views, "the lens changed");
    }

    #[test]
    fn a_moving_camera_refits_only_the_cascades_it_leaves() {
        let camera = camera();
        let light = hecs::World::new().spawn(());
        let mut suns = KeptCascades::default();
        let [first, _] = plan(&mut suns, light, &camera, 0.0);
        let nudged = CascadeCamera {
            position: camera.position + Vec3::X * 0.01,
            ..camera
        };
        let [fresh, views] = plan(&mut suns, light, &nudged, 0.0);
        assert_ne!(fresh, first, "the fit follows the camera");
        assert_eq!(views, first, "a nudge leaves every cascade serving");
        let walked = CascadeCamera {
            position: camera.position + Vec3::X * 8.0,
            ..camera
        };
        let [fresh, views] = plan(&mut suns, light, &walked, 0.0);
        assert_eq!(views[0], fresh[0], "the nearest cascade is left behind");
        assert_eq!(views[2], first[2], "the farthest still serves");
        let settings = LightShadows::default();
        for (index, view) in views.iter().enumerate() {
            assert!(cascade_covers(&walked, &settings, index, view), "{index}");
        }
    }
}
