//! The material as the shader reads it: one `PomUniform` per draw, laid out as in `pom.wgsl`
//! (the modes that pick code paths are pipeline constants instead: see `pipelines.rs`).

use bytemuck::{Pod, Zeroable};

use super::material::{HeightConvention, HeightSource, HeightUnits, ParallaxOcclusionMaterial};
use crate::material::TextureFacts;

/// Per-draw parameters of a parallax material.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct PomUniform {
    /// Linear base colour.
    pub base_color: [f32; 4],
    /// Depth of the relief (0 without a height map).
    pub height_scale: f32,
    /// 1 when `height_scale` is in world units.
    pub world_units: u32,
    /// Samples looking straight on.
    pub min_samples: u32,
    /// Samples at grazing angles.
    pub max_samples: u32,
    /// Mip level past which only normal mapping runs.
    pub lod_threshold: f32,
    /// Width of the LOD fade band.
    pub lod_band: f32,
    /// Penumbra width of soft shadows.
    pub shadow_softening: f32,
    /// Scales the normal map's tilt.
    pub normal_strength: f32,
    /// Phong / Blinn-Phong highlight weight.
    pub specular_strength: f32,
    /// Phong / Blinn-Phong exponent.
    pub shininess: f32,
    /// Cook-Torrance roughness.
    pub roughness: f32,
    /// Cook-Torrance metalness.
    pub metallic: f32,
    /// Channel of the height texture holding the height: 0 = red, 3 = alpha.
    pub height_channel: u32,
    /// 1 for the depth convention.
    pub depth_convention: u32,
    /// Bisection steps of relief mapping.
    pub relief_binary_steps: u32,
    /// Mip levels of the height texture as bound.
    pub height_mip_levels: f32,
    /// Size of the height texture as bound, in texels.
    pub height_texture_size: [f32; 2],
    /// Keeps the size a multiple of 16 bytes.
    pub _padding: [f32; 2],
}

crate::wgsl_layout!(PomUniform {
    base_color,
    height_scale,
    world_units,
    min_samples,
    max_samples,
    lod_threshold,
    lod_band,
    shadow_softening,
    normal_strength,
    specular_strength,
    shininess,
    roughness,
    metallic,
    height_channel,
    depth_convention,
    relief_binary_steps,
    height_mip_levels,
    height_texture_size,
    _padding
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
            base_color: material.base_color.to_array(),
            height_scale: if material.height_map.is_some() {
                material.height_scale
            } else {
                0.0
            },
            world_units: u32::from(material.height_units == HeightUnits::World),
            min_samples: material.min_samples,
            max_samples: material.max_samples,
            lod_threshold: material.lod_threshold,
            lod_band: material.lod_band,
            shadow_softening: material.shadow_softening,
            normal_strength: material.normal_strength,
            specular_strength: material.specular_strength,
            shininess: material.shininess,
            roughness: material.roughness,
            metallic: material.metallic,
            height_channel: match material.height_map {
                Some(HeightSource::NormalMapAlpha) => 3,
                _ => 0,
            },
            depth_convention: u32::from(material.height_convention == HeightConvention::Depth),
            relief_binary_steps: material.relief_binary_steps,
            height_mip_levels: height.mip_levels as f32,
            height_texture_size: [height.width as f32, height.height as f32],
            _padding: [0.0; 2],
        }
    }
}
