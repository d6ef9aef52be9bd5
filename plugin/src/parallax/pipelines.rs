//! What picks a parallax pipeline: method, shadow mode, lighting model, debug view, depth
//! offset, silhouette, and the height's channel and convention. `pom.wgsl` reads all but
//! double-sidedness (culling) as pipeline-overridable constants (depth offset and silhouette
//! also pick the entry points that march for their depth), so each
//! pipeline holds only its own code path: a single pipeline that branched on them per pixel was
//! markedly slower on POM and slower still on normal mapping, and folding the channel pick out
//! of every height sample (with a multiplication for the division per step) made forward POM
//! faster again (sandbox/BENCHMARKS.md, "What the numbers mean": specialized pipelines).

use super::material::{
    DebugView, ParallaxMethod, ParallaxOcclusionMaterial, ShadowMode, Silhouette, TextureMapping,
};
use crate::material::{Choice, ShaderEntry};
use crate::{HeightConvention, LightingModel};

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
    /// `DEPTH_OFFSET`: whether the depth passes write the displaced depth.
    pub depth_offset: bool,
    /// `SILHOUETTE`: whether pixels where the view ray leaves the surface are clipped.
    pub silhouette: Silhouette,
    /// Both sides drawn (no culling).
    pub double_sided: bool,
    /// `HEIGHT_CHANNEL`: the height's channel (0 = red, 3 = alpha).
    pub height_channel: u8,
    /// `HEIGHT_IS_DEPTH`: white is deepest.
    pub height_is_depth: bool,
    /// `LAYERED`: the height is the blend of a layered material's layers.
    pub layered: bool,
    /// `TRIPLANAR`: the maps are projected along the world axes and the march runs in world
    /// space.
    pub triplanar: bool,
}

impl PomPipelineKey {
    /// The pipeline a material draws with.
    pub fn of(material: &ParallaxOcclusionMaterial) -> Self {
        let layered = material.layers.is_some();
        // Layers are laid out in texture coordinates: they draw with uv mapping.
        let triplanar = material.mapping == TextureMapping::Triplanar && !layered;
        Self {
            // MaxMip is exact for one bilinear height field; a blend of layers or projections
            // is not bilinear between texels, so they march with occlusion mapping.
            method: if (layered || triplanar) && material.method == ParallaxMethod::MaxMip {
                ParallaxMethod::Occlusion
            } else {
                material.method
            },
            shadows: material.shadows,
            lighting: material.lighting,
            debug_view: material.debug_view,
            depth_offset: material.depth_offset,
            silhouette: material.silhouette,
            double_sided: material.double_sided,
            // Packed layer heights are in every channel, with white the top.
            height_channel: material
                .height_map
                .as_ref()
                .filter(|_| !layered)
                .map_or(0, |source| source.channel().index() as u8),
            height_is_depth: !layered && material.height_convention == HeightConvention::Depth,
            layered,
            triplanar,
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

    /// Whether the depth passes march: for the displaced depth, or for the coverage a
    /// silhouette clips. The others write the rasterized depth without a fragment shader.
    fn marches_for_depth(self) -> bool {
        self.depth_offset || self.silhouette != Silhouette::Off
    }

    /// The fragment entry point and constants of this pipeline in a frame without prepass.
    pub fn fragment(self) -> ShaderEntry {
        self.variant(if self.marches_for_depth() {
            "fs_main_marched_depth"
        } else {
            "fs_main"
        })
    }

    /// The prepass's fragment stage, where it marches: for the displaced depth, or for the
    /// coverage alone (the rasterizer then writes the polygon's depth).
    pub fn prepass_fragment(self) -> Option<ShaderEntry> {
        if self.depth_offset {
            Some(self.variant("fs_prepass_marched_depth"))
        } else {
            self.marches_for_depth()
                .then(|| self.variant("fs_prepass_clipped"))
        }
    }

    /// The shadow map's fragment stage: the relief's depth seen from the light (the march
    /// along the light's view ray), except where only normal mapping runs (the polygon's).
    pub fn shadow_fragment(self) -> Option<ShaderEntry> {
        (self.method != ParallaxMethod::NormalMapping).then(|| {
            // A caster's map always holds the relief's depth, whatever the material writes in
            // the camera's passes.
            let caster = Self {
                depth_offset: true,
                ..self
            };
            let mut variant = caster.variant("fs_prepass_marched_depth");
            variant.constants.push(("SHADOW_CASTER", 1.0));
            variant
        })
    }

    /// The opaque phase's fragment stage after a prepass.
    pub fn fragment_after_prepass(self) -> ShaderEntry {
        self.variant(if self.marches_for_depth() {
            "fs_main_after_marched_prepass"
        } else {
            "fs_main"
        })
    }

    /// The visibility pass's fragment stage (deferred path): the core's, or where a
    /// silhouette clips the one that marches for coverage. (With depth offset the pipeline
    /// draws in the candidate pass instead, [`Self::settles_depth_in_resolve`].)
    pub fn visibility_fragment(self) -> ShaderEntry {
        if self.marches_for_depth() && !self.depth_offset {
            self.variant("fs_visibility_clipped")
        } else {
            ShaderEntry::entry("fs_visibility")
        }
    }

    /// The compute resolve that marches and shades this pipeline's pixels on the deferred path
    /// (with depth offset, settling its candidates first).
    pub fn deferred_resolve(self) -> ShaderEntry {
        self.variant(if self.depth_offset {
            "cs_resolve_settling"
        } else {
            "cs_resolve"
        })
    }

    /// Whether the deferred path settles this pipeline's depth in the resolve: with depth
    /// offset, the displaced depth lies behind the polygon, by at most the relief's depth.
    pub fn settles_depth_in_resolve(self) -> bool {
        self.depth_offset
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
                ("DEPTH_OFFSET", f64::from(u8::from(self.depth_offset))),
                ("SILHOUETTE", f64::from(self.silhouette.code())),
                ("LAYERED", f64::from(u8::from(self.layered))),
                ("TRIPLANAR", f64::from(u8::from(self.triplanar))),
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
                silhouette: Silhouette::UvBounds,
                ..base.clone()
            },
            ParallaxOcclusionMaterial {
                double_sided: true,
                ..base.clone()
            },
            ParallaxOcclusionMaterial {
                height_map: Some(crate::HeightSource::NormalMapAlpha),
                ..base.clone()
            },
            ParallaxOcclusionMaterial {
                height_convention: HeightConvention::Depth,
                ..base.clone()
            },
            ParallaxOcclusionMaterial {
                mapping: TextureMapping::Triplanar,
                ..base.clone()
            },
        ];
        let mut keys: Vec<PomPipelineKey> = variants.iter().map(PomPipelineKey::of).collect();
        keys.push(key);
        keys.sort();
        keys.dedup();
        assert_eq!(keys.len(), 11, "{keys:?}");
        // Parameters that are not modes share a pipeline.
        let tuned = ParallaxOcclusionMaterial {
            height_scale: 0.2,
            max_samples: 99,
            ..base
        };
        assert_eq!(PomPipelineKey::of(&tuned), key);
    }
}
