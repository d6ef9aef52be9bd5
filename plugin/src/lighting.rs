//! What the shipped materials share about lighting a surface: the reflection model. Both the
//! lit material and the parallax material choose one (`lighting.wgsl` implements them), so it
//! lives below both.

crate::choice_enum! {
    /// The lighting model.
    pub enum LightingModel: "LIGHTING" {
        /// Phong, as in Tatarchuk's listing: highlight around the mirrored view ray.
        Phong = "phong",
        /// Blinn-Phong: highlight around the half vector.
        BlinnPhong = "blinn_phong",
        /// Cook-Torrance (GGX) specular over Oren-Nayar diffuse, with roughness and metallic.
        CookTorrance = "cook_torrance",
        /// GGX specular over Lambert diffuse, with roughness and metallic: glTF's BRDF (spec appendix B).
        GgxLambert = "ggx_lambert",
    }
}

impl LightingModel {
    /// Whether the model is driven by roughness and metallic (else specular and shininess).
    pub fn uses_roughness(self) -> bool {
        matches!(self, Self::CookTorrance | Self::GgxLambert)
    }
}
