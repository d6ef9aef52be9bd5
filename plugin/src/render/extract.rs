//! The Extract stage: copy what the renderer needs out of the world, once per frame.

use glam::{Mat4, Vec3};
use hecs::World;

use super::gpu_types::{
    DirectionalLightGpu, FrameUniform, MAX_DIRECTIONAL_LIGHTS, MAX_POINT_LIGHTS, PointLightGpu,
};
use super::lowest_mip::PixelFootprint;
use super::shadow_views::{
    CascadeCamera, MAX_SHADOW_VIEWS, ShadowViewPlan, directional_views, point_views, spot_view,
};
use super::target::RenderTarget;
use crate::{
    AmbientLight, AppError, Camera, Color, DirectionalLight, Exposure, GlobalTransform,
    LightShadows, PointLight, Projection, Resources, SpotLight,
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
    /// How large the active camera's pixels are in the world (for per-object LOD).
    pub footprint: Option<PixelFootprint>,
    /// The active camera's exposure (the default without a camera or component), already
    /// applied to the lights.
    pub exposure: Exposure,
    /// The shadow maps to render this frame, in the order the lights reference them.
    pub shadow_views: Vec<ShadowViewPlan>,
    /// Whether the lights asked for more than [`MAX_SHADOW_VIEWS`] maps.
    pub shadow_maps_overflowed: bool,
}

/// The shadow maps of a frame as its lights claim them, up to [`MAX_SHADOW_VIEWS`].
struct ShadowViewList {
    views: Vec<ShadowViewPlan>,
    overflowed: bool,
    /// Whether a feature draws the maps the frame plans ([`super::ShadowMapsDrawn`]; without
    /// one no light has maps).
    drawn: bool,
}

impl ShadowViewList {
    /// Adds a light's maps; returns (first view, count) for its GPU record, (0, 0) when it
    /// casts none or they do not fit.
    fn claim(&mut self, views: &[ShadowViewPlan]) -> (u32, u32) {
        // A light whose transform has no direction (a zero scale) or no finite place has no
        // map: NaN matrices would reach every receiver.
        let finite = |view: &ShadowViewPlan| {
            view.gpu
                .view_projection
                .iter()
                .flatten()
                .all(|value| value.is_finite())
                && view.gpu.texel_world_size.is_finite()
        };
        if !self.drawn || views.is_empty() || !views.iter().all(finite) {
            return (0, 0);
        }
        if self.views.len() + views.len() > MAX_SHADOW_VIEWS {
            self.overflowed = true;
            return (0, 0);
        }
        let first = self.views.len();
        self.views.extend(views.iter().enumerate().map(|(i, view)| {
            let mut view = *view;
            view.gpu.layer = (first + i) as u32;
            view
        }));
        (first as u32, views.len() as u32)
    }
}

/// What the shadow maps of one frame may take of the GPU's memory: the array holds every map at
/// the largest size asked for.
const SHADOW_MAP_BUDGET_BYTES: u64 = 512 << 20;

/// The largest map side this frame's shadow maps may have: the device's texture limit, and a
/// power of two small enough for every map the lights ask for to fit the budget.
fn shadow_map_cap(world: &World, device_limit: u32) -> u32 {
    let enabled = |shadows: Option<&LightShadows>| shadows.is_some_and(|shadows| shadows.enabled);
    let mut views = 0;
    for (_, shadows) in world
        .query::<(&DirectionalLight, Option<&LightShadows>)>()
        .iter()
    {
        views += 3 * usize::from(enabled(shadows));
    }
    for (_, shadows) in world.query::<(&SpotLight, Option<&LightShadows>)>().iter() {
        views += usize::from(enabled(shadows));
    }
    for (_, shadows) in world.query::<(&PointLight, Option<&LightShadows>)>().iter() {
        views += 6 * usize::from(enabled(shadows));
    }
    let views = views.clamp(1, MAX_SHADOW_VIEWS) as u64;
    let mut cap = LightShadows::MAX_MAP_SIZE.min(device_limit.max(LightShadows::MIN_MAP_SIZE));
    while cap > LightShadows::MIN_MAP_SIZE
        && u64::from(cap).pow(2) * 4 * views > SHADOW_MAP_BUDGET_BYTES
    {
        cap /= 2;
    }
    cap
}

/// A light's shadow settings as the renderer uses them, its map no larger than `cap`; `None`
/// when it casts no shadow (no [`LightShadows`], or one switched off).
fn enabled_shadows(shadows: Option<&LightShadows>, cap: u32) -> Option<LightShadows> {
    shadows
        .map(LightShadows::sanitized)
        .filter(|shadows| shadows.enabled)
        .map(|shadows| LightShadows {
            map_size: shadows.map_size.min(cap),
            ..shadows
        })
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

/// The Extract stage's system: reads the camera and the lights into [`ExtractedFrame`] (each
/// material's plugin extracts its own draws).
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
    let mut lights = LightExtraction {
        frame: FrameUniform {
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
            directional_lights: [DirectionalLightGpu::default(); MAX_DIRECTIONAL_LIGHTS],
            point_lights: [PointLightGpu::default(); MAX_POINT_LIGHTS],
        },
        shadow_views: ShadowViewList {
            views: Vec::new(),
            overflowed: false,
            drawn: resources.contains::<super::ShadowMapsDrawn>(),
        },
        map_cap: shadow_map_cap(world, device_texture_limit(resources)),
        light_scale,
        cascade_camera: camera
            .map(|(camera, transform)| cascade_camera(&camera, &transform, aspect)),
    };
    let directional_count = lights.directional_lights(world);
    let point_count = lights.point_and_spot_lights(world);
    lights.frame.light_counts = [directional_count as u32, point_count as u32, 0, 0];
    let overflowed = lights.shadow_views.overflowed;
    warn_of_shadow_overflow(resources, overflowed);
    resources.insert(ExtractedFrame {
        frame: lights.frame,
        clear_color: view.clear_color,
        exposure,
        shadow_maps_overflowed: overflowed,
        shadow_views: if camera.is_some() {
            lights.shadow_views.views
        } else {
            Vec::new()
        },
        has_camera: camera.is_some(),
        footprint: camera
            .map(|(camera, transform)| PixelFootprint::new(&camera, &transform, target_size)),
    });
    Ok(())
}

/// Warns when the lights ask for more shadow maps than there are, once per episode (the last
/// frame's [`ExtractedFrame`] says whether it had already).
fn warn_of_shadow_overflow(resources: &Resources, overflowed: bool) {
    let warned = resources
        .get::<ExtractedFrame>()
        .is_some_and(|last| last.shadow_maps_overflowed);
    if overflowed && !warned {
        log::warn!(
            "the lights ask for more than {MAX_SHADOW_VIEWS} shadow maps: the rest cast no scene shadow"
        );
    }
}

/// The largest texture side the device allows (the shadow maps' cap), or the maps' own cap
/// before there is a device.
fn device_texture_limit(resources: &Resources) -> u32 {
    resources
        .get::<crate::GpuContext>()
        .map_or(LightShadows::MAX_MAP_SIZE, |gpu| {
            gpu.device.limits().max_texture_dimension_2d
        })
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

/// The camera the directional lights fit their cascades to.
fn cascade_camera(camera: &Camera, transform: &GlobalTransform, aspect: f32) -> CascadeCamera {
    let matrix = transform.to_mat4();
    CascadeCamera {
        position: transform.translation(),
        forward: transform.forward(),
        right: matrix.x_axis.truncate().normalize_or_zero(),
        up: matrix.y_axis.truncate().normalize_or_zero(),
        projection: camera.projection,
        aspect,
    }
}

/// What the shaders multiply with the albedo for a light of `color` and `intensity` (lux or
/// candela; not finite or negative: none), pre-exposed by `light_scale`.
fn radiance(color: Color, intensity: f32, light_scale: f32) -> [f32; 4] {
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

/// The frame's lights being filled in, with the shadow maps they claim.
struct LightExtraction {
    frame: FrameUniform,
    shadow_views: ShadowViewList,
    /// The largest shadow map any light gets this frame.
    map_cap: u32,
    light_scale: f32,
    cascade_camera: Option<CascadeCamera>,
}

impl LightExtraction {
    /// Fills in the directional lights (with their cascades); returns how many.
    fn directional_lights(&mut self, world: &World) -> usize {
        let mut count = 0;
        for (light, transform, shadows) in world
            .query::<(&DirectionalLight, &GlobalTransform, Option<&LightShadows>)>()
            .iter()
        {
            if count == MAX_DIRECTIONAL_LIGHTS {
                log::warn!(
                    "more than {MAX_DIRECTIONAL_LIGHTS} directional lights: the rest are ignored"
                );
                break;
            }
            let (first_shadow_view, shadow_view_count) =
                match (enabled_shadows(shadows, self.map_cap), &self.cascade_camera) {
                    (Some(shadows), Some(camera)) => self.shadow_views.claim(&directional_views(
                        camera,
                        transform.forward(),
                        &shadows,
                    )),
                    _ => (0, 0),
                };
            self.frame.directional_lights[count] = DirectionalLightGpu {
                direction_to_light: (-transform.forward()).extend(0.0).into(),
                radiance: radiance(light.color, light.intensity, self.light_scale),
                first_shadow_view,
                shadow_view_count,
                _padding: [0; 2],
            };
            count += 1;
        }
        count
    }

    /// Fills in the point lights, then the spot lights, which share their array; returns how
    /// many.
    fn point_and_spot_lights(&mut self, world: &World) -> usize {
        let mut count = 0;
        for (light, transform, shadows) in world
            .query::<(&PointLight, &GlobalTransform, Option<&LightShadows>)>()
            .iter()
        {
            if count == MAX_POINT_LIGHTS {
                log::warn!("more than {MAX_POINT_LIGHTS} point lights: the rest are ignored");
                break;
            }
            let (first_shadow_view, shadow_view_count) =
                match enabled_shadows(shadows, self.map_cap) {
                    Some(shadows) => self.shadow_views.claim(&point_views(
                        transform.translation(),
                        light.range,
                        &shadows,
                    )),
                    None => (0, 0),
                };
            self.frame.point_lights[count] = PointLightGpu {
                position_range: transform.translation().extend(light.range.max(0.0)).into(),
                radiance: radiance(light.color, light.intensity, self.light_scale),
                spot_direction: [0.0, 0.0, -1.0, 0.0],
                // Scale 0, offset 1: full strength in every direction.
                spot_cone: [0.0, 1.0, 0.0, 0.0],
                first_shadow_view,
                shadow_view_count,
                _padding: [0; 2],
            };
            count += 1;
        }
        for (light, transform, shadows) in world
            .query::<(&SpotLight, &GlobalTransform, Option<&LightShadows>)>()
            .iter()
        {
            if count == MAX_POINT_LIGHTS {
                log::warn!(
                    "more than {MAX_POINT_LIGHTS} point and spot lights: the rest are ignored"
                );
                break;
            }
            self.frame.point_lights[count] = self.spot_light(light, transform, shadows);
            count += 1;
        }
        count
    }

    /// A spot light as the shaders read it, claiming its shadow map.
    fn spot_light(
        &mut self,
        light: &SpotLight,
        transform: &GlobalTransform,
        shadows: Option<&LightShadows>,
    ) -> PointLightGpu {
        // glTF's cone: t = cos(angle to the axis) × scale + offset, clamped, squared.
        let (inner, outer) = light.sanitized_cone();
        let scale = 1.0 / (inner.cos() - outer.cos()).max(1e-3);
        let (first_shadow_view, shadow_view_count) = match enabled_shadows(shadows, self.map_cap) {
            Some(shadows) => self.shadow_views.claim(&[spot_view(
                transform.translation(),
                transform.forward(),
                outer,
                light.range,
                &shadows,
            )]),
            None => (0, 0),
        };
        PointLightGpu {
            position_range: transform.translation().extend(light.range.max(0.0)).into(),
            radiance: radiance(light.color, light.intensity, self.light_scale),
            spot_direction: transform.forward().extend(0.0).into(),
            spot_cone: [scale, -outer.cos() * scale, 0.0, 0.0],
            first_shadow_view,
            shadow_view_count,
            _padding: [0; 2],
        }
    }
}
