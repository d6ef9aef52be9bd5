//! The Extract stage: copy what the renderer needs out of the world, once per frame.

use glam::{Mat4, Vec3};
use hecs::World;

use super::ShadowViewPlan;
use super::gpu_types::{DirectionalLightGpu, FrameUniform, MAX_DIRECTIONAL_LIGHTS, PointLightGpu};
use super::target::RenderTarget;
use crate::{
    AmbientLight, AppError, Camera, Color, Exposure, GlobalTransform, Projection, Resources,
};

/// Everything the Prepare and Render stages read about the current frame.
#[derive(Clone, Debug, PartialEq)]
pub struct ExtractedFrame {
    /// Camera and lights in GPU layout.
    pub frame: FrameUniform,
    /// The colour the target is cleared to.
    pub clear_color: Color,
    /// Whether an active camera was found (without one, the frame is only cleared).
    pub has_camera: bool,
    /// The active camera's exposure (the default without a camera or component), already
    /// applied to the lights.
    pub exposure: Exposure,
    /// The active camera and where it is (`None` without one).
    pub camera: Option<(Camera, GlobalTransform)>,
    /// The entity of each light in the frame uniform, in its order.
    pub lights: LightEntities,
    /// The point and spot lights (`point_lights` in frame.wgsl): the point lights, then the
    /// spot lights, as `lights.point` lists their entities.
    pub point_lights: Vec<PointLightGpu>,
    /// Each light cluster's first entry and count, then their lists (`light_clusters` in
    /// frame.wgsl; see [`crate::render::lights`]).
    pub light_clusters: Vec<u32>,
    /// The shadow maps to render this frame, in the order the lights reference them: empty
    /// unless a feature plans them (the shadows plugin does, after this extract).
    pub shadow_views: Vec<ShadowViewPlan>,
}

/// Words of the light clusters' header: the grid, the depth slicing and the camera they were
/// culled for (lights.wgsl's `light_cluster` reads them; clusters.rs writes them).
pub const LIGHT_CLUSTER_HEADER: usize = 32;

/// The clusters of a frame without point lights: one cluster, whose list is empty (and the
/// header's count of list entries 0).
pub const NO_LIGHT_CLUSTERS: [u32; LIGHT_CLUSTER_HEADER + 2] = {
    let mut words = [0; LIGHT_CLUSTER_HEADER + 2];
    (words[0], words[1], words[2]) = (1, 1, 1);
    words[LIGHT_CLUSTER_HEADER] = LIGHT_CLUSTER_HEADER as u32 + 2;
    words
};

/// The entity of each light the frame uniform holds, slot by slot.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct LightEntities {
    /// `directional_lights[i]`'s entity.
    pub directional: Vec<hecs::Entity>,
    /// `point_lights[i]`'s entity: the point lights, then the spot lights.
    pub point: Vec<hecs::Entity>,
}

/// What the active camera's entity says of its image: its exposure (the default where it has
/// none).
#[derive(Default)]
struct CameraDisplay {
    camera: Option<(Camera, GlobalTransform)>,
    exposure: Exposure,
}

/// The active camera (as [`crate::active_camera`] finds it) with its entity's display
/// components (their defaults where it has none), in one query.
fn active_camera_and_display(world: &World) -> CameraDisplay {
    world
        .query::<(&Camera, &GlobalTransform, Option<&Exposure>)>()
        .iter()
        .find(|(camera, ..)| camera.active)
        .map_or_else(Default::default, |(camera, transform, exposure)| {
            CameraDisplay {
                camera: Some((*camera, *transform)),
                exposure: exposure.copied().unwrap_or_default(),
            }
        })
}

fn columns(matrix: Mat4) -> [[f32; 4]; 4] {
    matrix.to_cols_array_2d()
}

/// The Extract stage's system: reads the camera and the ambient light into [`ExtractedFrame`]
/// (the lights feature adds the lights; each material's plugin extracts its own draws).
pub fn extract_frame(world: &mut World, resources: &mut Resources) -> Result<(), AppError> {
    let target = resources.require::<RenderTarget>()?;
    let (aspect, target_size) = (target.aspect(), target.size());
    let ambient = resources.get::<AmbientLight>().copied().unwrap_or_default();
    let display = active_camera_and_display(world);
    let exposure = display.exposure;
    let camera = display.camera;
    let view = CameraView::of(camera.as_ref(), aspect);
    // Lux and candela to what the shaders multiply with the albedo: a Lambertian surface of
    // albedo ρ lit with illuminance E sends radiance ρ·E/π towards the eye (Lagarde & de
    // Rousiers §4.1), times the camera's exposure: the scene target holds pre-exposed values
    // (Frostbite's pre-exposure), because daylight radiance (≈ 30,000 cd/m²) would overflow
    // its 16-bit floats, and unlit and emissive colours then show as authored at any exposure.
    let light_scale = std::f32::consts::FRAC_1_PI * exposure.multiplier();
    let ambient_radiance = radiance(ambient.color, ambient.intensity, light_scale);
    let frame = FrameUniform {
        view_projection: columns(view.view_projection),
        camera_position: view.position.extend(1.0).into(),
        view_direction: view.direction.into(),
        ambient: [
            ambient_radiance[0],
            ambient_radiance[1],
            ambient_radiance[2],
            0.0,
        ],
        light_counts: [0; 4],
        // z: the seed of per-frame noise, w: whether it moves from frame to frame, and the
        // texture footprints' scale: still without anti-aliasing, which sets them.
        target_size: [target_size.0, target_size.1, 0, 0],
        texture_lod: [1.0, 0.0, 0.0, 0.0],
        // No environment unless its feature sets one, after this extract.
        environment: [0.0, 0.0, 1.0, 0.0],
        environment_options: [0.0; 4],
        // The lights are the lights feature's (render/lights/), extracted after this.
        directional_lights: [DirectionalLightGpu::default(); MAX_DIRECTIONAL_LIGHTS],
    };
    // The last frame's lists, emptied, keep their memory for this frame's: a thousand lights'
    // clusters would otherwise take a fresh allocation (and its pages) every frame.
    let (mut lights, mut point_lights, mut light_clusters, mut shadow_views) = resources
        .remove::<ExtractedFrame>()
        .map(|last| {
            (
                last.lights,
                last.point_lights,
                last.light_clusters,
                last.shadow_views,
            )
        })
        .unwrap_or_default();
    lights.directional.clear();
    lights.point.clear();
    point_lights.clear();
    light_clusters.clear();
    light_clusters.extend_from_slice(&NO_LIGHT_CLUSTERS);
    shadow_views.clear();
    resources.insert(ExtractedFrame {
        frame,
        clear_color: view.clear_color,
        exposure,
        camera,
        lights,
        point_lights,
        light_clusters,
        shadow_views,
        has_camera: camera.is_some(),
    });
    Ok(())
}

/// The active camera as the frame uniform and the clear see it (a still default without one).
struct CameraView {
    view_projection: Mat4,
    position: Vec3,
    /// Where it looks, and 1 in `w` for an orthographic projection.
    direction: glam::Vec4,
    clear_color: Color,
}

impl CameraView {
    fn of(camera: Option<&(Camera, GlobalTransform)>, aspect: f32) -> Self {
        match camera {
            Some((camera, transform)) => {
                let view = transform.to_mat4().inverse();
                let orthographic = matches!(camera.projection, Projection::Orthographic { .. });
                Self {
                    view_projection: camera.projection.matrix(aspect) * view,
                    position: transform.translation(),
                    direction: transform
                        .forward()
                        .extend(if orthographic { 1.0 } else { 0.0 }),
                    clear_color: camera.clear_color,
                }
            }
            None => Self {
                view_projection: Mat4::IDENTITY,
                position: Vec3::ZERO,
                direction: Vec3::NEG_Z.extend(0.0),
                clear_color: Color::BLACK,
            },
        }
    }
}

/// What the shaders multiply with the albedo for a light of `color` and `intensity` (lux or
/// candela; not finite or negative: none), pre-exposed by `light_scale`.
pub(crate) fn radiance(color: Color, intensity: f32, light_scale: f32) -> [f32; 4] {
    let intensity = if intensity.is_finite() {
        intensity.max(0.0) * light_scale
    } else {
        0.0
    };
    [
        color.r * intensity,
        color.g * intensity,
        color.b * intensity,
        0.0,
    ]
}
