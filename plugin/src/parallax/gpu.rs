//! The material as the shader reads it: one `PomObject` per draw, laid out as in `pom.wgsl`
//! (the modes that pick code paths are pipeline constants instead: see `pipelines.rs`).

use bytemuck::{Pod, Zeroable};
use glam::Mat4;

use super::material::{
    DebugView, HeightConvention, HeightSource, HeightUnits, LightingModel, ParallaxMethod,
    ParallaxOcclusionMaterial, ShadowMode,
};

/// Per-draw transform and material parameters.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct PomObject {
    /// Object to world.
    pub model: [[f32; 4]; 4],
    /// Inverse transpose of `model`.
    pub normal_matrix: [[f32; 4]; 4],
    /// Linear base colour.
    pub base_color: [f32; 4],
    /// x: height scale, y: 1 if world units, z: min samples, w: max samples.
    pub height: [f32; 4],
    /// x: LOD threshold, y: LOD band, z: shadow softening, w: normal strength.
    pub lod: [f32; 4],
    /// x: specular strength, y: shininess, z: roughness, w: metallic.
    pub surface: [f32; 4],
    /// x: height channel, y: 1 for the depth convention, z: relief binary steps.
    pub height_map: [u32; 4],
    /// xy: height texture size, z: model determinant sign, w: mip level count.
    pub texture: [f32; 4],
}

pub(super) fn method_code(method: ParallaxMethod) -> (u32, u32) {
    match method {
        ParallaxMethod::NormalMapping => (0, 0),
        ParallaxMethod::ParallaxOffset => (1, 0),
        ParallaxMethod::Steep => (2, 0),
        ParallaxMethod::Occlusion => (3, 0),
        ParallaxMethod::Relief { binary_steps } => (4, binary_steps),
    }
}

pub(super) fn shadow_code(shadows: ShadowMode) -> u32 {
    match shadows {
        ShadowMode::Off => 0,
        ShadowMode::Hard => 1,
        ShadowMode::Soft => 2,
    }
}

pub(super) fn lighting_code(lighting: LightingModel) -> u32 {
    match lighting {
        LightingModel::Phong => 0,
        LightingModel::BlinnPhong => 1,
        LightingModel::CookTorrance => 2,
    }
}

pub(super) fn debug_code(view: DebugView) -> u32 {
    match view {
        DebugView::None => 0,
        DebugView::Lod => 1,
        DebugView::Mip => 2,
        DebugView::Samples => 3,
        DebugView::Uv => 4,
        DebugView::Shadow => 5,
        DebugView::Normal => 6,
    }
}

impl PomObject {
    /// Packs a sanitized material, its world transform and the size of its height texture
    /// (`(1, 1)` without one).
    pub fn new(
        material: &ParallaxOcclusionMaterial,
        model: Mat4,
        height_texture_size: (u32, u32),
    ) -> Self {
        let (_, binary_steps) = method_code(material.method);
        let determinant = model.determinant();
        let normal_matrix = if determinant.abs() > f32::MIN_POSITIVE {
            model.inverse().transpose()
        } else {
            Mat4::IDENTITY
        };
        let (width, height) = height_texture_size;
        let mip_levels = 32 - width.max(height).max(1).leading_zeros();
        let channel = match material.height_map {
            Some(HeightSource::NormalMapAlpha) => 3,
            _ => 0,
        };
        Self {
            model: model.to_cols_array_2d(),
            normal_matrix: normal_matrix.to_cols_array_2d(),
            base_color: material.base_color.to_array(),
            height: [
                if material.height_map.is_some() {
                    material.height_scale
                } else {
                    0.0
                },
                f32::from(u8::from(material.height_units == HeightUnits::World)),
                material.min_samples as f32,
                material.max_samples as f32,
            ],
            lod: [
                material.lod_threshold,
                material.lod_band,
                material.shadow_softening,
                material.normal_strength,
            ],
            surface: [
                material.specular_strength,
                material.shininess,
                material.roughness,
                material.metallic,
            ],
            height_map: [
                channel,
                u32::from(material.height_convention == HeightConvention::Depth),
                binary_steps,
                0,
            ],
            texture: [
                width as f32,
                height as f32,
                if determinant < 0.0 { -1.0 } else { 1.0 },
                mip_levels as f32,
            ],
        }
    }
}
