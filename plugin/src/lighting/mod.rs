//! What the shipped materials share about lighting a surface: the reflection models
//! ([`LIGHTING`], `lighting.wgsl`, implements them) and the parameters that drive it, declared once in
//! [`crate::with_lighting_parameters!`]. The lit material and the parallax material both use
//! them, so they live below both.

/// The reflection models in WGSL: Phong, Blinn-Phong, Cook-Torrance + Oren-Nayar and glTF's GGX.
pub(crate) const LIGHTING: crate::shader::WgslFile = crate::wgsl_file!("lighting/lighting.wgsl");

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

/// Declares a material with [`crate::material_parameters!`] and the lighting parameters every
/// lit surface shares, appended to its own: `base_color`, `normal_strength`, `specular_strength`
/// and `shininess` (Phong and Blinn-Phong), `roughness` and `metallic` (Cook-Torrance and
/// GGX-Lambert), and `double_sided`. Each is declared here once, help, limits and default
/// (the parallax material's values: specular 0.3, roughness 0.6); the material declares its
/// `lighting: LightingModel` itself, whose default is its own choice (Tatarchuk's Phong for the
/// parallax material, Blinn-Phong for the lit one).
#[macro_export]
#[doc(hidden)]
macro_rules! with_lighting_parameters {
    (
        $(#[$attr:meta])*
        pub struct $material:ident {
            $(inputs { $($inputs:tt)* })?
            $(textures { $($textures:tt)* })?
            parameters { $($parameters:tt)* }
        }
        $($trailer:tt)*
    ) => {
        $crate::material_parameters! {
            $(#[$attr])*
            pub struct $material {
                $(inputs { $($inputs)* })?
                $(textures { $($textures)* })?
                parameters {
                    $($parameters)*
                    /// Linear RGBA multiplied with the colour texture.
                    base_color: $crate::Color = $crate::Color::WHITE,
                        $crate::parameters::ParamSpec::color()
                        .group($crate::parameters::ParamGroup::Lighting);
                    /// Scales the normal map's tilt: 0 is flat, 1 as authored.
                    normal_strength: f32 = 1.0,
                        $crate::parameters::ParamSpec::float(0.0, 100.0).editor(0.0, 4.0)
                        .group($crate::parameters::ParamGroup::Lighting);
                    /// Weight of the Phong / Blinn-Phong highlight.
                    specular_strength: f32 = 0.3,
                        $crate::parameters::ParamSpec::float(0.0, 100.0).editor(0.0, 2.0)
                        .group($crate::parameters::ParamGroup::Lighting)
                        .applies_when(|material| !material.lighting.uses_roughness());
                    /// Phong / Blinn-Phong exponent: higher is a smaller, sharper highlight.
                    shininess: f32 = 32.0,
                        $crate::parameters::ParamSpec::float(1.0, 10_000.0).editor(1.0, 512.0)
                        .logarithmic()
                        .group($crate::parameters::ParamGroup::Lighting)
                        .applies_when(|material| !material.lighting.uses_roughness());
                    /// Cook-Torrance / GGX-Lambert roughness (glTF roughnessFactor): 0 is a
                    /// mirror, 1 fully rough.
                    roughness: f32 = 0.6, $crate::parameters::ParamSpec::float(0.0, 1.0)
                        .group($crate::parameters::ParamGroup::Lighting)
                        .applies_when(|material| material.lighting.uses_roughness());
                    /// Cook-Torrance / GGX-Lambert metalness (glTF metallicFactor): 0 is a
                    /// dielectric, 1 a metal.
                    metallic: f32 = 0.0, $crate::parameters::ParamSpec::float(0.0, 1.0)
                        .group($crate::parameters::ParamGroup::Lighting)
                        .applies_when(|material| material.lighting.uses_roughness());
                    /// Draw and light both sides (glTF doubleSided): the back gets the reversed
                    /// normal.
                    double_sided: bool = false, $crate::parameters::ParamSpec::toggle()
                        .group($crate::parameters::ParamGroup::Lighting);
                }
            }
            $($trailer)*
        }
    };
}
