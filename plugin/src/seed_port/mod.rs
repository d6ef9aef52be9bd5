//! The seed (Tatarchuk's shader: plugin/docs/authoring-materials.md, "The seed") as a
//! material, for the bench: its listings 1 and 2 transliterated to WGSL (see seed_port.wgsl for
//! every deviation from them), so every bench run can time the seed beside our parallax material
//! on the same workload and GPU: as written (a material in the opaque raster pass) and as one
//! compute dispatch over the target ([`SeedPortCompute`]).

mod compute;
mod packed;

use bytemuck::{Pod, Zeroable};

use crate::gpu::DefaultTexture;
use crate::material::{
    MAX_MATERIAL_TEXTURES, Material, MaterialPlugin, MaterialTextures, ShaderEntry, TextureFacts,
};
use crate::render::shaders::{self, ComposedShader, WgslFile};
use crate::{Assets, Handle, Image, ParallaxOcclusionMaterial, ShadowMode};

pub use compute::{
    SEED_PORT_COMPUTE_PASS, SEED_PORT_COMPUTE_SHADER, SeedPortCompute, SeedPortSurface,
};
pub use packed::packed_normal_height;

/// What can stop the seed port from being set up.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum SeedPortError {
    /// The normal map and the height map differ in size: one RGBA8 image holds both.
    #[error(
        "the normal map is {normal:?} texels and the height map {height:?}: the seed reads both \
         from one image, so they need one size"
    )]
    SizeMismatch {
        /// The normal map's width and height.
        normal: (u32, u32),
        /// The height map's width and height.
        height: (u32, u32),
    },
    /// A texture the parallax material names is not in the image store.
    #[error("a texture of the parallax material is not loaded")]
    MissingImage,
    /// The packed image could not be made.
    #[error("packing the normal and height maps: {0}")]
    Image(#[from] crate::ImageError),
    /// The world has no plane drawn with the seed port (for the compute pass).
    #[error("no entity with a seed port material, a mesh and a global transform")]
    NoPlane,
    /// The plane's mesh is not loaded, or has no triangle.
    #[error("the seed port plane's mesh is not loaded or has no triangle")]
    NoTriangle,
    /// The compute pass reads what the last frame extracted and uploaded: none was rendered.
    #[error("no frame was rendered yet, or its textures are not on the GPU: render one first")]
    NotRendered,
    /// A resource the compute pass needs is missing.
    #[error(transparent)]
    App(#[from] crate::AppError),
}

/// Tatarchuk's parallax occlusion mapping exactly as the seed's listing 2 has it: POM with
/// `n = lerp(max, min, N·V)` linear steps, the 7-tap soft shadow, the mip-level LOD switch, and
/// Phong lighting by the first light.
#[derive(Clone, Debug, PartialEq)]
pub struct SeedPortMaterial {
    /// sRGB colour texture (tBaseMap).
    pub base_color_texture: Option<Handle<Image>>,
    /// tNormalMap: RGBA8, the tangent-space normal in RGB with Direct3D's green (pointing down
    /// the image, +v) and the height in alpha ([`packed_normal_height`] makes one).
    pub normal_height_map: Option<Handle<Image>>,
    /// fHeightMapRange.
    pub height_map_range: f32,
    /// nMinSamples.
    pub min_samples: u32,
    /// nMaxSamples.
    pub max_samples: u32,
    /// nLODThreshold, in mip levels.
    pub lod_threshold: u32,
    /// fShadowSoftening.
    pub shadow_softening: f32,
    /// bDisplayShadows.
    pub shadows: bool,
    /// fSpecularExponent.
    pub specular_exponent: f32,
    /// cSpecularColor's strength (times the light's colour).
    pub specular_strength: f32,
}

impl Default for SeedPortMaterial {
    /// The seed's settings: range 0.05, samples 8..50, LOD threshold 4, softening 0.58; no
    /// textures.
    fn default() -> Self {
        Self::settings_of(&ParallaxOcclusionMaterial::default())
    }
}

impl SeedPortMaterial {
    /// The port with `material`'s colour texture, its normal and height maps packed into one
    /// RGBA8 image as the listing reads them (added to `images`), and the settings the listing
    /// shares with it (height scale, samples, LOD threshold, shadow softening, shadows on
    /// unless off, highlight).
    ///
    /// # Errors
    /// [`SeedPortError::MissingImage`] when a texture it names is not in `images`,
    /// [`SeedPortError::SizeMismatch`] when the normal and height maps differ in size.
    pub fn like(
        material: &ParallaxOcclusionMaterial,
        images: &mut Assets<Image>,
    ) -> Result<Self, SeedPortError> {
        let packed = packed_normal_height(material, images)?;
        Ok(Self {
            base_color_texture: material.base_color_texture.clone(),
            normal_height_map: packed.map(|image| images.add(image)),
            ..Self::settings_of(material)
        })
    }

    /// `material`'s shared settings, without textures.
    fn settings_of(material: &ParallaxOcclusionMaterial) -> Self {
        Self {
            base_color_texture: None,
            normal_height_map: None,
            height_map_range: material.height_scale,
            min_samples: material.min_samples.max(1),
            max_samples: material.max_samples.max(1),
            lod_threshold: material.lod_threshold.max(0.0).round() as u32,
            shadow_softening: material.shadow_softening,
            shadows: material.shadows != ShadowMode::Off,
            specular_exponent: material.shininess,
            specular_strength: material.specular_strength,
        }
    }
}

/// The port as the shader reads it (`SeedPortUniform` in seed_port.wgsl).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct SeedPortUniform {
    /// fHeightMapRange.
    pub height_map_range: f32,
    /// fShadowSoftening.
    pub shadow_softening: f32,
    /// fSpecularExponent.
    pub specular_exponent: f32,
    /// cSpecularColor's strength.
    pub specular_strength: f32,
    /// nLODThreshold.
    pub lod_threshold: i32,
    /// nMinSamples.
    pub min_samples: i32,
    /// nMaxSamples.
    pub max_samples: i32,
    /// bDisplayShadows.
    pub display_shadows: u32,
    /// vTextureDims: the normal and height map's size in texels.
    pub texture_dims: [f32; 2],
    /// Keeps the size a multiple of 16 bytes, as WGSL lays the struct out.
    pub _padding: [f32; 2],
}

crate::wgsl_layout!(SeedPortUniform {
    height_map_range,
    shadow_softening,
    specular_exponent,
    specular_strength,
    lod_threshold,
    min_samples,
    max_samples,
    display_shadows,
    texture_dims,
    _padding
});

/// The port's entry point.
pub const SEED_PORT_ENTRY: WgslFile = crate::wgsl_file!("seed_port/seed_port.wgsl");

/// The port's shader named `$name`: the core files it reads and the listing, followed by
/// `$more` (the fragment and the compute pass list them once).
macro_rules! seed_port_shader {
    ($name:literal, [$($more:expr),*]) => {
        ComposedShader {
            name: $name,
            constants: &[],
            files: &[
                shaders::FRAME,
                shaders::MESH_VERTEX,
                shaders::TANGENT_SPACE,
                crate::seed_port::SEED_PORT_ENTRY,
                $($more,)*
            ],
        }
    };
}
pub(crate) use seed_port_shader;

/// The port's shader.
pub const SEED_PORT_SHADER: ComposedShader = seed_port_shader!("seed_port.wgsl", []);

/// The texture slot of the normal and height map (tNormalMap).
const NORMAL_HEIGHT_SLOT: usize = 1;

impl Material for SeedPortMaterial {
    type PerDraw = SeedPortUniform;
    type Key = ();
    const NAME: &'static str = "seed port";
    const PER_DRAW_WGSL_NAME: &'static str = "SeedPortUniform";
    const TEXTURE_SLOTS: &'static [DefaultTexture] =
        &[DefaultTexture::WhiteSrgb, DefaultTexture::FlatNormal];

    /// The seed's shader as written runs forward only: that is what the bench measures.
    fn deferred_shader() -> Option<ComposedShader> {
        None
    }
    fn shader() -> ComposedShader {
        SEED_PORT_SHADER
    }

    fn textures(&self) -> MaterialTextures {
        let mut textures = [None; MAX_MATERIAL_TEXTURES];
        textures[0] = self.base_color_texture.as_ref().map(Handle::id);
        textures[NORMAL_HEIGHT_SLOT] = self.normal_height_map.as_ref().map(Handle::id);
        textures
    }

    fn key(&self) {}

    fn fragment(_: ()) -> ShaderEntry {
        ShaderEntry::entry("fs_seed_port")
    }

    fn per_draw(
        &self,
        textures: &[Option<TextureFacts>; MAX_MATERIAL_TEXTURES],
    ) -> SeedPortUniform {
        let height = textures[NORMAL_HEIGHT_SLOT].unwrap_or(TextureFacts {
            width: 1,
            height: 1,
            mip_levels: 1,
        });
        let (min_samples, max_samples) = (
            self.min_samples.clamp(1, 256),
            self.max_samples.clamp(1, 256),
        );
        SeedPortUniform {
            height_map_range: self.height_map_range,
            shadow_softening: self.shadow_softening,
            specular_exponent: self.specular_exponent,
            specular_strength: self.specular_strength,
            lod_threshold: self.lod_threshold.min(32) as i32,
            min_samples: min_samples.min(max_samples) as i32,
            max_samples: max_samples as i32,
            display_shadows: u32::from(self.shadows),
            texture_dims: [height.width as f32, height.height as f32],
            _padding: [0.0; 2],
        }
    }
}

/// Puts the seed's shader in place of every parallax material in `world`, with its textures
/// (the normal and height maps packed into one image, added to `images`) and shared settings
/// ([`SeedPortMaterial::like`]); returns how many it replaced. Materials that share their
/// textures share one packed image.
///
/// # Errors
/// As [`SeedPortMaterial::like`]; nothing in `world` is replaced then.
pub fn replace_parallax_materials(
    world: &mut hecs::World,
    images: &mut Assets<Image>,
) -> Result<usize, SeedPortError> {
    let mut ports: Vec<(ParallaxOcclusionMaterial, SeedPortMaterial)> = Vec::new();
    let mut planes = Vec::new();
    for (entity, material) in world.query_mut::<(hecs::Entity, &ParallaxOcclusionMaterial)>() {
        let same_textures = |(other, _): &&(ParallaxOcclusionMaterial, SeedPortMaterial)| {
            other.normal_map == material.normal_map
                && other.height_map == material.height_map
                && other.height_convention == material.height_convention
        };
        let port = match ports.iter().find(same_textures) {
            Some((_, port)) => SeedPortMaterial {
                base_color_texture: material.base_color_texture.clone(),
                normal_height_map: port.normal_height_map.clone(),
                ..SeedPortMaterial::settings_of(material)
            },
            None => SeedPortMaterial::like(material, images)?,
        };
        ports.push((material.clone(), port.clone()));
        planes.push((entity, port));
    }
    for (entity, port) in &planes {
        // Both listed by the query above, so the entity and its component exist.
        let _ = world.remove_one::<ParallaxOcclusionMaterial>(*entity);
        let _ = world.insert_one(*entity, port.clone());
    }
    Ok(planes.len())
}

/// Draws [`SeedPortMaterial`]s (the bench adds it beside the parallax plugin).
#[derive(Clone, Copy, Debug, Default)]
pub struct SeedPortPlugin;

impl crate::Plugin for SeedPortPlugin {
    fn build(&self, app: &mut crate::App) {
        app.add_plugin(MaterialPlugin::<SeedPortMaterial>::default());
    }
}

#[cfg(test)]
mod tests {
    #[test]
    fn the_uniform_matches_its_wgsl() {
        assert_eq!(
            crate::material::check_material_layout::<super::SeedPortMaterial>(),
            Ok(())
        );
    }
}
