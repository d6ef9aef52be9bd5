//! Extract stage of the parallax material: one draw per entity, with its material sanitized.

use std::collections::HashMap;

use hecs::{Entity, World};

use super::gpu::PomObject;
use super::lod_switch::{MeshLodCache, PixelFootprint, lowest_mip};
use super::material::{HeightSource, ParallaxOcclusionMaterial};
use super::pipelines::PomPipelineKey;
use crate::render::{RenderTarget, TextureKey};
use crate::{AssetId, Assets, GlobalTransform, Handle, Image, Mesh, Resources, active_camera};

/// One parallax-mapped mesh to draw.
#[derive(Clone, Debug, PartialEq)]
pub struct PomDraw {
    /// The mesh.
    pub mesh: AssetId<Mesh>,
    /// Base colour, normal map, height texture (`None` binds the defaults).
    pub textures: TextureKey<3>,
    /// The pipeline it draws with (its modes and depth offset).
    pub pipeline: PomPipelineKey,
    /// Transform and parameters.
    pub object: PomObject,
}

/// This frame's parallax draws, sorted by pipeline, then textures. A resource.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ExtractedPom {
    /// The draws.
    pub draws: Vec<PomDraw>,
}

/// The last material each entity was warned about, so a bad value is logged once, not per frame.
/// A resource.
#[derive(Debug, Default)]
pub struct MaterialWarnings(HashMap<Entity, ParallaxOcclusionMaterial>);

impl MaterialWarnings {
    /// Number of entities whose material has been clamped.
    pub fn len(&self) -> usize {
        self.0.len()
    }

    /// Whether no material needed clamping.
    pub fn is_empty(&self) -> bool {
        self.0.is_empty()
    }
}

fn height_texture(material: &ParallaxOcclusionMaterial) -> Option<AssetId<Image>> {
    match &material.height_map {
        Some(HeightSource::Texture(handle)) => Some(handle.id()),
        Some(HeightSource::NormalMapAlpha) => material.normal_map.as_ref().map(Handle::id),
        None => None,
    }
}

/// The pixel size of the camera the renderer draws from, on the target.
fn pixel_footprint(world: &World, resources: &Resources) -> Option<PixelFootprint> {
    let size = resources.get::<RenderTarget>()?.size();
    let (camera, transform) = active_camera(world)?;
    Some(PixelFootprint::new(&camera, &transform, size))
}

/// The Extract stage's system for [`ParallaxOcclusionMaterial`]. A draw whose every pixel is
/// past its LOD threshold gets the normal-mapping pipeline (see `lod_switch.rs`).
pub fn extract_pom(world: &mut World, resources: &mut Resources) {
    let mut warnings = resources.remove::<MaterialWarnings>().unwrap_or_default();
    let mut lod_cache = resources.remove::<MeshLodCache>().unwrap_or_default();
    let footprint = pixel_footprint(world, resources);
    let meshes = resources.get::<Assets<Mesh>>();
    let images = resources.get::<Assets<Image>>();
    let mut draws = Vec::new();
    for (entity, mesh, transform, material) in world
        .query::<(
            Entity,
            &Handle<Mesh>,
            &GlobalTransform,
            &ParallaxOcclusionMaterial,
        )>()
        .iter()
    {
        let model = transform.to_mat4();
        if !model.is_finite() {
            log::warn!("parallax entity {entity:?} has a non-finite transform: not drawn");
            continue;
        }
        let problems = material.problems();
        if !problems.is_empty() && warnings.0.get(&entity) != Some(material) {
            for problem in &problems {
                log::warn!("parallax material of {entity:?}: {problem}; clamped");
            }
            warnings.0.insert(entity, material.clone());
        }
        let material = material.sanitized();
        let height = height_texture(&material);
        let size = height
            .and_then(|id| images.and_then(|images| images.get(id)))
            .map_or((1, 1), Image::size);
        draws.push(PomDraw {
            mesh: mesh.id(),
            textures: [
                material.base_color_texture.as_ref().map(Handle::id),
                material.normal_map.as_ref().map(Handle::id),
                height,
            ],
            pipeline: PomPipelineKey::of(&material),
            object: PomObject::new(&material, model, size),
        });
        if let (Some(draw), Some(footprint), Some(meshes)) = (draws.last_mut(), &footprint, meshes)
            && draw.pipeline != draw.pipeline.normal_mapping()
            && let Some(bounds) = lod_cache.bounds(meshes, mesh.id())
            && lowest_mip(&bounds, &model, footprint, size)
                .is_some_and(|mip| mip >= material.lod_threshold)
        {
            draw.pipeline = draw.pipeline.normal_mapping();
        }
    }
    draws.sort_by_key(|draw| (draw.pipeline, draw.textures, draw.mesh));
    warnings.0.retain(|entity, _| world.contains(*entity));
    if let Some(meshes) = meshes {
        lod_cache.retain_existing(meshes);
    }
    resources.insert(lod_cache);
    resources.insert(warnings);
    resources.insert(ExtractedPom { draws });
}
