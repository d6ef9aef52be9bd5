//! What picks a parallax pipeline: method, shadow mode, lighting model, debug view, depth
//! offset, and the height's channel and convention. `pom.wgsl` reads all but depth offset (an
//! entry point) and double-sidedness (culling) as pipeline-overridable constants, so each
//! pipeline holds only its own code path: on the H100 the single pipeline that branched on them
//! per pixel took 27 % longer on POM without shadows and 52 % longer on normal mapping; on the
//! H200, folding the channel pick out of every height sample (with a multiplication for the
//! division per step) took forward POM from 11.14 / 15.18 / 16.69 to 10.59 / 13.85 / 15.41 ms
//! (sandbox/BENCHMARKS.md).

use super::material::{
    DebugView, HeightConvention, HeightSource, ParallaxMethod, ParallaxOcclusionMaterial,
    ShadowMode,
};
use crate::LightingModel;
use crate::material::{Choice, ShaderEntry};

/// What one parallax pipeline is compiled for.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct PomPipelineKey {
    /// `METHOD` in pom.wgsl.
    pub method: ParallaxMethod,
    /// `SHADOW_MODE`.
    pub shadows: ShadowMode,
    /// `LIGHTING_MODEL`.
    pub lighting: LightingModel,
    /// `DEBUG_VIEW`.
    pub debug_view: DebugView,
    /// Whether the fragment shader writes the displaced depth (`fs_main_depth_offset`).
    pub depth_offset: bool,
    /// Both sides drawn (no culling).
    pub double_sided: bool,
    /// `HEIGHT_CHANNEL`: the height's channel (0 = red, 3 = alpha).
    pub height_channel: u8,
    /// `HEIGHT_IS_DEPTH`: white is deepest.
    pub height_is_depth: bool,
}

impl PomPipelineKey {
    /// The pipeline a material draws with.
    pub fn of(material: &ParallaxOcclusionMaterial) -> Self {
        Self {
            method: material.method,
            shadows: material.shadows,
            lighting: material.lighting,
            debug_view: material.debug_view,
            depth_offset: material.depth_offset,
            double_sided: material.double_sided,
            height_channel: material
                .height_map
                .as_ref()
                .map_or(0, HeightSource::channel),
            height_is_depth: material.height_convention == HeightConvention::Depth,
        }
    }

    /// The same pipeline with the march compiled out (method: normal mapping), for draws on
    /// which every pixel is past the LOD threshold: same image, less work.
    pub fn normal_mapping(self) -> Self {
        Self {
            method: ParallaxMethod::NormalMapping,
            ..self
        }
    }

    /// The fragment entry point and constants of this pipeline in a frame without prepass.
    pub fn fragment(self) -> ShaderEntry {
        self.variant(if self.depth_offset {
            "fs_main_depth_offset"
        } else {
            "fs_main"
        })
    }

    /// The prepass's fragment stage: only a depth-offset material needs one (it writes the
    /// displaced depth); the others write the rasterized depth without a fragment shader.
    pub fn prepass_fragment(self) -> Option<ShaderEntry> {
        self.depth_offset
            .then(|| self.variant("fs_prepass_depth_offset"))
    }

    /// The shadow map's fragment stage: the relief's depth seen from the light (the march
    /// along the light's view ray), except where only normal mapping runs (the polygon's).
    pub fn shadow_fragment(self) -> Option<ShaderEntry> {
        (self.method != ParallaxMethod::NormalMapping).then(|| {
            let mut variant = self.variant("fs_prepass_depth_offset");
            variant.constants.push(("SHADOW_CASTER", 1.0));
            variant
        })
    }

    /// The opaque phase's fragment stage after a prepass.
    pub fn fragment_after_prepass(self) -> ShaderEntry {
        self.variant(if self.depth_offset {
            "fs_main_after_depth_prepass"
        } else {
            "fs_main"
        })
    }

    /// The visibility pass's fragment stage (deferred path): the core's, or with depth offset
    /// the one that also writes the displaced depth.
    pub fn visibility_fragment(self) -> ShaderEntry {
        if self.depth_offset {
            self.variant("fs_visibility_depth_offset")
        } else {
            ShaderEntry::entry("fs_visibility")
        }
    }

    /// The compute resolve that marches and shades this pipeline's pixels on the deferred path.
    pub fn deferred_resolve(self) -> ShaderEntry {
        self.variant("cs_resolve")
    }

    fn variant(self, entry_point: &'static str) -> ShaderEntry {
        ShaderEntry {
            entry_point,
            constants: vec![
                ("METHOD", f64::from(self.method.code())),
                ("SHADOW_MODE", f64::from(self.shadows.code())),
                ("LIGHTING_MODEL", f64::from(self.lighting.code())),
                ("DEBUG_VIEW", f64::from(self.debug_view.code())),
                ("HEIGHT_CHANNEL", f64::from(self.height_channel)),
                ("HEIGHT_IS_DEPTH", f64::from(u8::from(self.height_is_depth))),
            ],
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_mode_of_the_material_picks_its_own_pipeline() {
        let base = ParallaxOcclusionMaterial::default();
        let key = PomPipelineKey::of(&base);
        let variants = [
            ParallaxOcclusionMaterial {
                method: ParallaxMethod::Steep,
                ..base.clone()
            },
            ParallaxOcclusionMaterial {
                shadows: ShadowMode::Hard,
                ..base.clone()
            },
            ParallaxOcclusionMaterial {
                lighting: LightingModel::CookTorrance,
                ..base.clone()
            },
            ParallaxOcclusionMaterial {
                debug_view: DebugView::Samples,
                ..base.clone()
            },
            ParallaxOcclusionMaterial {
                depth_offset: true,
                ..base.clone()
            },
            ParallaxOcclusionMaterial {
                double_sided: true,
                ..base.clone()
            },
            ParallaxOcclusionMaterial {
                height_map: Some(HeightSource::NormalMapAlpha),
                ..base.clone()
            },
            ParallaxOcclusionMaterial {
                height_convention: HeightConvention::Depth,
                ..base.clone()
            },
        ];
        let mut keys: Vec<PomPipelineKey> = variants.iter().map(PomPipelineKey::of).collect();
        keys.push(key);
        keys.sort();
        keys.dedup();
        assert_eq!(keys.len(), 9, "{keys:?}");
        // Parameters that are not modes share a pipeline.
        let tuned = ParallaxOcclusionMaterial {
            height_scale: 0.2,
            max_samples: 99,
            ..base
        };
        assert_eq!(PomPipelineKey::of(&tuned), key);
    }
}
