use pom::material::{FragmentVariant, MAX_MATERIAL_TEXTURES, MaterialTextures, TextureFacts};
use pom::render::shaders::{ComposedShader, FRAME, MESH_VERTEX, WgslFile};
use pom::{Color, Material, render::DefaultTexture};

/// An unlit surface of one colour.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Tinted {
    pub color: Color,
}
/// `Tinted` as the shader reads it; `wgsl_layout!` lets a test check it against the WGSL.
#[repr(C)]
#[derive(Clone, Copy, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct TintedUniform {
    color: [f32; 4],
}
pom::wgsl_layout!(TintedUniform { color });
const TINTED_WGSL: WgslFile = WgslFile {
    path: "tinted.wgsl",
    source: "struct TintedUniform { color: vec4<f32> }
@group(0) @binding(2) var<storage, read> materials: array<TintedUniform>;
@fragment
fn fs_main(in: VertexOut) -> @location(0) vec4<f32> { return materials[in.object_index].color; }",
};

impl Material for Tinted {
    type Uniform = TintedUniform;
    type Key = ();
    const NAME: &'static str = "tinted";
    const UNIFORM_WGSL_NAME: &'static str = "TintedUniform";
    const TEXTURE_SLOTS: &'static [DefaultTexture] = &[];
    fn shader() -> ComposedShader {
        ComposedShader { name: "tinted", constants: &[], files: &[FRAME, MESH_VERTEX, TINTED_WGSL] }
    }
    fn textures(&self) -> MaterialTextures { [None; MAX_MATERIAL_TEXTURES] }
    fn key(&self) {}
    fn fragment(_: ()) -> FragmentVariant { FragmentVariant::entry("fs_main") }
    fn uniform(&self, _: &[Option<TextureFacts>; MAX_MATERIAL_TEXTURES]) -> TintedUniform {
        TintedUniform { color: self.color.to_array() }
    }
}
