//! The `antialiasing` group: the passes of TAA and the post filter, the jittered march under
//! TAA (with one and three secant steps) against the plain one, and the frame with and without
//! the mip bias of TAA and of the post filter.

use anyhow::Result;
use pom::ParallaxOcclusionMaterial;
use pom::material::Choice;

use super::Runner;

impl Runner<'_> {
    /// The passes of each anti-aliasing (TAA before tonemapping, the post filter after it) on
    /// the base material's plane, and under TAA the jittered march at 16 samples (with one and
    /// with three secant steps) against the plain march at 50, the 50-sample frame without
    /// TAA's mip bias, and the 50-sample frame under the post filter (its mip bias) and off.
    pub(super) fn antialiasing(&mut self, size: (u32, u32)) -> Result<()> {
        let view = self.view;
        let mut scene = self.scene(size, &view)?;
        let material = self.base.clone();
        Self::configure(&mut scene, &material);
        let place = (size, self.view.tiling);
        for (aa, phases) in [
            (pom::AntiAliasing::Off, &["post"][..]),
            (
                pom::AntiAliasing::Fxaa,
                &["post", pom::render::POST_FILTER_PASS][..],
            ),
            (pom::AntiAliasing::Taa, &[pom::render::TAA_PASS, "post"][..]),
        ] {
            scene.set_anti_aliasing(aa, Default::default());
            let times = scene.time_phases(self.warmup, self.frames, phases)?;
            let path = scene.path_ran();
            for (phase, times) in &times {
                let row = (path, *phase, aa.name().to_owned());
                self.record("antialiasing", place, &material, row, times)?;
            }
        }
        scene.set_anti_aliasing(pom::AntiAliasing::Taa, Default::default());
        let mut fifty = None;
        for (samples, jitter, secant_steps) in [(50, false, 1), (16, true, 1), (16, true, 3)] {
            let material = ParallaxOcclusionMaterial {
                max_samples: samples,
                jitter_march: jitter,
                secant_steps,
                ..self.base.clone()
            };
            let variant = format!(
                "taa, {samples} samples{}{}",
                if jitter { ", jittered march" } else { "" },
                if secant_steps > 1 {
                    format!(", {secant_steps} secant steps")
                } else {
                    String::new()
                }
            );
            let ms = self.case_variant(&mut scene, "antialiasing", place, material, variant)?;
            match fifty {
                None => fifty = Some(ms),
                Some(fifty) => {
                    let what = format!(
                        "jittered march: 16 samples, {secant_steps} secant steps / 50 samples, \
                         under TAA"
                    );
                    self.ratio(what, size, ms, fifty);
                }
            }
        }
        // Textures sampled finer under TAA read more texels: the mip bias's cost.
        let unbiased = pom::TemporalAntiAliasing {
            mip_bias: 0.0,
            ..Default::default()
        };
        scene.set_anti_aliasing(pom::AntiAliasing::Taa, unbiased);
        let variant = "taa, 50 samples, mip bias 0".to_owned();
        let ms = self.case_variant(
            &mut scene,
            "antialiasing",
            place,
            self.base.clone(),
            variant,
        )?;
        if let Some(fifty) = fifty {
            let what = "TAA's mip bias: -2 / 0, 50 samples".to_owned();
            self.ratio(what, size, fifty, ms);
        }
        // The post filter samples textures a level finer too (`POST_FILTER_MIP_BIAS`).
        let mut frames = Vec::new();
        for aa in [pom::AntiAliasing::Fxaa, pom::AntiAliasing::Off] {
            scene.set_anti_aliasing(aa, Default::default());
            let variant = format!("{}, 50 samples", aa.name());
            let material = self.base.clone();
            frames.push(self.case_variant(&mut scene, "antialiasing", place, material, variant)?);
        }
        let what = "the post filter's mip bias: -1 / 0, 50 samples".to_owned();
        self.ratio(what, size, frames[0], frames[1]);
        Ok(())
    }
}
