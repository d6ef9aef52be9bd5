//! Plain-old-data structs laid out exactly as `forward.wgsl` declares them.

use bytemuck::{Pod, Zeroable};

/// Most directional lights one frame shades with (`MAX_DIRECTIONAL_LIGHTS` in WGSL).
pub const MAX_DIRECTIONAL_LIGHTS: usize = 4;
/// Most point lights one frame shades with (`MAX_POINT_LIGHTS` in WGSL).
pub const MAX_POINT_LIGHTS: usize = 16;

/// One directional light as the shader reads it.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct DirectionalLightGpu {
    /// xyz: unit vector from the surface towards the light.
    pub direction_to_light: [f32; 4],
    /// rgb: colour × intensity.
    pub radiance: [f32; 4],
}

/// One point light as the shader reads it.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct PointLightGpu {
    /// xyz: position, w: range.
    pub position_range: [f32; 4],
    /// rgb: colour × intensity.
    pub radiance: [f32; 4],
}

/// Per-frame values: camera and lights.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct FrameUniform {
    /// Projection × view.
    pub view_projection: [[f32; 4]; 4],
    /// xyz: camera position in the world.
    pub camera_position: [f32; 4],
    /// xyz: the direction the camera looks; w: 1 for an orthographic camera, whose view rays
    /// are all parallel to it.
    pub view_direction: [f32; 4],
    /// rgb: ambient colour × intensity.
    pub ambient: [f32; 4],
    /// x: directional light count, y: point light count.
    pub light_counts: [u32; 4],
    /// The directional lights; only the first `light_counts.x` are used.
    pub directional_lights: [DirectionalLightGpu; MAX_DIRECTIONAL_LIGHTS],
    /// The point lights; only the first `light_counts.y` are used.
    pub point_lights: [PointLightGpu; MAX_POINT_LIGHTS],
}

/// Per-object values: transform and material parameters.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct ObjectUniform {
    /// Object to world.
    pub model: [[f32; 4]; 4],
    /// Inverse transpose of `model`, for normals.
    pub normal_matrix: [[f32; 4]; 4],
    /// Linear base colour.
    pub base_color: [f32; 4],
    /// x: normal strength, y: specular strength, z: shininess, w: sign of det(model).
    pub params: [f32; 4],
}

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
}

impl Vertex {
    /// The vertex buffer layout matching `VertexIn` in WGSL.
    pub const LAYOUT: wgpu::VertexBufferLayout<'static> = wgpu::VertexBufferLayout {
        array_stride: std::mem::size_of::<Vertex>() as wgpu::BufferAddress,
        step_mode: wgpu::VertexStepMode::Vertex,
        attributes: &wgpu::vertex_attr_array![
            0 => Float32x3, 1 => Float32x3, 2 => Float32x2, 3 => Float32x4
        ],
    };
}
