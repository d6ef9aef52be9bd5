//! The plugin's WGSL, embedded at build time and composed from shared library files.
//!
//! WGSL has no `#include`: each entry shader is the concatenation of the library files it needs
//! and its own file. The naga test validates every composed shader and checks that every `.wgsl`
//! file under `plugin/src` is part of one.

pub use crate::shader::{ComposedShader, GeneratedWgsl, ShaderTarget, WgslFile};

/// Camera and light uniforms, and the light iteration helpers.
pub const FRAME: WgslFile = crate::wgsl_file!("render/frame.wgsl");
/// Tangent frames and normal-map decoding.
pub const TANGENT_SPACE: WgslFile = crate::wgsl_file!("render/tangent_space.wgsl");
/// Helpers for generated parameter structs (colours as `array<f32, 4>`).
pub const PARAMS: WgslFile = crate::wgsl_file!("render/params.wgsl");
/// Vertex input/output, the per-draw transforms and the shared vertex stage `vs_main`.
pub const MESH_VERTEX: WgslFile = crate::wgsl_file!("render/mesh_vertex.wgsl");
/// Scene shadows: the shadow maps and `scene_shadow()`, for materials that receive them.
pub const SHADOWS: WgslFile = crate::wgsl_file!("render/shadows.wgsl");
/// The depth prepass's result, bound for materials that test a depth of their own against it.
pub const PREPASS_DEPTH: WgslFile = crate::wgsl_file!("render/prepass_depth.wgsl");
/// The sRGB transfer function both ways (display images hold encoded values).
pub const SRGB: WgslFile = crate::wgsl_file!("render/srgb.wgsl");
/// `fullscreen_vertex`: the vertex stage of full-screen passes.
pub const FULLSCREEN_TRIANGLE: WgslFile = crate::wgsl_file!("render/fullscreen_triangle.wgsl");
/// The visibility pass of the deferred path: `visibility_id()` and the default `fs_visibility`.
pub const VISIBILITY: WgslFile = crate::wgsl_file!("render/visibility/visibility.wgsl");
/// Reading the visibility keys from compute (`visible_id`).
pub const VISIBILITY_READ: WgslFile = crate::wgsl_file!("render/visibility/visibility_read.wgsl");
/// The Sobel compute pass of dynamic height fields.
pub const SOBEL_ENTRY: WgslFile = crate::wgsl_file!("dynamic_height/sobel.wgsl");

/// The first constants of a material's deferred shader ([`crate::Material::deferred_shader`]):
/// the `primitive_index` extension the visibility pass needs, `TILES_PER_ROW` of the resolve's
/// tile lists and `TILE_SIDE` of its tiles. (`SceneOutput`, the scene target as the resolve
/// writes it, is the composer's: [`crate::shader::ShaderTarget`].)
pub fn deferred_header() -> String {
    format!(
        "enable primitive_index;\nconst TILES_PER_ROW: u32 = {}u;\nconst TILE_SIDE: u32 = {}u;\n",
        RESOLVE_TILES_PER_ROW, DEFERRED_TILE_SIDE
    )
}

/// Pixels along each side of the deferred path's tiles and compute workgroups (`TILE_SIDE` in
/// WGSL).
pub(crate) const DEFERRED_TILE_SIDE: u32 = 8;

/// The deferred tiles across and down a target of `size` pixels (edge tiles partly outside).
pub(crate) fn deferred_tiles((width, height): (u32, u32)) -> (u32, u32) {
    (
        width.div_ceil(DEFERRED_TILE_SIDE),
        height.div_ceil(DEFERRED_TILE_SIDE),
    )
}

/// Tiles per row of a resolve batch's indirect dispatch (`TILES_PER_ROW` in WGSL): a dispatch
/// has at most 65535 workgroups a side, a 4K target 129,600 tiles of 8 × 8.
pub(crate) const RESOLVE_TILES_PER_ROW: u32 = 256;

// The renderer's part of composing: the counting twin and the module on a device.
impl ComposedShader {
    /// The source for `target` whose `count_fragment_invocation()` counts into group 0's
    /// [`super::frame_group::FRAGMENT_COUNTER`] (a [`crate::gpu::FragmentInvocationCounter`]).
    pub fn counting_source(&self, target: &ShaderTarget) -> String {
        self.source_for(&ShaderTarget {
            fragment_counter: Some(super::frame_group::FRAGMENT_COUNTER),
            ..*target
        })
    }

    /// Compiles the shader on `device` for its default scene format, labelled with its name.
    pub fn create_module(&self, device: &wgpu::Device) -> wgpu::ShaderModule {
        let target = ShaderTarget::of_device(device, wgpu::TextureFormat::Rgba16Float);
        create_module(device, self.name, self.source_for(&target))
    }
}

/// Compiles `source` (already composed for `device`'s [`ShaderTarget`]) on `device`, labelled
/// `name`.
pub(crate) fn create_module(
    device: &wgpu::Device,
    name: &str,
    source: String,
) -> wgpu::ShaderModule {
    device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some(name),
        source: wgpu::ShaderSource::Wgsl(source.into()),
    })
}

/// Normals of dynamic height fields, derived on the GPU.
pub const SOBEL: ComposedShader = ComposedShader {
    name: "sobel.wgsl",
    constants: &[],
    files: &[SOBEL_ENTRY],
};
