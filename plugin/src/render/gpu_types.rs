//! Plain-old-data structs laid out exactly as `frame.wgsl` and `mesh_vertex.wgsl` declare them
//! (checked by the layout tests).

use bytemuck::{Pod, Zeroable};

/// Most directional lights one frame shades with (`MAX_DIRECTIONAL_LIGHTS` in WGSL).
pub const MAX_DIRECTIONAL_LIGHTS: usize = 4;
/// Most point and spot lights one frame shades with (`MAX_POINT_LIGHTS` in WGSL).
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

/// One point or spot light as the shader reads it.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct PointLightGpu {
    /// xyz: position, w: range.
    pub position_range: [f32; 4],
    /// rgb: colour × intensity.
    pub radiance: [f32; 4],
    /// xyz: the direction a spot shines; w unused.
    pub spot_direction: [f32; 4],
    /// x: angle scale, y: angle offset of the spot's cone (glTF's formula; 0 and 1 for a
    /// point light, which shines everywhere).
    pub spot_cone: [f32; 4],
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
    /// x: directional light count, y: point and spot light count.
    pub light_counts: [u32; 4],
    /// The directional lights; only the first `light_counts.x` are used.
    pub directional_lights: [DirectionalLightGpu; MAX_DIRECTIONAL_LIGHTS],
    /// The point and spot lights; only the first `light_counts.y` are used.
    pub point_lights: [PointLightGpu; MAX_POINT_LIGHTS],
}

/// Per-draw transform, shared by every material (`MeshTransform` in `mesh_vertex.wgsl`).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct MeshTransform {
    /// Object to world.
    pub model: [[f32; 4]; 4],
    /// Inverse transpose of `model`, for normals (identity when `model` has no inverse).
    pub normal_matrix: [[f32; 4]; 4],
    /// Sign of det(model): mirroring flips the bitangent.
    pub determinant_sign: f32,
    /// Keeps the size a multiple of 16 bytes, as WGSL lays the struct out.
    pub _padding: [f32; 3],
}

crate::wgsl_layout!(MeshTransform {
    model,
    normal_matrix,
    determinant_sign,
    _padding
});

impl MeshTransform {
    /// The transform of an object placed by `model`.
    pub fn new(model: glam::Mat4) -> Self {
        let determinant = model.determinant();
        // A zero scale has no inverse; such an object has no area, so any normal will do.
        // A huge but finite scale can overflow the inverse: any normal will do there too.
        let normal_matrix = Some(model.inverse().transpose())
            .filter(|inverse| determinant.abs() > f32::MIN_POSITIVE && inverse.is_finite())
            .unwrap_or(glam::Mat4::IDENTITY);
        Self {
            model: model.to_cols_array_2d(),
            normal_matrix: normal_matrix.to_cols_array_2d(),
            determinant_sign: if determinant < 0.0 { -1.0 } else { 1.0 },
            _padding: [0.0; 3],
        }
    }
}

crate::wgsl_layout!(FrameUniform {
    view_projection,
    camera_position,
    view_direction,
    ambient,
    light_counts,
    directional_lights,
    point_lights
});

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
