//! Checks a material's uniform against its composed WGSL ([`crate::shader::check_wgsl_layout`]
//! does the comparison).

use crate::shader::{LayoutMismatch, check_wgsl_layout};

/// Checks material `M`'s uniform and the shared per-draw transform against `M`'s composed WGSL.
/// Call it in a test of every material you write.
pub fn check_material_layout<M: super::Material>() -> Result<(), LayoutMismatch> {
    let source = M::shader().source();
    check_wgsl_layout::<M::PerDraw>(&source, M::PER_DRAW_WGSL_NAME)?;
    check_wgsl_layout::<crate::render::MeshTransform>(&source, "MeshTransform")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[repr(C)]
    #[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
    struct Sample {
        color: [f32; 4],
        scale: f32,
        count: u32,
        _padding: [u32; 2],
    }
    crate::wgsl_layout!(Sample {
        color,
        scale,
        count,
        _padding
    });

    #[test]
    fn the_shipped_materials_and_the_frame_match_their_wgsl() {
        assert_eq!(check_material_layout::<crate::LitMaterial>(), Ok(()));
        assert_eq!(
            check_material_layout::<crate::ParallaxOcclusionMaterial>(),
            Ok(())
        );
        let source = crate::lit::LIT_SHADER.source();
        assert_eq!(
            check_wgsl_layout::<crate::render::FrameUniform>(&source, "Frame"),
            Ok(())
        );
        use crate::render::gpu_types::{DirectionalLightGpu, PointLightGpu, ShadowViewGpu};
        assert_eq!(
            check_wgsl_layout::<DirectionalLightGpu>(&source, "DirectionalLight"),
            Ok(())
        );
        assert_eq!(
            check_wgsl_layout::<PointLightGpu>(&source, "PointLight"),
            Ok(())
        );
        assert_eq!(
            check_wgsl_layout::<ShadowViewGpu>(&source, "ShadowView"),
            Ok(())
        );
    }

    #[test]
    fn moving_a_member_of_a_shipped_uniform_fails() {
        use crate::Material;
        let source = crate::ParallaxOcclusionMaterial::shader().source();
        let moved = source.replacen(
            "    height_texture_width: f32,\n    height_texture_height: f32,",
            "    height_texture_height: f32,\n    height_texture_width: f32,",
            1,
        );
        assert_ne!(moved, source, "the edit must apply");
        assert!(matches!(
            check_wgsl_layout::<crate::parallax::PomUniform>(&moved, "PomUniform"),
            Err(LayoutMismatch::Members { .. })
        ));
        // The generated parameter struct is checked as well.
        assert_eq!(
            check_wgsl_layout::<crate::parallax::PomParams>(&source, "PomParams"),
            Ok(())
        );
    }

    #[test]
    fn a_matching_struct_passes_and_a_moved_member_fails() {
        let good =
            "struct Sample { color: vec4<f32>, scale: f32, count: u32, _padding: vec2<u32> }";
        assert_eq!(check_wgsl_layout::<Sample>(good, "Sample"), Ok(()));
        let moved =
            "struct Sample { scale: f32, color: vec4<f32>, count: u32, _padding: vec2<u32> }";
        assert!(matches!(
            check_wgsl_layout::<Sample>(moved, "Sample"),
            Err(LayoutMismatch::Members { .. })
        ));
        let short = "struct Sample { color: vec4<f32>, scale: f32, count: u32 }";
        assert!(check_wgsl_layout::<Sample>(short, "Sample").is_err());
        assert_eq!(
            check_wgsl_layout::<Sample>(good, "Other"),
            Err(LayoutMismatch::NoStruct("Other".into()))
        );
    }
}
