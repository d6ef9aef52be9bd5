//! `ParallaxOcclusionMaterial`: the artist-facing parameters, each declared once with its
//! default, limits, unit and help (`material_parameters!`; the lighting ones shared with the
//! lit material, `with_lighting_parameters!`), and the checks between them.

use super::layers::{
    LayersError, ParallaxLayers, layer_problems, layers_are_valid, sanitized_layers,
};
use crate::material::{LimitError, ParamGroup, ParamSpec};
use crate::{Handle, HeightConvention, Image, LightingModel};

/// Highest `layer_blend_contrast`: at 1 the mix would jump from one layer to the next, and the
/// march's refinement between two steps would find no crossing to converge on.
pub const MAX_BLEND_CONTRAST: f32 = 0.99;

crate::choice_enum! {
    /// How the ray/height-field intersection is found. One march serves every method; they
    /// differ in how many samples they take and how they refine the crossing.
    pub enum ParallaxMethod: "METHOD" {
        /// No parallax: the texture coordinate is used as is (normal mapping only).
        NormalMapping = "normal",
        /// One height sample shifted along the view, with offset limiting (Welsh 2004).
        ParallaxOffset = "offset",
        /// Steep parallax (McGuire 2005): linear search, shades the first sample below.
        Steep = "steep",
        /// Parallax occlusion mapping (Tatarchuk 2006): linear search, then secant_steps secants.
        Occlusion = "pom",
        /// Relief mapping (Policarpo 2005): linear search, then relief_binary_steps bisections.
        Relief = "relief",
        /// Exact intersection over a maximum-height pyramid (Tevs et al. 2008): no missed peaks.
        MaxMip = "maxmip",
    }
}

crate::choice_enum! {
    /// Self-shadowing of the height field.
    pub enum ShadowMode: "SHADOWS" {
        /// No self-shadowing.
        Off = "off",
        /// March towards the light; any blocker makes the point fully dark (McGuire; exact with MaxMip).
        Hard = "hard",
        /// Tatarchuk's penumbra estimate from weighted height samples along the light ray.
        Soft = "soft",
    }
}

crate::choice_enum! {
    /// Whether the relief shows at the outline of the surface (T §5.6: POM's silhouettes are
    /// the polygon's). With `uv_bounds`, a view ray that leaves the texture bounds
    /// (`bounds_u_min` ..) before it meets the relief leaves the surface, and the pixel shows
    /// what lies behind: for surfaces the texture does not wrap around (a crate's face, a sign,
    /// a tile). With `curved`, the view ray is bent by the surface's curvature along its
    /// direction (Oliveira and Policarpo 2005, here from the interpolated normal's change across
    /// the pixel), and a ray that rises out of the relief's shell without meeting it leaves the
    /// surface: for closed, curved surfaces.
    pub enum Silhouette: "SILHOUETTE" {
        /// The outline is the polygon's: every pixel of it shows the relief.
        Off = "off",
        /// A ray leaving the texture bounds before it meets the relief leaves the surface (a crate's face, a sign).
        UvBounds = "uv_bounds",
        /// The ray bends with the surface's curvature and leaves where it rises out of the relief (a sphere, a rock).
        Curved = "curved",
    }
}

crate::choice_enum! {
    /// The unit of `height_scale`.
    pub enum HeightUnits: "UNITS" {
        /// Texture units (T's fHeightMapRange): depth changes with tiling and object scale.
        Texture = "texture",
        /// World units (Luna §3): the same depth under any tiling or object scale.
        World = "world",
    }
}

crate::choice_enum! {
    /// How the material's maps are laid on the mesh.
    pub enum TextureMapping: "MAPPING" {
        /// By the mesh's texture coordinates (TEXCOORD_0) and tangents.
        Uv = "uv",
        /// Projected along the world axes, mixed by the normal: meshes without usable UVs (rocks).
        Triplanar = "triplanar",
    }
}

/// Fewest world units one repeat of a triplanar projection spans (and the most):
/// `triplanar_scale`'s limits.
pub const TRIPLANAR_SCALE_LIMITS: (f32, f32) = (1e-3, 1e4);

fn is_triplanar(material: &ParallaxOcclusionMaterial) -> bool {
    material.mapping == TextureMapping::Triplanar
}

crate::choice_enum! {
    /// What the fragment shader outputs instead of the lit colour, for inspection.
    pub enum DebugView: "DEBUG" {
        /// The lit surface.
        None = "none",
        /// Tatarchuk's LOD tint: blue grows through the LOD band, deepest where only normal maps.
        Lod = "lod",
        /// The mip level as grey: black = level 0, white = the smallest level.
        Mip = "mip",
        /// Height fetches as a heat map, black (none) through red and yellow to white (max).
        Samples = "samples",
        /// Raw: R, G = fract(u, v) of the final coordinate; B = 1 full march, 0.5 band, 0 none.
        Uv = "uv",
        /// The self-shadowing visibility of the first light (1 = lit), raw, in R, G and B.
        Shadow = "shadow",
        /// The scene-shadow (shadow map) visibility of the first light (1 = lit), raw, in R, G, B.
        SceneShadow = "scene_shadow",
        /// The shading normal in tangent space, encoded as n × 0.5 + 0.5.
        Normal = "normal",
    }
}

/// Where the height comes from.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum HeightSource {
    /// A texture of its own; the red channel is read (grey images have it in every channel).
    Texture(Handle<Image>),
    /// The alpha channel of the normal map, as McGuire and Tatarchuk pack it.
    NormalMapAlpha,
}

impl HeightSource {
    /// The texture channel holding the height: red (its own texture) or alpha.
    pub fn channel(&self) -> crate::Channel {
        match self {
            HeightSource::Texture(_) => crate::Channel::Red,
            HeightSource::NormalMapAlpha => crate::Channel::Alpha,
        }
    }
}

/// Largest magnitude of a texture-bounds coordinate (`bounds_u_min` ..): far past any atlas or
/// count of repeats, small enough that a float texture coordinate still resolves a texel.
pub const BOUNDS_LIMIT: f32 = 4096.0;

fn clips_at_bounds(material: &ParallaxOcclusionMaterial) -> bool {
    material.silhouette == Silhouette::UvBounds
}

/// Most height samples one march may take; larger `max_samples` are clamped to it.
pub const MAX_SAMPLES_LIMIT: u32 = 256;
/// The most lights a pixel gives the relief's self-shadows (as many as lights.wgsl ranks).
pub const MAX_SHADOWED_LIGHTS: u32 = crate::render::lights::MAX_RANKED_LIGHTS;

crate::with_lighting_parameters! {
    /// A surface that looks displaced: Tatarchuk's parallax occlusion mapping with soft
    /// self-shadows and per-pixel LOD. Put it on an entity with a `Handle<Mesh>` and a transform.
    ///
    /// Defaults are Tatarchuk's: samples 8..50, LOD threshold 4, soft shadows with softening 0.58.
    /// The height field is pushed *down* from the polygon: the brightest height is at the surface.
    /// Every parameter is declared once, below; [`ParallaxOcclusionMaterial::PARAMETERS`] lists
    /// them with their limits and help.
    #[derive(Clone, Debug, PartialEq)]
    pub struct ParallaxOcclusionMaterial {
        inputs {
            /// sRGB colour texture, sampled at the displaced coordinate (white when absent).
            base_color_texture: Option<Handle<Image>> = None,
            /// Tangent-space normal map (OpenGL convention), sampled at the displaced coordinate;
            /// flat when absent.
            normal_map: Option<Handle<Image>> = None,
            /// Where the height field comes from; `None` means flat (no parallax).
            height_map: Option<HeightSource> = None,
            /// Up to four layers mixed by height (terrain): when set, they replace the three
            /// maps above, and the relief is the blend of their heights.
            layers: Option<ParallaxLayers> = None,
        }
        parameters {
            /// How the view ray meets the height field.
            method: ParallaxMethod = ParallaxMethod::Occlusion, ParamSpec::choice::<ParallaxMethod>()
                .group(ParamGroup::Method);
            /// How the maps are laid on the mesh: its texture coordinates (uv), or projected
            /// along the world axes (triplanar: meshes without usable UVs).
            mapping: TextureMapping = TextureMapping::Uv, ParamSpec::choice::<TextureMapping>()
                .group(ParamGroup::Method);
            /// World units one repeat of a triplanar projection spans.
            triplanar_scale: f32 = 1.0,
                ParamSpec::float(TRIPLANAR_SCALE_LIMITS.0, TRIPLANAR_SCALE_LIMITS.1)
                .editor(0.05, 10.0).logarithmic().unit("world units").group(ParamGroup::Method)
                .applies_when(is_triplanar);
            /// How narrow the bands where triplanar projections meet are: 1 blends widely,
            /// higher keeps each face on its own projection.
            triplanar_sharpness: f32 = 4.0, ParamSpec::float(1.0, 64.0).editor(1.0, 32.0)
                .group(ParamGroup::Method)
                .applies_when(is_triplanar);
            /// Bisection steps relief mapping takes after its linear search: more is sharper.
            relief_binary_steps: u32 = 6, ParamSpec::integer(1, 16)
                .group(ParamGroup::Method)
                .applies_when(|material| material.method == ParallaxMethod::Relief);
            /// Secant steps parallax occlusion mapping takes after its linear search (1 is
            /// Tatarchuk's): each more costs a sample and moves the hit onto curved slopes.
            secant_steps: u32 = 1, ParamSpec::integer(1, 8)
                .group(ParamGroup::Method)
                .applies_when(|material| material.method == ParallaxMethod::Occlusion);
            /// Depth of the relief from white to black of the height map, in the units
            /// height_units picks (T's fHeightMapRange).
            height_scale: f32 = 0.05, ParamSpec::float(0.0, 10.0).editor(0.0, 0.2)
                .unit("texture/world units");
            /// Texture units change the depth with tiling and object scale; world units do not.
            height_units: HeightUnits = HeightUnits::Texture, ParamSpec::choice::<HeightUnits>()
                .group(ParamGroup::Method);
            /// Whether white in the height map is the top (height) or the deepest point (depth).
            height_convention: HeightConvention = HeightConvention::Height,
                ParamSpec::choice::<HeightConvention>()
                .group(ParamGroup::Method);
            /// Write the displaced depth, so other geometry meets the relief where it is (slower).
            depth_offset: bool = false, ParamSpec::toggle()
                .group(ParamGroup::Method);
            /// Height samples looking straight at the surface (T eq. 1's n_min): fewer is faster.
            min_samples: u32 = 8, ParamSpec::integer(1, MAX_SAMPLES_LIMIT).logarithmic();
            /// Height samples at grazing angles (T eq. 1's n_max): raise it if layers show.
            max_samples: u32 = 50, ParamSpec::integer(1, MAX_SAMPLES_LIMIT).logarithmic();
            /// Start each march a per-pixel, per-frame part of a step early: with TAA, few
            /// samples settle to the image of many (without it, layers turn to noise).
            jitter_march: bool = false, ParamSpec::toggle()
                .group(ParamGroup::Method);
            /// Mip level past which only normal mapping runs (T's nLODThreshold).
            lod_threshold: f32 = 4.0, ParamSpec::float(0.0, 16.0).editor(0.0, 12.0)
                .unit("mip levels");
            /// Width of the band below the threshold where parallax fades out: wider hides it.
            lod_band: f32 = 1.0, ParamSpec::float(0.01, 16.0).editor(0.01, 4.0)
                .unit("mip levels");
            /// Whether the relief shows at the outline: off, clipped where the view ray leaves
            /// the texture bounds (uv_bounds), or where it rises out of a curved surface (curved).
            silhouette: Silhouette = Silhouette::Off, ParamSpec::choice::<Silhouette>()
                .group(ParamGroup::Silhouette);
            /// Smallest u of the surface's texture (uv_bounds): 0, or an atlas rectangle's edge.
            bounds_u_min: f32 = 0.0, ParamSpec::float(-BOUNDS_LIMIT, BOUNDS_LIMIT)
                .editor(-1.0, 1.0).unit("texture units").group(ParamGroup::Silhouette)
                .applies_when(clips_at_bounds);
            /// Largest u (uv_bounds): 1, or the count of repeats across the surface.
            bounds_u_max: f32 = 1.0, ParamSpec::float(-BOUNDS_LIMIT, BOUNDS_LIMIT)
                .editor(0.0, 8.0).unit("texture units").group(ParamGroup::Silhouette)
                .applies_when(clips_at_bounds);
            /// Smallest v of the surface's texture (uv_bounds).
            bounds_v_min: f32 = 0.0, ParamSpec::float(-BOUNDS_LIMIT, BOUNDS_LIMIT)
                .editor(-1.0, 1.0).unit("texture units").group(ParamGroup::Silhouette)
                .applies_when(clips_at_bounds);
            /// Largest v (uv_bounds).
            bounds_v_max: f32 = 1.0, ParamSpec::float(-BOUNDS_LIMIT, BOUNDS_LIMIT)
                .editor(0.0, 8.0).unit("texture units").group(ParamGroup::Silhouette)
                .applies_when(clips_at_bounds);
            /// How much the layer standing higher wins where layers' weights overlap: 0 mixes by
            /// weight alone, towards 0.99 the higher layer covers the lower one.
            layer_blend_contrast: f32 = 0.5, ParamSpec::float(0.0, MAX_BLEND_CONTRAST)
                .group(ParamGroup::Method)
                .applies_when(|material| material.layers.is_some());
            /// Whether bumps cast shadows on the surface: off, hard-edged, or soft.
            shadows: ShadowMode = ShadowMode::Soft, ParamSpec::choice::<ShadowMode>();
            /// Penumbra width of soft shadows: larger is softer (0.58 is Tatarchuk's look).
            shadow_softening: f32 = 0.58, ParamSpec::float(0.01, 100.0).editor(0.01, 4.0)
                .logarithmic()
                .applies_when(|material| material.shadows == ShadowMode::Soft);
            /// How many of the lights at a pixel get the relief's self-shadows: the brightest
            /// there; the rest light it unshadowed by its relief (cheaper under many lights).
            shadowed_lights: u32 = 4, ParamSpec::integer(0, MAX_SHADOWED_LIGHTS)
                .group(ParamGroup::Lighting)
                .applies_when(|material| material.shadows != ShadowMode::Off);
            /// How much the relief hides the environment's light where it hides the sky (the grout
            /// between cobbles): 0 not at all, 1 as the height field's horizon says.
            relief_occlusion: f32 = 1.0, ParamSpec::float(0.0, 1.0).group(ParamGroup::Lighting);
            /// Reflection model: Phong and Blinn-Phong use specular and shininess, Cook-Torrance
            /// and GGX-Lambert roughness and metallic.
            lighting: LightingModel = LightingModel::Phong, ParamSpec::choice::<LightingModel>()
                .group(ParamGroup::Lighting);
            /// An inspection image instead of the lit surface (LOD, mip, samples, uv, ...).
            debug_view: DebugView = DebugView::None, ParamSpec::choice::<DebugView>()
                .group(ParamGroup::Debug);
        }
    }
    preset PomPreset PresetExtras {
        /// A layered material's layers: each one's tiling and depth share, and the files of
        /// its maps relative to the preset (`LayerPreset`).
        #[serde(skip_serializing_if = "Option::is_none")]
        layers: Option<Vec<super::LayerPreset>>,
        /// The file of a layered material's weight map, relative to the preset.
        #[serde(skip_serializing_if = "Option::is_none")]
        layer_weights_texture: Option<String>,
    };
    patch PomPatch;
    gpu PomParams;
}

/// A parameter of [`ParallaxOcclusionMaterial`] that is out of range.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum PomMaterialError {
    /// A parameter outside its declared limits (NaN, too small, too large).
    #[error(transparent)]
    Limit(#[from] LimitError),
    /// The sample bounds are inverted.
    #[error("min_samples ({min}) is greater than max_samples ({max})")]
    SamplesInverted {
        /// min_samples.
        min: u32,
        /// max_samples.
        max: u32,
    },
    /// The texture bounds enclose no area along one axis (minimum at or above maximum).
    #[error(
        "bounds_{axis}_min ({min}) is not below bounds_{axis}_max ({max}): the bounds enclose no area"
    )]
    BoundsEmpty {
        /// `u` or `v`.
        axis: char,
        /// The axis's minimum.
        min: f32,
        /// Its maximum.
        max: f32,
    },
    /// A problem of the layers.
    #[error(transparent)]
    Layers(#[from] LayersError),
    /// Layers with triplanar mapping: their weight map and tiling are laid out in texture
    /// coordinates.
    #[error(
        "mapping is triplanar but the material has layers, which are laid out in texture coordinates: they are drawn with uv mapping"
    )]
    TriplanarLayers,
}

impl ParallaxOcclusionMaterial {
    /// Every parameter problem, in declaration order; empty when the material is valid.
    pub fn problems(&self) -> Vec<PomMaterialError> {
        let mut problems: Vec<PomMaterialError> = self
            .limit_problems()
            .into_iter()
            .map(PomMaterialError::from)
            .collect();
        if self.min_samples > self.max_samples {
            problems.push(PomMaterialError::SamplesInverted {
                min: self.min_samples,
                max: self.max_samples,
            });
        }
        for (axis, min, max) in self.bounds_axes() {
            // NaN is a limit problem already; bounds matter only to the silhouette that reads
            // them.
            if clips_at_bounds(self) && min >= max {
                problems.push(PomMaterialError::BoundsEmpty { axis, min, max });
            }
        }
        if self.layers.is_some() && is_triplanar(self) {
            problems.push(PomMaterialError::TriplanarLayers);
        }
        if let Some(layers) = &self.layers {
            problems.extend(
                layer_problems(layers)
                    .into_iter()
                    .map(PomMaterialError::from),
            );
        }
        problems
    }

    /// Each axis of the texture bounds: its name, minimum and maximum.
    fn bounds_axes(&self) -> [(char, f32, f32); 2] {
        [
            ('u', self.bounds_u_min, self.bounds_u_max),
            ('v', self.bounds_v_min, self.bounds_v_max),
        ]
    }

    /// Whether every parameter is valid (no allocation: the renderer asks every frame).
    pub fn is_valid(&self) -> bool {
        self.first_limit_problem().is_none()
            && self.min_samples <= self.max_samples
            && (!clips_at_bounds(self) || self.bounds_axes().iter().all(|(_, min, max)| min < max))
            && self
                .layers
                .as_ref()
                .is_none_or(|layers| layers_are_valid(layers) && !is_triplanar(self))
    }

    /// Checks every parameter; the first problem is the error.
    ///
    /// # Example
    /// ```
    /// let mut material = pom::ParallaxOcclusionMaterial::default();
    /// assert!(material.validate().is_ok());
    /// material.min_samples = 60;
    /// assert_eq!(
    ///     material.validate().unwrap_err().to_string(),
    ///     "min_samples (60) is greater than max_samples (50)"
    /// );
    /// ```
    pub fn validate(&self) -> Result<(), PomMaterialError> {
        match self.problems().into_iter().next() {
            Some(problem) => Err(problem),
            None => Ok(()),
        }
    }

    /// A copy with every parameter brought into range: NaN and ∞ become the default, numbers are
    /// clamped to their limits, inverted sample and texture bounds are swapped, and texture
    /// bounds of no area become the default [0, 1], and layers are mapped by uv. This is what the renderer draws; it logs
    /// [`Self::problems`] once per change.
    pub fn sanitized(&self) -> Self {
        let mut clean = self.clone();
        clean.clamp_to_limits();
        if clean.min_samples > clean.max_samples {
            std::mem::swap(&mut clean.min_samples, &mut clean.max_samples);
        }
        for (min, max) in [
            (&mut clean.bounds_u_min, &mut clean.bounds_u_max),
            (&mut clean.bounds_v_min, &mut clean.bounds_v_max),
        ] {
            if *min > *max {
                std::mem::swap(min, max);
            } else if *min == *max {
                (*min, *max) = (0.0, 1.0);
            }
        }
        if let Some(layers) = &self.layers {
            clean.layers = Some(sanitized_layers(layers));
            clean.mapping = TextureMapping::Uv;
        }
        clean
    }
}

#[cfg(test)]
#[path = "material_tests.rs"]
mod tests;
