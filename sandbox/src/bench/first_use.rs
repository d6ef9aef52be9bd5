//! The frame that first uses a pipeline variant: the plane settles on POM with soft shadows,
//! then switches to MaxMip with hard shadows, whose pipelines compile then: in that frame
//! (blocking, a headless app's default), or on worker threads while frames draw the
//! material's fallback (background, a window's). Wall times (the frame's update and the GPU
//! finishing it), since a compile stalls the CPU, not the GPU: the settled frames before, the
//! first frame of the new variant, the frames after.

use anyhow::Result;
use pom::{ParallaxMethod, ShadowMode};

use super::scene::{BenchScene, SceneOptions};
use super::{Median, Runner};

impl Runner<'_> {
    /// Times the first use of MaxMip with hard shadows at `size`, compiled blocking and in the
    /// background, and each one's ratio to the median settled frame before it.
    pub(super) fn first_use(&mut self, size: (u32, u32)) -> Result<()> {
        for background in [false, true] {
            let compile = if background { "background" } else { "blocking" };
            let mut scene = BenchScene::new(
                SceneOptions {
                    background_pipelines: background,
                    ..SceneOptions::timed_plane(size, self.path)
                },
                self.textures,
                self.base.clone(),
                &self.view,
            )?;
            let (settled, first) = self.time_first_use(&mut scene, size, compile)?;
            self.ratio(
                format!("first use of maxmip + hard shadows ({compile} compile) / settled frame"),
                size,
                first,
                settled,
            );
        }
        Ok(())
    }

    /// Settles `scene`, switches its variant and records the three cases; returns the median
    /// settled frame and the first frame of the new variant.
    fn time_first_use(
        &mut self,
        scene: &mut BenchScene,
        size: (u32, u32),
        compile: &str,
    ) -> Result<(Median, Median)> {
        let place = (size, 1.0);
        let before = self.with_modes(ParallaxMethod::Occlusion, ShadowMode::Soft);
        let after = self.with_modes(ParallaxMethod::MaxMip, ShadowMode::Hard);
        Self::configure(scene, &before);
        for _ in 0..self.warmup.frames.max(3) {
            scene.wall_frame_ms()?;
        }
        let frames = |scene: &mut BenchScene| -> Result<Vec<f64>> {
            (0..self.frames).map(|_| scene.wall_frame_ms()).collect()
        };
        let settled = frames(scene)?;
        Self::configure(scene, &after);
        let first = scene.wall_frame_ms()?;
        // Frames until the background compiles are in (none where they were blocking).
        let mut waited = 0;
        while scene.compiles_in_flight() > 0 && waited < 1000 {
            scene.wall_frame_ms()?;
            waited += 1;
        }
        let following = frames(scene)?;
        let path = scene.path_ran();
        let record = |runner: &mut Self, material, variant: String, times: &[f64]| {
            let row = (path, "frame (wall)", variant);
            runner.record("first_use", place, material, row, times)
        };
        let settled = record(
            self,
            &before,
            format!("settled, before ({compile})"),
            &settled,
        )?;
        let first = record(
            self,
            &after,
            format!("first frame of the variant ({compile}; {waited} more frames until compiled)"),
            &[first],
        )?;
        record(
            self,
            &after,
            format!("settled, after ({compile})"),
            &following,
        )?;
        Ok((settled, first))
    }
}
