//! The material as the shader reads it: one `PomUniform` per draw, laid out as in `pom.wgsl`:
//! the parameters as declared (`PomParams`, generated with its WGSL from the declarations) and
//! the facts of the height texture as bound, and a layered material's layers. The modes that pick code paths, and the height's
//! channel and convention, are pipeline constants: see `pipelines.rs`.

use bytemuck::{Pod, Zeroable};

use super::LayerWeights;
use super::material::{ParallaxOcclusionMaterial, PomParams};
use crate::material::TextureFacts;

/// Per-draw data of a parallax material.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct PomUniform {
    /// Each layer's repeats across the texture coordinates 0..1 (layered materials; 1 else).
    /// The vectors come first, where their 16-byte alignment needs no padding whatever the
    /// parameters' size.
    pub layer_tiling: [f32; 4],
    /// Each layer's relief depth as a share of the height scale (0 past the last layer).
    pub layer_depth: [f32; 4],
    /// The sanitized parameters.
    pub params: PomParams,
    /// Width of the height texture as bound, in texels (1 without one).
    pub height_texture_width: f32,
    /// Height of the height texture as bound, in texels.
    pub height_texture_height: f32,
    /// Mip levels of the height texture as bound.
    pub height_mip_levels: f32,
    /// 1 when the material has a height map (0: flat, no parallax).
    pub has_height_map: u32,
    /// Layers mixed (0: not a layered material).
    pub layer_count: u32,
    /// 1 when the weights come from the weight map, 0 from the vertex colours.
    pub weights_from_texture: u32,
    /// Width of the weight map as bound, in texels.
    pub weight_texture_width: f32,
    /// Height of the weight map as bound, in texels.
    pub weight_texture_height: f32,
    /// Up to the vectors' 16-byte alignment, as WGSL pads the struct in an array.
    pub padding: [u32; 3],
}

crate::wgsl_layout!(PomUniform {
    layer_tiling,
    layer_depth,
    params,
    height_texture_width,
    height_texture_height,
    height_mip_levels,
    has_height_map,
    layer_count,
    weights_from_texture,
    weight_texture_width,
    weight_texture_height,
    padding
});

impl PomUniform {
    /// Packs a sanitized material with the height texture and the layers' weight map as bound
    /// (`None`: none, a 1×1 stand-in). A layered material's heights are its packed heights,
    /// whose size the march reads as its first layer tiles them across 0..1.
    pub fn new(
        material: &ParallaxOcclusionMaterial,
        height: Option<TextureFacts>,
        weights: Option<TextureFacts>,
    ) -> Self {
        let stand_in = TextureFacts {
            width: 1,
            height: 1,
            mip_levels: 1,
        };
        let (height, weights) = (height.unwrap_or(stand_in), weights.unwrap_or(stand_in));
        let mut uniform = Self {
            params: material.gpu_params(),
            height_texture_width: height.width as f32,
            height_texture_height: height.height as f32,
            height_mip_levels: height.mip_levels as f32,
            has_height_map: u32::from(material.height_map.is_some()),
            layer_tiling: [1.0; 4],
            layer_depth: [0.0; 4],
            layer_count: 0,
            weights_from_texture: 0,
            weight_texture_width: weights.width as f32,
            weight_texture_height: weights.height as f32,
            padding: [0; 3],
        };
        if let Some(layers) = &material.layers {
            for (index, layer) in layers.drawn().iter().enumerate() {
                uniform.layer_tiling[index] = layer.tiling;
                uniform.layer_depth[index] = layer.height_scale;
            }
            uniform.layer_count = layers.drawn().len() as u32;
            uniform.weights_from_texture =
                u32::from(matches!(layers.weights, LayerWeights::Texture(_)));
            uniform.has_height_map = 1;
            uniform.height_texture_width *= uniform.layer_tiling[0];
            uniform.height_texture_height *= uniform.layer_tiling[0];
        }
        uniform
    }
}
