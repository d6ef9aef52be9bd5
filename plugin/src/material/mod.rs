//! The material seam: a [`Material`] declares its GPU form (per-draw data, textures, WGSL,
//! pipeline key) and [`MaterialPlugin`] extracts, prepares and draws it; a [`ShadedMaterial`]
//! is one written as a WGSL shading function, around which the seam composes every entry
//! point. The core renderer never names a material; `LitMaterial` and
//! `ParallaxOcclusionMaterial` are two materials like any other.

mod batches;
mod declare;
mod deferred;
mod draw;
mod draw_order;
mod draw_view;
mod extract;
mod followed_models;
mod frame_bindings;
mod layout_check;
mod lowest_mip;
mod material_warnings;
mod mesh_pipeline;
mod pipelines;
mod plugin;
mod polygons;
mod registry;
mod resolve_tiles;
mod shaded;
mod shader_check;

pub use crate::gpu::{MAX_MATERIAL_TEXTURES, MaterialTextures, ShaderEntry, TextureFacts};
pub use crate::shader::{
    Choice, ChoiceInfo, LayoutMismatch, MemberLayout, WgslLayout, check_wgsl_layout,
};
// The parameter layer's names, where materials have always found them.
pub use crate::parameters::{
    GpuParam, LimitError, Param, ParamError, ParamGroup, ParamKind, ParamSpec, ParamType,
    ParamValue, every_parameter_changed,
};
pub(crate) use batches::ExtractedDraw;
pub use declare::{DeclaredMaterial, PresetExtras};
pub use deferred::{CANDIDATES, DEFERRED_RESOLVE, deferred_twin};
pub use draw_view::DrawView;
pub(crate) use extract::ExtractedMaterials;
pub use layout_check::check_material_layout;
pub(crate) use lowest_mip::{MeshLodBounds, MeshLodCache, PixelFootprint};
pub use material_warnings::MaterialWarnings;
pub use plugin::{
    MaterialPlugin, MissingRenderPlugin, TooManyDerivedTextureSlots, TooManyTextureSlots,
    draw_meshes_without_material, drawn_in_opaque_and_resolve, drawn_keys, pipelines_ready,
};

#[cfg(feature = "dev-tools")]
pub(crate) use registry::MaterialRegistry;
pub use resolve_tiles::DEFERRED_CLASSIFY_SHADER;
pub use shaded::{
    SHADED_CUT_OUT, SHADED_CUT_OUT_VISIBILITY, SHADED_FORWARD, SHADED_RESOLVE, SURFACE_INPUT,
    ShadedMaterial,
};
pub use shader_check::MaterialShaderError;

use std::fmt::Debug;
use std::hash::Hash;

use crate::gpu::{DefaultTexture, DerivedTextures, MAX_DERIVED_TEXTURES};
use crate::render::shaders::ComposedShader;

/// A surface type the renderer can draw: put it on an entity with a `Handle<Mesh>` and a
/// transform, and add [`MaterialPlugin<Self>`].
///
/// The shader lists the core's `FRAME` and `MESH_VERTEX` files first (see
/// [`crate::render::shaders`]): they declare (group 0) `frame` (binding 0) and the per-draw
/// `transforms` (binding 1), the vertex entry `vs_main` and its output `VertexOut`
/// (`object_index` indexes per-draw arrays). The material declares its
/// own per-draw `array<PerDraw>` at group 0 binding 2 and its textures at group 1, bindings
/// `0..TEXTURE_SLOTS.len()`, followed by one trilinear repeating sampler.
pub trait Material: hecs::Component + Clone + PartialEq + Default {
    /// One element of the per-draw storage array the shader reads (`materials[object_index]`):
    /// a `#[repr(C)]` Pod struct laid out like the WGSL struct
    /// [`Material::PER_DRAW_WGSL_NAME`] (check it with [`check_wgsl_layout`]).
    type PerDraw: bytemuck::Pod + PartialEq + WgslLayout + Send + Sync;
    /// What selects a pipeline variant: draws with equal keys share one pipeline.
    type Key: Copy + Eq + Hash + Ord + Debug + Send + Sync + 'static;

    /// A name for labels and messages.
    const NAME: &'static str;
    /// The WGSL name of [`Material::PerDraw`].
    const PER_DRAW_WGSL_NAME: &'static str;
    /// The texture bound in each slot when the material has none there (at most
    /// [`MAX_MATERIAL_TEXTURES`]; more is an error when the plugin starts).
    const TEXTURE_SLOTS: &'static [DefaultTexture];
    /// Whether the surface lies on the material's polygons and covers them whole: no fragment
    /// entry discards or writes its depth (true by default). The core then writes its depth
    /// prepass, shadow maps and deferred visibility pass without a fragment stage of the
    /// material's, and composes its deferred shader. A material that discards (alpha masks) or
    /// moves its depth (parallax relief) says `false` and names its own prepass fragment; one
    /// that says `true` but discards is an error when its plugin starts.
    const SURFACE_ON_POLYGON: bool = true;

    /// The material's WGSL (entry points and its own library files).
    fn shader() -> ComposedShader;
    /// The images in the texture slots.
    fn textures(&self) -> MaterialTextures;
    /// The pipeline variant.
    fn key(&self) -> Self::Key;
    /// The fragment entry point and constants of `key`'s pipeline in the opaque phase when
    /// the frame has no depth prepass (it tests and writes depth itself).
    fn fragment(key: Self::Key) -> ShaderEntry;
    /// Whether `key` blends over what is behind it: its draws then go to the transparent phase
    /// (one list with every material's blended draws, farthest first by the view depth of each
    /// draw's centre; depth tested, not in the prepass) instead of the prepass and the opaque
    /// phase. `false` by default.
    fn blends(_key: Self::Key) -> bool {
        false
    }
    /// Which faces `key`'s pipelines cull: back faces by default; `None` draws both sides
    /// (double-sided surfaces, whose shaders then see `front_facing` false on the back).
    fn cull_mode(_key: Self::Key) -> Option<wgpu::Face> {
        Some(wgpu::Face::Back)
    }
    /// How many textures the GPU derives for the material from its images
    /// ([`Material::derived_textures`]; at most [`MAX_DERIVED_TEXTURES`]). They are bound at
    /// group 1 after the sampler, bindings `TEXTURE_SLOTS.len() + 1 ..`, as unfilterable float
    /// textures (`textureLoad`). 0 by default.
    const DERIVED_TEXTURE_SLOTS: usize = 0;
    /// The textures derived from the material's images, one per derived slot, each by a
    /// [`crate::gpu::TextureDeriver`] the material names (the parallax material's
    /// `MaxHeightPyramid`): built on the GPU when first used and after every re-upload of their
    /// source; `None` binds one texel of
    /// 1.0. None by default.
    fn derived_textures(&self) -> DerivedTextures {
        [None; MAX_DERIVED_TEXTURES]
    }
    /// The fragment stage of `key` in the depth prepass: `None` (the default) writes the
    /// rasterized depth with no fragment shader at all; a material whose fragments move their
    /// depth (parallax depth offset) names the entry point that writes it.
    fn prepass_fragment(_key: Self::Key) -> Option<ShaderEntry> {
        None
    }
    /// The fragment stage of `key` in a shadow map (the light's view, depth only):
    /// [`Material::prepass_fragment`] by default. A material whose surface lies elsewhere than
    /// its polygon (parallax relief) names the entry point that writes that depth.
    fn shadow_fragment(key: Self::Key) -> Option<ShaderEntry> {
        Self::prepass_fragment(key)
    }
    /// The fragment stage of `key` in the opaque phase after a depth prepass (depth tested
    /// `LessEqual`, never written): [`Material::fragment`] by default.
    fn fragment_after_prepass(key: Self::Key) -> ShaderEntry {
        Self::fragment(key)
    }
    /// The material's shader for the deferred path ([`crate::RenderPath`]). By default, for a
    /// material whose surface lies on its polygon ([`Material::SURFACE_ON_POLYGON`]), the core
    /// composes it ([`deferred_twin`]): the material then writes the
    /// visibility pass with the core's `fs_visibility` and shades in the opaque phase on both
    /// paths. A material of its own kind returns the constants of [`Material::shader`] after
    /// [`crate::render::shaders::deferred_header`], its files, then the core's
    /// [`crate::render::shaders::VISIBILITY`] (and [`crate::render::shaders::VISIBILITY_READ`]
    /// with [`DEFERRED_RESOLVE`] for a compute resolve) and its own
    /// deferred entry points. `None` opts out: an app that draws the material renders forward
    /// (the deferred path needs every opaque draw in the visibility buffer), and says so once.
    fn deferred_shader() -> Option<ComposedShader> {
        Self::SURFACE_ON_POLYGON.then(|| deferred::deferred_twin(&Self::shader()))
    }
    /// The variant drawn in `key`'s place while `key`'s pipelines compile on a worker thread
    /// ([`crate::gpu::PipelineCompilation::background`]): a cheap one that looks alike. The
    /// fallback of the default material's key is compiled when the plugin starts and stands in
    /// for any variant whose own fallback is not ready either. `None` (the default): the
    /// default material's key itself stands in.
    fn fallback_key(_key: Self::Key) -> Option<Self::Key> {
        None
    }
    /// The fragment stage of `key` in the visibility pass (the deferred path's prepass, which
    /// also writes each pixel's id): the core's `fs_visibility` by default. A material whose
    /// [`Material::prepass_fragment`] discards or moves the depth names its twin, which does the
    /// same and then calls `keep_visible(position, depth, visibility_id(...))`.
    fn visibility_fragment(_key: Self::Key) -> ShaderEntry {
        ShaderEntry::entry("fs_visibility")
    }
    /// The compute entry point (and constants) that shades `key`'s pixels from the visibility
    /// buffer on the deferred path, in its deferred shader; `None` (the default): `key` draws in
    /// the opaque phase on both paths.
    fn deferred_resolve(_key: Self::Key) -> Option<ShaderEntry> {
        None
    }
    /// Whether `key`'s visible depth lies behind its polygon (parallax depth offset) and its
    /// [`Material::deferred_resolve`] settles it: on the deferred path its polygons then draw
    /// in the candidate pass, not the visibility pass ([`CANDIDATES`], composed after the
    /// visibility file, keeps the nearest one per pixel by its polygon's depth), and its
    /// resolve, which runs before every other, marches each candidate once and calls
    /// `settle_candidate` with the depth it found. `false` by default.
    fn settles_depth_in_resolve(_key: Self::Key) -> bool {
        false
    }
    /// This material's element of the per-draw array, given the textures as the GPU holds them
    /// (`None`: the slot's default).
    fn per_draw(&self, textures: &[Option<TextureFacts>; MAX_MATERIAL_TEXTURES]) -> Self::PerDraw;
    /// What is wrong with the parameters, one line each (logged once per change; the per-draw
    /// data must still be drawable). Empty by default.
    fn problems(&self) -> Vec<String> {
        Vec::new()
    }
    /// Whether this material's shadow casters read the frame's per-frame noise (a march
    /// jittered under TAA): where a caster does, every shadow map is drawn again on each frame
    /// the noise moves, else a map is kept while nothing it shows changed. `true` by default (a
    /// caster shader of one's own may read it).
    fn casts_with_frame_noise(&self) -> bool {
        true
    }
    /// The key one draw uses, knowing its per-draw data (as [`Material::per_draw`] packed it) and its
    /// place in the view: a material may pick a cheaper variant for a far-away object. `key` by
    /// default.
    fn draw_key(
        &self,
        key: Self::Key,
        _per_draw: &Self::PerDraw,
        _view: &mut DrawView<'_>,
    ) -> Self::Key {
        key
    }
}
