//! The Extract stage's part of scene shadows: after the core has extracted the lights, each
//! light with [`LightShadows`] claims its maps (cascades, a spot map, cube faces) in the frame's
//! list, up to [`MAX_SHADOW_VIEWS`], and its GPU record is told where they are.

use hecs::{Entity, World};

use super::cascades::KeptCascades;
use super::views::{CascadeCamera, directional_views, point_views, spot_view};
use crate::gpu::GpuContext;
use crate::render::{ExtractedFrame, MAX_SHADOW_VIEWS, RenderTarget, ShadowViewPlan};
use crate::{
    AppError, DirectionalLight, GlobalTransform, LightShadows, PointLight, Resources, SpotLight,
};

/// What the shadow maps of one frame may take of the GPU's memory: the array holds every map at
/// the largest size asked for.
const SHADOW_MAP_BUDGET_BYTES: u64 = 512 << 20;

/// Whether the last frame's lights asked for more maps than there are (warned once per
/// episode).
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct ShadowMapOverflow(bool);

/// The shadows plugin's Extract system: plans the frame's shadow maps and points each casting
/// light at its own.
pub(super) fn plan_shadow_maps(
    world: &mut World,
    resources: &mut Resources,
) -> Result<(), AppError> {
    let aspect = resources.require::<RenderTarget>()?.aspect();
    let map_cap = shadow_map_cap(world, device_texture_limit(resources));
    let Some((camera, transform)) = resources.require::<ExtractedFrame>()?.camera else {
        return Ok(());
    };
    let matrix = transform.to_mat4();
    let cascade_camera = CascadeCamera {
        position: transform.translation(),
        forward: transform.forward(),
        right: matrix.x_axis.truncate().normalize_or_zero(),
        up: matrix.y_axis.truncate().normalize_or_zero(),
        projection: camera.projection,
        aspect,
    };
    let mut list = ShadowViewList::default();
    let mut suns = std::mem::take(resources.get_or_default::<KeptCascades>());
    suns.begin_frame();
    let extracted = resources.require_mut::<ExtractedFrame>()?;
    let shadows =
        |entity: Entity| enabled_shadows(world.get::<&LightShadows>(entity).ok(), map_cap);
    let place = |entity: Entity| world.get::<&GlobalTransform>(entity).ok().map(|t| *t);
    for (slot, &entity) in extracted.lights.directional.iter().enumerate() {
        let (Some(settings), Some(transform)) = (shadows(entity), place(entity)) else {
            continue;
        };
        let fresh = directional_views(&cascade_camera, transform.forward(), &settings);
        let views = suns.follow(entity, (&cascade_camera, &settings), fresh);
        let light = &mut extracted.frame.directional_lights[slot];
        (light.first_shadow_view, light.shadow_view_count) = list.claim(&views);
    }
    for (slot, &entity) in extracted.lights.point.iter().enumerate() {
        let (Some(settings), Some(transform)) = (shadows(entity), place(entity)) else {
            continue;
        };
        let position = transform.translation();
        let views = if let Ok(light) = world.get::<&PointLight>(entity) {
            point_views(position, light.range, &settings).to_vec()
        } else if let Ok(light) = world.get::<&SpotLight>(entity) {
            let outer = light.sanitized_cone().1;
            vec![spot_view(
                position,
                transform.forward(),
                outer,
                light.range,
                &settings,
            )]
        } else {
            continue;
        };
        let light = &mut extracted.point_lights[slot];
        (light.first_shadow_view, light.shadow_view_count) = list.claim(&views);
    }
    extracted.shadow_views = list.views;
    suns.end_frame();
    *resources.get_or_default::<KeptCascades>() = suns;
    let overflow = resources.get_or_default::<ShadowMapOverflow>();
    if list.overflowed && !overflow.0 {
        log::warn!(
            "the lights ask for more than {MAX_SHADOW_VIEWS} shadow maps: the rest cast no scene shadow"
        );
    }
    overflow.0 = list.overflowed;
    Ok(())
}

/// The shadow maps of a frame as its lights claim them, up to [`MAX_SHADOW_VIEWS`].
#[derive(Default)]
struct ShadowViewList {
    views: Vec<ShadowViewPlan>,
    overflowed: bool,
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
        if views.is_empty() || !views.iter().all(finite) {
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
fn enabled_shadows(shadows: Option<hecs::Ref<'_, LightShadows>>, cap: u32) -> Option<LightShadows> {
    shadows
        .map(|shadows| shadows.sanitized())
        .filter(|shadows| shadows.enabled)
        .map(|shadows| LightShadows {
            map_size: shadows.map_size.min(cap),
            ..shadows
        })
}

/// The largest texture side the device allows (the shadow maps' cap), or the maps' own cap
/// before there is a device.
fn device_texture_limit(resources: &Resources) -> u32 {
    resources
        .get::<GpuContext>()
        .map_or(LightShadows::MAX_MAP_SIZE, |gpu| {
            gpu.device.limits().max_texture_dimension_2d
        })
}
