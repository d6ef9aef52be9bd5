//! The material as the shader reads it: one `PomUniform` per draw, laid out as in `pom.wgsl`:
//! the parameters as declared (`PomParams`, generated with its WGSL from the declarations) and
//! the facts of the height texture as bound. The modes that pick code paths, and the height's
//! channel and convention, are pipeline constants: see `pipelines.rs`.

use bytemuck::{Pod, Zeroable};

use super::material::{ParallaxOcclusionMaterial, PomParams};
use crate::material::TextureFacts;

/// Per-draw data of a parallax material.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct PomUniform {
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
}

crate::wgsl_layout!(PomUniform {
    params,
    height_texture_width,
    height_texture_height,
    height_mip_levels,
    has_height_map
});

impl PomUniform {
    /// Packs a sanitized material with the height texture as bound (`None`: no height texture,
    /// a 1×1 stand-in).
    pub fn new(material: &ParallaxOcclusionMaterial, height: Option<TextureFacts>) -> Self {
        let height = height.unwrap_or(TextureFacts {
            width: 1,
            height: 1,
            mip_levels: 1,
        });
        Self {
            params: material.gpu_params(),
            height_texture_width: height.width as f32,
            height_texture_height: height.height as f32,
            height_mip_levels: height.mip_levels as f32,
            has_height_map: u32::from(material.height_map.is_some()),
        }
    }
}
