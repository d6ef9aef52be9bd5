//! The parallax material's render pipelines, one per combination of method, shadow mode,
//! lighting model, debug view and depth offset. `pom.wgsl` reads those as pipeline-overridable
//! constants, so each pipeline holds only its own code path: on the H100 the single pipeline
//! that branched on them per pixel took 27 % longer on POM without shadows and 52 % longer on
//! normal mapping (sandbox/BENCHMARKS.md).

use std::collections::HashMap;

use super::gpu::{debug_code, lighting_code, method_code, shadow_code};
use super::material::ParallaxOcclusionMaterial;
use crate::render::mesh_pipeline;

/// What one parallax pipeline is compiled for.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct PomPipelineKey {
    /// `METHOD` in pom.wgsl.
    pub method: u32,
    /// `SHADOW_MODE`.
    pub shadows: u32,
    /// `LIGHTING_MODEL`.
    pub lighting: u32,
    /// `DEBUG_VIEW`.
    pub debug_view: u32,
    /// Whether the fragment shader writes the displaced depth (`fs_main_depth_offset`).
    pub depth_offset: bool,
}

impl PomPipelineKey {
    /// The pipeline a (sanitized) material draws with.
    pub fn of(material: &ParallaxOcclusionMaterial) -> Self {
        Self {
            method: method_code(material.method).0,
            shadows: shadow_code(material.shadows),
            lighting: lighting_code(material.lighting),
            debug_view: debug_code(material.debug_view),
            depth_offset: material.depth_offset,
        }
    }

    /// The same pipeline with the march compiled out (method: normal mapping), for draws on
    /// which every pixel is past the LOD threshold: same image, less work.
    pub fn normal_mapping(self) -> Self {
        Self {
            method: method_code(super::ParallaxMethod::NormalMapping).0,
            ..self
        }
    }

    fn constants(&self) -> [(&'static str, f64); 4] {
        [
            ("METHOD", f64::from(self.method)),
            ("SHADOW_MODE", f64::from(self.shadows)),
            ("LIGHTING_MODEL", f64::from(self.lighting)),
            ("DEBUG_VIEW", f64::from(self.debug_view)),
        ]
    }
}

/// The compiled `pom.wgsl` and every pipeline made from it so far, created on first use.
#[derive(Debug)]
pub struct PomPipelines {
    shader: wgpu::ShaderModule,
    layout: wgpu::PipelineLayout,
    color_format: wgpu::TextureFormat,
    pipelines: HashMap<PomPipelineKey, wgpu::RenderPipeline>,
}

impl PomPipelines {
    /// No pipelines yet; they will come from `shader` with `layout`, for targets of
    /// `color_format`.
    pub fn new(
        shader: wgpu::ShaderModule,
        layout: wgpu::PipelineLayout,
        color_format: wgpu::TextureFormat,
    ) -> Self {
        Self {
            shader,
            layout,
            color_format,
            pipelines: HashMap::new(),
        }
    }

    /// Compiles the pipeline for `key` unless it exists (a first use costs one pipeline
    /// compile, a few milliseconds, once).
    pub fn ensure(&mut self, device: &wgpu::Device, key: PomPipelineKey) {
        if !self.pipelines.contains_key(&key) {
            let pipeline = self.build(device, key);
            self.pipelines.insert(key, pipeline);
        }
    }

    /// The pipeline for `key`, once [`PomPipelines::ensure`]d.
    pub fn get(&self, key: &PomPipelineKey) -> Option<&wgpu::RenderPipeline> {
        self.pipelines.get(key)
    }

    /// Every pipeline in use rebuilt from `shader` (a recompiled `pom.wgsl`), for shader hot
    /// reload: create it inside an error scope, then swap it in.
    pub fn rebuilt(&self, device: &wgpu::Device, shader: wgpu::ShaderModule) -> Self {
        let mut rebuilt = Self::new(shader, self.layout.clone(), self.color_format);
        // At least the default pipeline, so a broken shader is caught before anything uses it.
        let default_key = PomPipelineKey::of(&ParallaxOcclusionMaterial::default());
        for key in self.pipelines.keys().copied().chain([default_key]) {
            rebuilt.ensure(device, key);
        }
        rebuilt
    }

    fn build(&self, device: &wgpu::Device, key: PomPipelineKey) -> wgpu::RenderPipeline {
        let (label, entry_point) = if key.depth_offset {
            ("parallax depth-offset pipeline", "fs_main_depth_offset")
        } else {
            ("parallax pipeline", "fs_main")
        };
        mesh_pipeline(
            device,
            label,
            &self.layout,
            &self.shader,
            entry_point,
            &key.constants(),
            self.color_format,
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{DebugView, LightingModel, ParallaxMethod, ShadowMode};

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
        ];
        let mut keys: Vec<PomPipelineKey> = variants.iter().map(PomPipelineKey::of).collect();
        keys.push(key);
        keys.sort();
        keys.dedup();
        assert_eq!(keys.len(), 6, "{keys:?}");
        // Parameters that are not modes share a pipeline.
        let tuned = ParallaxOcclusionMaterial {
            height_scale: 0.2,
            max_samples: 99,
            ..base
        };
        assert_eq!(PomPipelineKey::of(&tuned), key);
    }
}
