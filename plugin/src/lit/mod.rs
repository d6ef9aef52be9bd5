//! `LitMaterial`: the lit, normal-mapped material, a [`Material`] like any other. With
//! [`MaterialPlugin::for_meshes_without_material`] it also draws meshes that have no material.

use bytemuck::{Pod, Zeroable};

use crate::material::{
    Choice, FragmentVariant, MAX_MATERIAL_TEXTURES, Material, MaterialPlugin, MaterialTextures,
    TextureFacts,
};
use crate::render::DefaultTexture;
use crate::render::shaders::{self, ComposedShader, WgslFile};
use crate::{Color, Handle, Image, LightingModel};

/// A Blinn-Phong material with an optional colour texture and normal map.
///
/// Put it on an entity with a `Handle<Mesh>` and a [`crate::Transform`]; with
/// [`crate::DefaultPlugins`] a mesh entity without any material is drawn with
/// `LitMaterial::default()`.
#[derive(Clone, Debug, PartialEq)]
pub struct LitMaterial {
    /// Colour multiplied with the texture, linear.
    pub base_color: Color,
    /// sRGB colour texture (white when absent).
    pub base_color_texture: Option<Handle<Image>>,
    /// Tangent-space normal map, OpenGL convention (green up the image); flat when absent.
    pub normal_map: Option<Handle<Image>>,
    /// Scales the normal map's XY tilt: 0 = flat, 1 = as authored.
    pub normal_strength: f32,
    /// Weight of the specular highlight.
    pub specular_strength: f32,
    /// Blinn-Phong exponent: higher = smaller, sharper highlight (clamped to ≥ 1).
    pub shininess: f32,
}

impl Default for LitMaterial {
    fn default() -> Self {
        Self {
            base_color: Color::WHITE,
            base_color_texture: None,
            normal_map: None,
            normal_strength: 1.0,
            specular_strength: 0.25,
            shininess: 32.0,
        }
    }
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

/// [`LitMaterial`] as `lit.wgsl` reads it.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct LitUniform {
    /// Linear base colour.
    pub base_color: [f32; 4],
    /// Scales the normal map's tilt.
    pub normal_strength: f32,
    /// Weight of the highlight.
    pub specular_strength: f32,
    /// Blinn-Phong exponent.
    pub shininess: f32,
    /// Keeps the size a multiple of 16 bytes.
    pub _padding: f32,
}

crate::wgsl_layout!(LitUniform {
    base_color,
    normal_strength,
    specular_strength,
    shininess,
    _padding
});

/// The lit material's entry point.
pub const LIT_ENTRY: WgslFile = crate::wgsl_file!("lit/lit.wgsl");

/// The lit material's shader.
pub const LIT_SHADER: ComposedShader = ComposedShader {
    name: "lit.wgsl",
    constants: &[LightingModel::wgsl_constants],
    files: &[
        shaders::FRAME,
        shaders::MESH_VERTEX,
        shaders::TANGENT_SPACE,
        shaders::LIGHTING,
        LIT_ENTRY,
    ],
};

impl Material for LitMaterial {
    type Uniform = LitUniform;
    type Key = ();
    const NAME: &'static str = "lit";
    const UNIFORM_WGSL_NAME: &'static str = "LitUniform";
    const TEXTURE_SLOTS: &'static [DefaultTexture] =
        &[DefaultTexture::WhiteSrgb, DefaultTexture::FlatNormal];

    fn shader() -> ComposedShader {
        LIT_SHADER
    }

    fn textures(&self) -> MaterialTextures {
        [
            self.base_color_texture.as_ref().map(Handle::id),
            self.normal_map.as_ref().map(Handle::id),
            None,
            None,
        ]
    }

    fn key(&self) -> Self::Key {}

    fn fragment(_: Self::Key) -> FragmentVariant {
        FragmentVariant::entry("fs_main")
    }

    fn uniform(&self, _: &[Option<TextureFacts>; MAX_MATERIAL_TEXTURES]) -> LitUniform {
        LitUniform {
            base_color: self.base_color.to_array(),
            normal_strength: self.normal_strength,
            specular_strength: self.specular_strength,
            shininess: self.shininess,
            _padding: 0.0,
        }
    }
}

/// Draws [`LitMaterial`]s, and every mesh that has no material at all.
pub fn lit_plugin() -> MaterialPlugin<LitMaterial> {
    MaterialPlugin::for_meshes_without_material()
}
