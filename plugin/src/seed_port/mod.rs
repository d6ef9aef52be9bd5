//! The seed's shader as a material, for the bench: Tatarchuk's listings 1 and 2 transliterated
//! to WGSL (see seed_port.wgsl for the few deviations it needs to run), so every bench run can
//! time the seed beside our parallax material on the same workload and GPU.

use bytemuck::{Pod, Zeroable};

use crate::material::{
    MAX_MATERIAL_TEXTURES, Material, MaterialPlugin, MaterialTextures, ShaderEntry, TextureFacts,
};
use crate::render::DefaultTexture;
use crate::render::shaders::{self, ComposedShader, WgslFile};
use crate::{Handle, HeightSource, Image, ParallaxOcclusionMaterial, ShadowMode};

/// Tatarchuk's parallax occlusion mapping exactly as the seed's listing 2 has it: POM with
/// `n = lerp(max, min, N·V)` linear steps, the 7-tap soft shadow, the mip-level LOD switch, and
/// Phong lighting by the first light.
#[derive(Clone, Debug, PartialEq)]
pub struct SeedPortMaterial {
    /// sRGB colour texture (tBaseMap).
    pub base_color_texture: Option<Handle<Image>>,
    /// Tangent-space normal map (tNormalMap's RGB).
    pub normal_map: Option<Handle<Image>>,
    /// Height map, read from red (the listing keeps it in tNormalMap's alpha).
    pub height_map: Option<Handle<Image>>,
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
    /// The seed's settings: range 0.05, samples 8..50, LOD threshold 4, softening 0.58.
    fn default() -> Self {
        Self::like(&ParallaxOcclusionMaterial::default())
    }
}

impl SeedPortMaterial {
    /// The port with `material`'s textures and the settings the listing shares with it (height
    /// scale, samples, LOD threshold, shadow softening, shadows on unless off, highlight).
    pub fn like(material: &ParallaxOcclusionMaterial) -> Self {
        Self {
            base_color_texture: material.base_color_texture.clone(),
            normal_map: material.normal_map.clone(),
            height_map: match &material.height_map {
                Some(HeightSource::Texture(height)) => Some(height.clone()),
                _ => None,
            },
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
    /// vTextureDims: the height map's size in texels.
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

/// The port's shader.
pub const SEED_PORT_SHADER: ComposedShader = ComposedShader {
    name: "seed_port.wgsl",
    constants: &[],
    files: &[
        shaders::FRAME,
        shaders::MESH_VERTEX,
        shaders::TANGENT_SPACE,
        SEED_PORT_ENTRY,
    ],
};

/// The texture slot of the height map.
const HEIGHT_SLOT: usize = 2;

impl Material for SeedPortMaterial {
    type PerDraw = SeedPortUniform;
    type Key = ();
    const NAME: &'static str = "seed port";
    const PER_DRAW_WGSL_NAME: &'static str = "SeedPortUniform";
    const TEXTURE_SLOTS: &'static [DefaultTexture] = &[
        DefaultTexture::WhiteSrgb,
        DefaultTexture::FlatNormal,
        DefaultTexture::WhiteLinear,
    ];

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
        textures[1] = self.normal_map.as_ref().map(Handle::id);
        textures[HEIGHT_SLOT] = self.height_map.as_ref().map(Handle::id);
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
        let height = textures[HEIGHT_SLOT].unwrap_or(TextureFacts {
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

/// Puts the seed's shader in place of every parallax material in `world`, with its textures and
/// shared settings ([`SeedPortMaterial::like`]); returns how many it replaced.
pub fn replace_parallax_materials(world: &mut hecs::World) -> usize {
    let planes: Vec<_> = world
        .query_mut::<(hecs::Entity, &ParallaxOcclusionMaterial)>()
        .into_iter()
        .map(|(entity, material)| (entity, SeedPortMaterial::like(material)))
        .collect();
    for (entity, port) in &planes {
        // Both listed by the query above, so the entity and its component exist.
        let _ = world.remove_one::<ParallaxOcclusionMaterial>(*entity);
        let _ = world.insert_one(*entity, port.clone());
    }
    planes.len()
}

/// Draws [`SeedPortMaterial`]s (the bench adds it beside the parallax plugin).
pub fn seed_port_plugin() -> MaterialPlugin<SeedPortMaterial> {
    MaterialPlugin::default()
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
