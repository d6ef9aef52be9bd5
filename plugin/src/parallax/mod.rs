//! The parallax occlusion mapping material: its parameters, GPU form and plugin.

mod gpu;
mod layer_heights;
mod layer_preset;
mod layers;
mod material;
mod max_pyramid;
mod mesh_needs;
mod pipelines;
mod preset;

pub use crate::lighting::LightingModel;
pub use gpu::PomUniform;
pub use layer_heights::{LayerError, MAX_LAYERS, pack_layer_heights};
pub use layer_preset::{LayerFiles, LayerPreset};
pub use layers::{LAYER_TILING_LIMITS, LayerWeights, LayersError, ParallaxLayer, ParallaxLayers};
pub use material::{
    BOUNDS_LIMIT, DebugView, HeightSource, HeightUnits, MAX_BLEND_CONTRAST, MAX_SAMPLES_LIMIT,
    ParallaxMethod, ParallaxOcclusionMaterial, PomMaterialError, PomParams, PomPatch, PomPreset,
    ShadowMode, Silhouette, TRIPLANAR_SCALE_LIMITS, TextureMapping,
};
#[cfg(feature = "scene-tests")]
pub use max_pyramid::read_max_pyramid;
pub use max_pyramid::{HEIGHT_CHANNEL, MAX_PYRAMID_SHADER, MaxHeightPyramid};
pub use mesh_needs::{
    CurvedSilhouette, CurvedSilhouetteWarnings, MeshWarnings, TriplanarMapping,
    TriplanarMeshWarnings, curvature_problem, triplanar_problem, warn_about_unsuitable_meshes,
};
pub use pipelines::PomPipelineKey;
pub use preset::PresetError;

use crate::gpu::{DefaultTexture, DerivedTexture, DerivedTextures, MAX_DERIVED_TEXTURES};
use crate::material::DrawView;
use crate::material::{
    Choice, MAX_MATERIAL_TEXTURES, Material, MaterialPlugin, MaterialTextures, ShaderEntry,
    TextureFacts,
};
use crate::render::shaders::{self, ComposedShader, WgslFile};
use crate::{App, AssetId, Handle, Image, Plugin};

/// Triplanar mapping's projection of a pixel, and its colour and normal at the visible point.
pub const PARALLAX_TRIPLANAR: WgslFile = crate::wgsl_file!("parallax/triplanar.wgsl");
/// The ray march, LOD and self-shadow functions of the parallax material.
pub const PARALLAX_MARCH: WgslFile = crate::wgsl_file!("parallax/march.wgsl");
/// The MaxMip method's traversal of the maximum pyramid.
pub const PARALLAX_MAX_MIP: WgslFile = crate::wgsl_file!("parallax/max_mip.wgsl");
/// The parallax material's entry points.
pub const PARALLAX_ENTRY: WgslFile = crate::wgsl_file!("parallax/pom.wgsl");

/// The parallax shader's generated constants after `$first`, and its files followed by
/// `$more`: the forward and the deferred shader list them once.
macro_rules! parallax_shader {
    ($name:literal, [$($first:expr),*], [$($more:expr),*]) => {
        ComposedShader {
            name: $name,
            constants: &[
                $($first,)*
                ParallaxMethod::wgsl_constants,
                ShadowMode::wgsl_constants,
                Silhouette::wgsl_constants,
                HeightUnits::wgsl_constants,
                TextureMapping::wgsl_constants,
                LightingModel::wgsl_constants,
                DebugView::wgsl_constants,
                crate::render::display_referred_wgsl,
                PomParams::wgsl,
            ],
            files: &[
                shaders::FRAME,
                crate::render::lights::LIGHTS_WGSL,
                shaders::PARAMS,
                shaders::MESH_VERTEX,
                shaders::SHADOWS,
                crate::render::environment::SPHERICAL_HARMONICS,
                crate::render::environment::ENVIRONMENT,
                shaders::PREPASS_DEPTH,
                shaders::TANGENT_SPACE,
                crate::lighting::LIGHTING,
                HEIGHT_CHANNEL,
                PARALLAX_MARCH,
                PARALLAX_TRIPLANAR,
                PARALLAX_MAX_MIP,
                PARALLAX_ENTRY,
                $($more,)*
            ],
        }
    };
}

/// The parallax material's shader.
pub const PARALLAX_SHADER: ComposedShader = parallax_shader!("pom.wgsl", [], []);

/// The parallax material's entry points of the deferred path.
pub const PARALLAX_DEFERRED_ENTRY: WgslFile = crate::wgsl_file!("parallax/pom_deferred.wgsl");

/// The parallax material's shader for the deferred path: [`PARALLAX_SHADER`], the visibility
/// pass and the compute resolve.
pub const PARALLAX_DEFERRED_SHADER: ComposedShader = parallax_shader!(
    "pom.wgsl (deferred)",
    [shaders::deferred_header],
    [
        shaders::VISIBILITY,
        crate::material::CANDIDATES,
        shaders::VISIBILITY_READ,
        crate::material::DEFERRED_RESOLVE,
        PARALLAX_DEFERRED_ENTRY
    ]
);

/// Entities whose parallax material was clamped (each warned about once per change).
pub type MaterialWarnings = crate::material::MaterialWarnings<ParallaxOcclusionMaterial>;

/// Texture slot of the height map (a layered material's packed heights).
const HEIGHT_SLOT: usize = 2;
/// Texture slot of a layered material's weight map.
const LAYER_WEIGHTS_SLOT: usize = 3;
/// Texture slot of the second layer's colour map; its normal map follows, then the next layer's.
const MORE_LAYERS_SLOT: usize = 4;

impl Material for ParallaxOcclusionMaterial {
    type PerDraw = PomUniform;
    type Key = PomPipelineKey;
    const NAME: &'static str = "parallax";
    const PER_DRAW_WGSL_NAME: &'static str = "PomUniform";
    // The relief lies below the polygon (and the depth offset moves the depth there).
    const SURFACE_ON_POLYGON: bool = false;
    // Colour, normal and height (a layered material's first layer and packed heights), the
    // layers' weights, then colour and normal of the second to fourth layers.
    const TEXTURE_SLOTS: &'static [DefaultTexture] = &[
        DefaultTexture::WhiteSrgb,
        DefaultTexture::FlatNormal,
        DefaultTexture::WhiteLinear,
        DefaultTexture::WhiteLinear,
        DefaultTexture::WhiteSrgb,
        DefaultTexture::FlatNormal,
        DefaultTexture::WhiteSrgb,
        DefaultTexture::FlatNormal,
        DefaultTexture::WhiteSrgb,
        DefaultTexture::FlatNormal,
    ];

    fn shader() -> ComposedShader {
        PARALLAX_SHADER
    }

    fn textures(&self) -> MaterialTextures {
        let mut textures = [None; MAX_MATERIAL_TEXTURES];
        let Some(layers) = &self.layers else {
            textures[0] = self.base_color_texture.as_ref().map(Handle::id);
            textures[1] = self.normal_map.as_ref().map(Handle::id);
            textures[HEIGHT_SLOT] = self.height_image();
            return textures;
        };
        textures[HEIGHT_SLOT] = Some(layers.heights.id());
        if let LayerWeights::Texture(weights) = &layers.weights {
            textures[LAYER_WEIGHTS_SLOT] = Some(weights.id());
        }
        for (index, layer) in layers.drawn().iter().enumerate() {
            let colour_slot = if index == 0 {
                0
            } else {
                MORE_LAYERS_SLOT + 2 * (index - 1)
            };
            textures[colour_slot] = layer.base_color_texture.as_ref().map(Handle::id);
            textures[colour_slot + 1] = layer.normal_map.as_ref().map(Handle::id);
        }
        textures
    }

    /// MaxMip's maximum pyramid of the height map, as the shader reads it (channel and
    /// convention applied), at binding 4.
    const DERIVED_TEXTURE_SLOTS: usize = 1;

    fn derived_textures(&self) -> DerivedTextures {
        let mut derived = [None; MAX_DERIVED_TEXTURES];
        if PomPipelineKey::of(self).method == ParallaxMethod::MaxMip
            && let (Some(source), Some(image)) = (&self.height_map, self.height_image())
        {
            derived[0] = Some(DerivedTexture {
                source: image,
                derivation: MaxHeightPyramid::derivation(source.channel(), self.height_convention),
            });
        }
        derived
    }

    fn key(&self) -> PomPipelineKey {
        PomPipelineKey::of(self)
    }

    fn fragment(key: PomPipelineKey) -> ShaderEntry {
        key.fragment()
    }

    fn cull_mode(key: PomPipelineKey) -> Option<wgpu::Face> {
        (!key.double_sided).then_some(wgpu::Face::Back)
    }

    // While a variant compiles: the same surface, normal-mapped (Tatarchuk's own LOD fallback).
    fn fallback_key(key: PomPipelineKey) -> Option<PomPipelineKey> {
        Some(PomPipelineKey {
            method: ParallaxMethod::NormalMapping,
            shadows: ShadowMode::Off,
            depth_offset: false,
            debug_view: DebugView::None,
            ..key
        })
    }

    fn prepass_fragment(key: PomPipelineKey) -> Option<ShaderEntry> {
        key.prepass_fragment()
    }

    fn shadow_fragment(key: PomPipelineKey) -> Option<ShaderEntry> {
        key.shadow_fragment()
    }

    fn fragment_after_prepass(key: PomPipelineKey) -> ShaderEntry {
        key.fragment_after_prepass()
    }

    fn deferred_shader() -> Option<ComposedShader> {
        Some(PARALLAX_DEFERRED_SHADER)
    }

    fn visibility_fragment(key: PomPipelineKey) -> ShaderEntry {
        key.visibility_fragment()
    }

    fn deferred_resolve(key: PomPipelineKey) -> Option<ShaderEntry> {
        Some(key.deferred_resolve())
    }

    fn settles_depth_in_resolve(key: PomPipelineKey) -> bool {
        key.settles_depth_in_resolve()
    }

    fn per_draw(&self, textures: &[Option<TextureFacts>; MAX_MATERIAL_TEXTURES]) -> PomUniform {
        let (height, weights) = (textures[HEIGHT_SLOT], textures[LAYER_WEIGHTS_SLOT]);
        if self.is_valid() {
            PomUniform::new(self, height, weights)
        } else {
            PomUniform::new(&self.sanitized(), height, weights)
        }
    }

    fn problems(&self) -> Vec<String> {
        if self.is_valid() {
            return Vec::new();
        }
        ParallaxOcclusionMaterial::problems(self)
            .iter()
            .map(ToString::to_string)
            .collect()
    }

    fn casts_with_frame_noise(&self) -> bool {
        // The jittered march's start (pom.wgsl's `march_noise`) is the casters' only noise.
        self.jitter_march
    }

    /// Per-object LOD: a draw on which every pixel is past the LOD threshold uses the
    /// normal-mapping pipeline. Per pixel the shader would skip the march there anyway
    /// (T §5.4.3) and the image is the same, but a pipeline that holds the march is slower even
    /// where it does not run (more registers per pixel: on the far-field bench, normal mapping
    /// drawn with the POM pipeline was markedly slower than with its own). The mip bound is
    /// conservative.
    fn draw_key(
        &self,
        key: PomPipelineKey,
        uniform: &PomUniform,
        view: &mut DrawView<'_>,
    ) -> PomPipelineKey {
        let normal_mapping = key.normal_mapping();
        // A triplanar draw's texture density is its scale's, not its mesh's texture
        // coordinates' (which the mip bound reads).
        if key == normal_mapping || key.triplanar {
            return key;
        }
        // The uniform holds the sanitized threshold and the height texture as bound.
        let texture = TextureFacts {
            width: uniform.height_texture_width as u32,
            height: uniform.height_texture_height as u32,
            mip_levels: uniform.height_mip_levels as u32,
        };
        if view
            .lowest_mip(&texture)
            .is_some_and(|mip| mip >= uniform.params.lod_threshold)
        {
            normal_mapping
        } else {
            key
        }
    }
}

impl ParallaxOcclusionMaterial {
    /// The image the height is read from: its own texture, or the normal map (alpha).
    fn height_image(&self) -> Option<AssetId<Image>> {
        match &self.height_map {
            Some(HeightSource::Texture(handle)) => Some(handle.id()),
            Some(HeightSource::NormalMapAlpha) => self.normal_map.as_ref().map(Handle::id),
            None => None,
        }
    }
}

/// The product's materials: draws every entity that has a [`ParallaxOcclusionMaterial`] (its
/// own, or a `Handle` to one shared in `Assets<ParallaxOcclusionMaterial>`), a `Handle<Mesh>` and
/// a transform, keeps dynamic height fields' normals up to date, and adds
/// [`crate::LitPlugin`] (which draws every other mesh) unless it is there. Add it after
/// [`crate::RenderPlugin`] (or use [`crate::DefaultPlugins`]).
#[derive(Clone, Copy, Debug, Default)]
pub struct PomPlugin;

impl Plugin for PomPlugin {
    fn build(&self, app: &mut App) {
        app.add_plugin(crate::LitPlugin)
            .add_plugin(MaterialPlugin::<ParallaxOcclusionMaterial>::default());
        app.add_system(crate::Stage::Prepare, crate::derive_dynamic_normals);
        app.add_system(crate::Stage::Extract, warn_about_unsuitable_meshes);
    }

    fn finish(&self, app: &mut App) -> Result<(), crate::BoxedError> {
        let gpu = app
            .resources
            .get::<crate::GpuContext>()
            .ok_or(crate::material::MissingRenderPlugin)?;
        let sobel = crate::SobelPass::new(gpu);
        app.insert_resource(sobel);
        Ok(())
    }
}
