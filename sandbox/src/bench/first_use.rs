//! The frame that first uses a pipeline variant: the plane settles on POM with soft shadows,
//! then switches to MaxMip with hard shadows, whose pipelines are compiled in that frame. Wall
//! times (the frame's update and the GPU finishing it), since a compile stalls the CPU, not
//! the GPU: the settled frames before, the first frame of the new variant, the frames after.

use anyhow::Result;
use pom::{ParallaxMethod, ShadowMode};

use super::{Median, Runner};

impl Runner<'_> {
    /// Times the first use of MaxMip with hard shadows at `size`, and its ratio to the median
    /// settled frame before it.
    pub(super) fn first_use(&mut self, size: (u32, u32)) -> Result<()> {
        let place = (size, 1.0);
        let view = self.view;
        let mut scene = self.scene(size, &view)?;
        let before = self.with_modes(ParallaxMethod::Occlusion, ShadowMode::Soft);
        let after = self.with_modes(ParallaxMethod::MaxMip, ShadowMode::Hard);
        Self::configure(&mut scene, &before);
        for _ in 0..self.warmup.frames.max(3) {
            scene.wall_frame_ms()?;
        }
        let frames = |scene: &mut super::BenchScene| -> Result<Vec<f64>> {
            (0..self.frames).map(|_| scene.wall_frame_ms()).collect()
        };
        let settled = frames(&mut scene)?;
        Self::configure(&mut scene, &after);
        let first = scene.wall_frame_ms()?;
        let following = frames(&mut scene)?;
        let path = scene.path_ran();
        let record = |runner: &mut Self, material, variant: &str, times: &[f64]| {
            let row = (path, "frame (wall)", variant.to_owned());
            runner.record("first_use", place, material, row, times)
        };
        let settled: Median = record(self, &before, "settled, before", &settled)?;
        let first: Median = record(self, &after, "first frame of the variant", &[first])?;
        record(self, &after, "settled, after", &following)?;
        self.ratio(
            "first use of maxmip + hard shadows / settled frame".to_owned(),
            size,
            first,
            settled,
        );
        Ok(())
    }
}
