//! The vertex of every mesh on the GPU, laid out as `mesh_vertex.wgsl` and the deferred
//! resolve declare it (checked by the layout tests).

use bytemuck::{Pod, Zeroable};

/// One vertex of the interleaved vertex buffer.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct Vertex {
    /// Object-space position.
    pub position: [f32; 3],
    /// Object-space normal.
    pub normal: [f32; 3],
    /// Texture coordinate.
    pub uv: [f32; 2],
    /// Tangent with bitangent sign.
    pub tangent: [f32; 4],
    /// Linear RGBA vertex colour (white without one).
    pub color: [f32; 4],
}

// The deferred resolve reads vertex buffers as `array<StoredVertex>` (deferred_resolve.wgsl).
crate::wgsl_layout!(Vertex {
    position,
    normal,
    uv,
    tangent,
    color
});

impl Vertex {
    /// The vertex buffer layout matching `VertexIn` in WGSL.
    pub const LAYOUT: wgpu::VertexBufferLayout<'static> = wgpu::VertexBufferLayout {
        array_stride: std::mem::size_of::<Vertex>() as wgpu::BufferAddress,
        step_mode: wgpu::VertexStepMode::Vertex,
        attributes: &wgpu::vertex_attr_array![
            0 => Float32x3, 1 => Float32x3, 2 => Float32x2, 3 => Float32x4, 4 => Float32x4
        ],
    };
}
