//! The plugin's WGSL, embedded at build time and composed from shared library files.
//!
//! WGSL has no `#include`: each entry shader is the concatenation of the library files it needs
//! and its own file. The naga test validates every composed shader and checks that every `.wgsl`
//! file under `plugin/src` is part of one.

/// One WGSL file, by its path under `plugin/src`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct WgslFile {
    /// Path relative to `plugin/src`, for error messages and hot reload.
    pub path: &'static str,
    /// The file's text as it was at build time.
    pub source: &'static str,
}

macro_rules! wgsl_file {
    ($path:literal) => {
        WgslFile {
            path: $path,
            source: include_str!(concat!("../", $path)),
        }
    };
}

/// Camera and light uniforms, and the light iteration helpers.
pub const FRAME: WgslFile = wgsl_file!("render/frame.wgsl");
/// Tangent frames and normal-map decoding.
pub const TANGENT_SPACE: WgslFile = wgsl_file!("render/tangent_space.wgsl");
/// Phong, Blinn-Phong and Cook-Torrance + Oren-Nayar.
pub const LIGHTING: WgslFile = wgsl_file!("render/lighting.wgsl");
/// Vertex input/output and the world transform.
pub const MESH_VERTEX: WgslFile = wgsl_file!("render/mesh_vertex.wgsl");
/// The lit material's entry points.
pub const FORWARD_ENTRY: WgslFile = wgsl_file!("render/forward.wgsl");

/// The ray march, LOD and self-shadow functions of the parallax material.
pub const PARALLAX_MARCH: WgslFile = wgsl_file!("parallax/march.wgsl");
/// The parallax material's entry points.
pub const PARALLAX_ENTRY: WgslFile = wgsl_file!("parallax/pom.wgsl");

/// The Sobel compute pass of dynamic height fields.
pub const SOBEL_ENTRY: WgslFile = wgsl_file!("dynamic_height/sobel.wgsl");

/// The texel-rate probe's full-screen pass.
pub const TEXEL_RATE_PROBE_ENTRY: WgslFile = wgsl_file!("render/texel_rate_probe.wgsl");

/// An entry shader: the files it is made of, in order.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ComposedShader {
    /// A name for labels and messages.
    pub name: &'static str,
    /// Library files first, the entry file last.
    pub files: &'static [WgslFile],
}

impl ComposedShader {
    /// The concatenated source, each file introduced by a comment naming it.
    pub fn source(&self) -> String {
        let mut source = String::new();
        for file in self.files {
            source.push_str("// ---- ");
            source.push_str(file.path);
            source.push_str(" ----\n");
            source.push_str(file.source);
            source.push('\n');
        }
        source
    }

    /// Compiles the composed source on `device`, labelled with the shader's name.
    pub fn create_module(&self, device: &wgpu::Device) -> wgpu::ShaderModule {
        device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some(self.name),
            source: wgpu::ShaderSource::Wgsl(self.source().into()),
        })
    }
}

/// The forward pass for [`crate::LitMaterial`].
pub const FORWARD: ComposedShader = ComposedShader {
    name: "forward.wgsl",
    files: &[FRAME, TANGENT_SPACE, LIGHTING, MESH_VERTEX, FORWARD_ENTRY],
};

/// The pass for [`crate::ParallaxOcclusionMaterial`].
pub const PARALLAX: ComposedShader = ComposedShader {
    name: "pom.wgsl",
    files: &[
        FRAME,
        TANGENT_SPACE,
        LIGHTING,
        MESH_VERTEX,
        PARALLAX_MARCH,
        PARALLAX_ENTRY,
    ],
};

/// Normals of dynamic height fields, derived on the GPU.
pub const SOBEL: ComposedShader = ComposedShader {
    name: "sobel.wgsl",
    files: &[SOBEL_ENTRY],
};

/// The bench's fragment-stage texel-rate probe (`super::TexelRateProbe`).
pub const TEXEL_RATE_PROBE: ComposedShader = ComposedShader {
    name: "texel_rate_probe.wgsl",
    files: &[TEXEL_RATE_PROBE_ENTRY],
};

/// Every entry shader of the plugin.
pub const ALL: &[ComposedShader] = &[FORWARD, PARALLAX, SOBEL, TEXEL_RATE_PROBE];
