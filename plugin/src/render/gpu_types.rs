//! Plain-old-data structs laid out exactly as `frame.wgsl` and `mesh_vertex.wgsl` declare them
//! (checked by the layout tests).

use bytemuck::{Pod, Zeroable};

/// Most directional lights one frame shades with (`MAX_DIRECTIONAL_LIGHTS` in WGSL).
pub const MAX_DIRECTIONAL_LIGHTS: usize = 4;

/// One directional light as the shader reads it.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct DirectionalLightGpu {
    /// xyz: unit vector from the surface towards the light.
    pub direction_to_light: [f32; 4],
    /// rgb: colour × intensity.
    pub radiance: [f32; 4],
    /// The light's shadow maps: the first of its [`ShadowViewGpu`]s (its cascades).
    pub first_shadow_view: u32,
    /// How many shadow views it has (0: it casts no scene shadow).
    pub shadow_view_count: u32,
    /// Keeps the size a multiple of 16 bytes, as WGSL lays the struct out.
    pub _padding: [u32; 2],
}

crate::wgsl_layout!(DirectionalLightGpu {
    direction_to_light,
    radiance,
    first_shadow_view,
    shadow_view_count,
    _padding
});

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
    /// The light's shadow maps: the first of its [`ShadowViewGpu`]s (a spot's one, a point
    /// light's six cube faces in the order +X, −X, +Y, −Y, +Z, −Z).
    pub first_shadow_view: u32,
    /// How many shadow views it has (0: it casts no scene shadow).
    pub shadow_view_count: u32,
    /// Keeps the size a multiple of 16 bytes, as WGSL lays the struct out.
    pub _padding: [u32; 2],
}

crate::wgsl_layout!(PointLightGpu {
    position_range,
    radiance,
    spot_direction,
    spot_cone,
    first_shadow_view,
    shadow_view_count,
    _padding
});

/// One shadow map as the receiving shaders read it (`ShadowView` in shadows.wgsl): a cascade of
/// a directional light, a spot light's map or one cube face of a point light.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct ShadowViewGpu {
    /// World to the light's clip space.
    pub view_projection: [[f32; 4]; 4],
    /// The part of its layer the map covers along each side (a smaller map uses a corner).
    pub uv_scale: f32,
    /// Cascades: the distance along the camera's view up to which this cascade covers.
    pub far_view_depth: f32,
    /// World size of one texel: across the whole map for an orthographic view, at one unit
    /// from the light for a perspective one.
    pub texel_world_size: f32,
    /// 1 for a perspective view (spot, cube face): texels grow with the distance.
    pub perspective: u32,
    /// Filter radius in texels.
    pub softness: f32,
    /// The array layer holding the map.
    pub layer: u32,
    /// Keeps the size a multiple of 16 bytes, as WGSL lays the struct out.
    pub _padding: [u32; 2],
}

crate::wgsl_layout!(ShadowViewGpu {
    view_projection,
    uv_scale,
    far_view_depth,
    texel_world_size,
    perspective,
    softness,
    layer,
    _padding
});

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
    /// x: directional light count, y: point and spot light count (the lights' storage
    /// buffer, `point_lights` in frame.wgsl).
    pub light_counts: [u32; 4],
    /// xy: the target's width and height in pixels (the visibility buffer's rows); z: the seed
    /// of per-frame noise (counts TAA frames; 0 without TAA); w: 1 under TAA, whose history
    /// averages per-frame noise away.
    pub target_size: [u32; 4],
    /// x: the scale of every texture read's gradients, 2 to the mip bias of TAA or the post filter
    /// (1 without anti-aliasing); yzw: 0.
    pub texture_lod: [f32; 4],
    /// x: what the environment's values are multiplied with (its intensity × the exposure), y:
    /// the radiance cube's mips (0: no environment, the ambient term lights instead; the last
    /// is roughness 1), zw: cosine and sine of its rotation about +Y.
    pub environment: [f32; 4],
    /// x: 1 where the environment's specular gets back the energy a single scattering loses
    /// on rough surfaces (multiple-scattering compensation), else 0.
    pub environment_options: [f32; 4],
    /// The directional lights; only the first `light_counts.x` are used.
    pub directional_lights: [DirectionalLightGpu; MAX_DIRECTIONAL_LIGHTS],
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
    /// 1 where scene shadows fall on the object, 0 for a [`crate::NotShadowReceiver`].
    pub receives_shadows: u32,
    /// On the deferred path, the visibility id of the object's first triangle (its triangle
    /// `t` shows as this + `t`; 0 marks no draw); 0 on the forward path.
    pub first_visibility_id: u32,
    /// Under TAA, the number of its motion since the last frame (`ObjectMotion`s, counted
    /// from 1); 0 for a draw that did not move.
    pub motion: u32,
}

crate::wgsl_layout!(MeshTransform {
    model,
    normal_matrix,
    determinant_sign,
    receives_shadows,
    first_visibility_id,
    motion
});

impl MeshTransform {
    /// The transform of an object placed by `model`, receiving scene shadows or not.
    pub fn new(model: glam::Mat4, receives_shadows: bool) -> Self {
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
            receives_shadows: u32::from(receives_shadows),
            first_visibility_id: 0,
            motion: 0,
        }
    }

    /// Whether this is the transform of an object placed by `model`, receiving scene shadows
    /// or not (what [`MeshTransform::new`] would make of them, but for the id and motion).
    pub(crate) fn places(&self, model: glam::Mat4, receives_shadows: bool) -> bool {
        self.model == model.to_cols_array_2d()
            && self.receives_shadows == u32::from(receives_shadows)
    }
}

crate::wgsl_layout!(FrameUniform {
    view_projection,
    camera_position,
    view_direction,
    ambient,
    light_counts,
    target_size,
    texture_lod,
    environment,
    environment_options,
    directional_lights
});
