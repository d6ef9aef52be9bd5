//! `LitMaterial`: the lit, normal-mapped material, a [`Material`] like any other. Its WGSL is a
//! shading function over the seam's surface input, around which it composes the seam's entry
//! points: on the deferred path its opaque and masked draws shade in the compute resolve. With
//! [`MaterialPlugin::for_meshes_without_material`] it also draws meshes that have no material.

use crate::gpu::DefaultTexture;
use crate::material::{
    Choice, DeclaredMaterial, MAX_MATERIAL_TEXTURES, Material, MaterialPlugin, MaterialTextures,
    ParamSpec, SHADED_CUT_OUT, SHADED_CUT_OUT_VISIBILITY, SHADED_FORWARD, SHADED_RESOLVE,
    SURFACE_INPUT, ShaderEntry, TextureFacts,
};
use crate::render::shaders::{self, ComposedShader, WgslFile};
use crate::{Color, LightingModel};

crate::choice_enum! {
    /// How a surface's alpha is used (glTF alphaMode).
    pub enum AlphaMode: "ALPHA_MODE" {
        /// Alpha is ignored: the surface is opaque.
        Opaque = "opaque",
        /// Cut out where alpha is below alpha_cutoff; opaque elsewhere.
        Mask = "mask",
        /// Blended over what is behind, in the transparent phase, drawn back to front.
        Blend = "blend",
    }
}

crate::with_lighting_parameters! {
    /// A lit material with optional colour, normal, emissive, occlusion and metallic-roughness
    /// textures: Blinn-Phong by default, GGX-Lambert for glTF's metallic-roughness materials.
    ///
    /// Put it on an entity with a `Handle<Mesh>` and a [`crate::Transform`]; with
    /// [`crate::DefaultPlugins`] a mesh entity without any material is drawn with
    /// `LitMaterial::default()`.
    #[derive(Clone, Debug, PartialEq)]
    pub struct LitMaterial {
        textures {
            /// sRGB colour texture (white when absent).
            base_color_texture: WhiteSrgb,
            /// Tangent-space normal map, OpenGL convention (green up the image); flat when absent.
            normal_map: FlatNormal,
            /// sRGB emissive texture, multiplied with `emissive` (white when absent).
            emissive_texture: WhiteSrgb,
            /// Ambient occlusion in the red channel, linear (glTF occlusionTexture); none when absent.
            occlusion_texture: WhiteLinear,
            /// Roughness in green and metalness in blue, linear, multiplied with `roughness` and
            /// `metallic` (glTF metallicRoughnessTexture); GGX models only.
            metallic_roughness_texture: WhiteLinear,
        }
        parameters {
            /// Reflection model: Phong and Blinn-Phong use specular and shininess; Cook-Torrance
            /// and GGX-Lambert (glTF's) roughness and metallic, times the metallic-roughness texture.
            lighting: LightingModel = LightingModel::BlinnPhong, ParamSpec::choice::<LightingModel>();
            /// How much the occlusion texture darkens the ambient light: 0 = not at all, 1 = fully.
            occlusion_strength: f32 = 1.0, ParamSpec::float(0.0, 1.0);
            /// Light the surface gives off itself, linear (glTF emissiveFactor).
            emissive: Color = Color::BLACK, ParamSpec::color();
            /// Multiplies `emissive` (KHR_materials_emissive_strength): above 1 for lamps and screens.
            emissive_strength: f32 = 1.0, ParamSpec::float(0.0, 100_000.0).editor(0.0, 10.0);
            /// Ignore the lights: show the base colour as is (KHR_materials_unlit).
            unlit: bool = false, ParamSpec::toggle();
            /// Whether alpha cuts the surface out (glTF alphaMode).
            alpha_mode: AlphaMode = AlphaMode::Opaque, ParamSpec::choice::<AlphaMode>();
            /// Alpha below which a masked surface is cut out (glTF alphaCutoff).
            alpha_cutoff: f32 = 0.5, ParamSpec::float(0.0, 1.0)
                .applies_when(|material| material.alpha_mode == AlphaMode::Mask);
        }
    }
    preset LitPreset;
    patch LitPatch;
    gpu LitParams;
}

impl LitMaterial {
    /// A material of one colour.
    pub fn from_color(base_color: Color) -> Self {
        Self {
            base_color,
            ..Self::default()
        }
    }
}

/// The lit material's shading function (`shade`, `covers`) and bindings.
pub const LIT_ENTRY: WgslFile = crate::wgsl_file!("lit/lit.wgsl");

/// The lit shader's generated constants after `$first`, and its files (the core's, the lit
/// shading function and the seam's entry points around it) followed by `$more`: the forward and
/// the deferred shader list them once.
macro_rules! lit_shader {
    ($name:literal, [$($first:expr),*], [$($more:expr),*]) => {
        ComposedShader {
            name: $name,
            constants: &[
                $($first,)*
                LightingModel::wgsl_constants,
                AlphaMode::wgsl_constants,
                LitParams::wgsl,
            ],
            files: &[
                shaders::FRAME,
                crate::render::lights::LIGHTS_WGSL,
                shaders::PARAMS,
                shaders::MESH_VERTEX,
                shaders::SHADOWS,
                crate::render::environment::SPHERICAL_HARMONICS,
                crate::render::environment::ENVIRONMENT,
                shaders::TANGENT_SPACE,
                crate::lighting::LIGHTING,
                SURFACE_INPUT,
                LIT_ENTRY,
                SHADED_FORWARD,
                SHADED_CUT_OUT,
                $($more,)*
            ],
        }
    };
}

/// The lit material's shader.
pub const LIT_SHADER: ComposedShader = lit_shader!("lit.wgsl", [], []);

/// The lit material's shader for the deferred path: [`LIT_SHADER`], its visibility pass and
/// the compute resolve, where opaque and masked surfaces shade (blended ones draw in the
/// transparent phase on both paths).
pub const LIT_DEFERRED_SHADER: ComposedShader = lit_shader!(
    "lit.wgsl (deferred)",
    [shaders::deferred_header],
    [
        SHADED_CUT_OUT_VISIBILITY,
        shaders::VISIBILITY,
        shaders::VISIBILITY_READ,
        crate::material::DEFERRED_RESOLVE,
        SHADED_RESOLVE
    ]
);

/// What one lit pipeline is compiled for.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct LitPipelineKey {
    /// Both sides drawn (no culling).
    pub double_sided: bool,
    /// How alpha is used: a mask may discard (in the prepass too); a blend draws in the
    /// transparent phase.
    pub alpha_mode: AlphaMode,
}

impl LitPipelineKey {
    /// `whole`, or for a masked surface `cut_out`: the seam's entry that leaves the holes out.
    fn entry(self, whole: &'static str, cut_out: &'static str) -> ShaderEntry {
        ShaderEntry::entry(if self.alpha_mode == AlphaMode::Mask {
            cut_out
        } else {
            whole
        })
    }
}

impl Material for LitMaterial {
    type PerDraw = LitParams;
    type Key = LitPipelineKey;
    const NAME: &'static str = "lit";
    const PER_DRAW_WGSL_NAME: &'static str = "LitParams";
    // Masked surfaces discard, in the prepass too.
    const SURFACE_ON_POLYGON: bool = false;
    const TEXTURE_SLOTS: &'static [DefaultTexture] = <Self as DeclaredMaterial>::TEXTURE_SLOTS;

    fn shader() -> ComposedShader {
        LIT_SHADER
    }

    fn textures(&self) -> MaterialTextures {
        self.texture_images()
    }

    fn key(&self) -> Self::Key {
        LitPipelineKey {
            double_sided: self.double_sided,
            alpha_mode: self.alpha_mode,
        }
    }

    fn blends(key: Self::Key) -> bool {
        key.alpha_mode == AlphaMode::Blend
    }

    fn prepass_fragment(key: Self::Key) -> Option<ShaderEntry> {
        // A cut-out surface must leave its holes out of the depth too.
        (key.alpha_mode == AlphaMode::Mask).then(|| ShaderEntry::entry("fs_prepass_cut_out"))
    }

    fn deferred_shader() -> Option<ComposedShader> {
        Some(LIT_DEFERRED_SHADER)
    }

    fn visibility_fragment(key: Self::Key) -> ShaderEntry {
        key.entry("fs_visibility", "fs_visibility_cut_out")
    }

    fn deferred_resolve(key: Self::Key) -> Option<ShaderEntry> {
        // What the visibility pass kept is covered: the resolve shades it whole.
        (!Self::blends(key)).then(|| ShaderEntry::entry("cs_resolve"))
    }

    fn cull_mode(key: Self::Key) -> Option<wgpu::Face> {
        (!key.double_sided).then_some(wgpu::Face::Back)
    }

    fn fragment(key: Self::Key) -> ShaderEntry {
        key.entry("fs_main", "fs_main_cut_out")
    }

    fn per_draw(&self, _: &[Option<TextureFacts>; MAX_MATERIAL_TEXTURES]) -> LitParams {
        self.params()
    }

    fn problems(&self) -> Vec<String> {
        self.parameter_problems()
    }

    fn casts_with_frame_noise(&self) -> bool {
        false
    }
}

/// Draws [`LitMaterial`]s, and every mesh that has no material at all.
#[derive(Clone, Copy, Debug, Default)]
pub struct LitPlugin;

impl crate::Plugin for LitPlugin {
    fn build(&self, app: &mut crate::App) {
        app.add_plugin(MaterialPlugin::<LitMaterial>::for_meshes_without_material());
        // A lit material plugin added before without that setting still draws the other meshes.
        crate::material::draw_meshes_without_material::<LitMaterial>(app);
    }
}
