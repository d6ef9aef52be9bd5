//! [`ShadedMaterial`]: a material written as one WGSL shading function over a documented surface
//! input; the core writes every entry point around it, so it runs on both paths.

use super::{DeclaredMaterial, Material};
use crate::gpu::{DefaultTexture, MaterialTextures, ShaderEntry, TextureFacts};
use crate::render::frame_group::MATERIAL_UNIFORMS;
use crate::render::shaders::{self, ComposedShader, GeneratedWgsl, WgslFile};

/// The surface input, and the helpers a shading function samples textures and shadows with.
pub const SURFACE_INPUT: WgslFile = crate::wgsl_file!("material/surface_input.wgsl");
/// The forward path's fragment entry around `shade`.
pub const SHADED_FORWARD: WgslFile = crate::wgsl_file!("material/shaded_forward.wgsl");
/// The deferred resolve's compute entry around `shade`.
pub const SHADED_RESOLVE: WgslFile = crate::wgsl_file!("material/shaded_resolve.wgsl");
/// The fragment entries of a material that cuts holes ([`ShadedMaterial::CUTS_OUT`]).
pub const SHADED_CUT_OUT: WgslFile = crate::wgsl_file!("material/shaded_cut_out.wgsl");
/// The visibility-pass entry of a material that cuts holes.
pub const SHADED_CUT_OUT_VISIBILITY: WgslFile =
    crate::wgsl_file!("material/shaded_cut_out_visibility.wgsl");

/// A material written as a shading function: declare its parameters and textures with
/// [`crate::material_parameters!`], write `shade` in WGSL, and the core composes its forward
/// fragment, its deferred resolve and its shadow, prepass and visibility draws (its surface lies
/// on its polygons: no fragment stage of its own there). It runs on the deferred path, shading
/// in the compute resolve.
///
/// The shading file defines
/// `fn shade(surface: SurfaceInput, material: MaterialParams) -> vec4<f32>`, which returns
/// scene-linear light and alpha. It sees:
/// - `SurfaceInput` (`plugin/src/material/surface_input.wgsl`): position, normal, tangent frame,
///   uv, vertex colour, direction to the eye, pixel footprint, draw index, facing;
/// - its parameters as `material` (colours as `array<f32, 4>`: `rgba(material.color)`), of
///   type `MaterialParams` (or the `gpu` name a declaration in the full form gives);
/// - each texture input under its field name, sampled with `texture_at(texture, surface)`;
/// - the lights (`light_count()`, `light_at(i, position)`, `frame.ambient`) and the scene's
///   shadows (`surface_shadow(i, surface)`);
/// - `perturbed_normal`, `safe_normalize` and the rest of the core's `tangent_space.wgsl`.
///
/// A material that cuts holes in its surface (an alpha mask, a grille) says so with
/// [`ShadedMaterial::CUTS_OUT`]. One that moves its depth (a parallax relief) or wants entry
/// points of its own implements [`Material`] itself instead.
pub trait ShadedMaterial: DeclaredMaterial + hecs::Component + PartialEq + Default {
    /// The WGSL file that defines `shade`.
    const SHADING: WgslFile;
    /// Whether the material cuts holes in its surface (false by default). The shading file then
    /// also defines `fn covers(surface: SurfaceInput, material: MaterialParams) -> bool`, and
    /// the core leaves what it does not cover out of the depth prepass, every shadow map, the
    /// visibility pass and the forward path's image; `shade` itself never discards.
    const CUTS_OUT: bool = false;
}

/// The composed shaders of a shaded material, made once per type.
trait ShadedShaders {
    const FORWARD: ComposedShader;
    const DEFERRED: ComposedShader;
}

/// A shaded material's composition: the generated constants after `$first`, the library files,
/// its shading file and the forward entry, then `$more`.
macro_rules! shaded_shader {
    ($T:ty, [$($first:expr),*], [$($more:expr),*]) => {
        ComposedShader {
            name: <$T as DeclaredMaterial>::TYPE_NAME,
            constants: &[$($first as GeneratedWgsl,)* declarations::<$T> as GeneratedWgsl],
            files: &[
                shaders::FRAME,
                crate::render::lights::LIGHTS_WGSL,
                shaders::PARAMS,
                shaders::MESH_VERTEX,
                shaders::SHADOWS,
                crate::render::environment::SPHERICAL_HARMONICS,
                crate::render::environment::ENVIRONMENT,
                shaders::TANGENT_SPACE,
                SURFACE_INPUT,
                <$T as ShadedMaterial>::SHADING,
                SHADED_FORWARD,
                $($more,)*
            ],
        }
    };
}

/// A shaded material's deferred composition: the forward one's, its visibility pass (`$cut`:
/// the files a material that cuts holes adds) and the compute resolve.
macro_rules! shaded_deferred_shader {
    ($T:ty, [$($cut:expr),*]) => {
        shaded_shader!(
            $T,
            [shaders::deferred_header],
            [
                $($cut,)*
                shaders::VISIBILITY,
                shaders::VISIBILITY_READ,
                crate::material::DEFERRED_RESOLVE,
                SHADED_RESOLVE
            ]
        )
    };
}

impl<T: ShadedMaterial> ShadedShaders for T {
    const FORWARD: ComposedShader = if T::CUTS_OUT {
        shaded_shader!(T, [], [SHADED_CUT_OUT])
    } else {
        shaded_shader!(T, [], [])
    };
    const DEFERRED: ComposedShader = if T::CUTS_OUT {
        shaded_deferred_shader!(T, [SHADED_CUT_OUT, SHADED_CUT_OUT_VISIBILITY])
    } else {
        shaded_deferred_shader!(T, [])
    };
}

/// `name` of the entry points that cut holes where `T` does, else `whole`.
fn entry<T: ShadedMaterial>(whole: &'static str, cut_out: &'static str) -> ShaderEntry {
    ShaderEntry::entry(if T::CUTS_OUT { cut_out } else { whole })
}

/// `T`'s generated WGSL: its parameter struct, the per-draw array of it (`materials`), its
/// textures at group 1 in slot order and the trilinear `material_sampler` after them.
fn declarations<T: DeclaredMaterial>() -> String {
    let mut wgsl = T::params_wgsl();
    wgsl.push_str(&format!(
        "@group(0) @binding({MATERIAL_UNIFORMS}) var<storage, read> materials: array<{}>;\n",
        T::PARAMS_WGSL_NAME
    ));
    for (binding, name) in T::TEXTURE_NAMES.iter().enumerate() {
        wgsl.push_str(&format!(
            "@group(1) @binding({binding}) var {name}: texture_2d<f32>;\n"
        ));
    }
    wgsl.push_str(&format!(
        "@group(1) @binding({}) var material_sampler: sampler;\n",
        T::TEXTURE_NAMES.len()
    ));
    wgsl
}

impl<T: ShadedMaterial> Material for T {
    type PerDraw = T::Params;
    type Key = ();
    const NAME: &'static str = T::TYPE_NAME;
    const PER_DRAW_WGSL_NAME: &'static str = T::PARAMS_WGSL_NAME;
    const TEXTURE_SLOTS: &'static [DefaultTexture] = <T as DeclaredMaterial>::TEXTURE_SLOTS;
    const SURFACE_ON_POLYGON: bool = !T::CUTS_OUT;

    fn shader() -> ComposedShader {
        T::FORWARD
    }

    fn deferred_shader() -> Option<ComposedShader> {
        Some(T::DEFERRED)
    }

    fn textures(&self) -> MaterialTextures {
        self.texture_images()
    }

    fn key(&self) {}

    fn fragment(_: ()) -> ShaderEntry {
        entry::<T>("fs_main", "fs_main_cut_out")
    }

    fn prepass_fragment(_: ()) -> Option<ShaderEntry> {
        T::CUTS_OUT.then(|| ShaderEntry::entry("fs_prepass_cut_out"))
    }

    fn visibility_fragment(_: ()) -> ShaderEntry {
        entry::<T>("fs_visibility", "fs_visibility_cut_out")
    }

    fn deferred_resolve(_: ()) -> Option<ShaderEntry> {
        Some(ShaderEntry::entry("cs_resolve"))
    }

    fn per_draw(&self, _: &[Option<TextureFacts>; crate::gpu::MAX_MATERIAL_TEXTURES]) -> T::Params {
        self.params()
    }

    fn problems(&self) -> Vec<String> {
        self.parameter_problems()
    }

    fn casts_with_frame_noise(&self) -> bool {
        // Only a cut-out's `covers` runs in the shadow pass, and it may dither by the noise.
        T::CUTS_OUT
    }
}
