//! [`MaterialPlugin`]: the Extract, Prepare and draw systems of any [`Material`], and the
//! registry of the materials an app draws.

#[cfg(feature = "dev-tools")]
use std::any::Any;
use std::any::TypeId;
use std::collections::HashMap;
use std::marker::PhantomData;

use hecs::{Entity, World};

use super::DepthBindings;
use super::Material;
use super::batches::{ExtractedDraw, MaterialBatches, MaterialShader, PrepareInputs};
use super::deferred::ResolveTargets;
#[cfg(feature = "dev-tools")]
use crate::render::shaders::ComposedShader;
use crate::render::{
    DrawPhase, ExtractedFrame, FragmentInvocationCounter, MeshLodCache, RenderPhases, RenderTarget,
    Renderer, UploadStats, depth_bindings,
};
use crate::{
    App, AppError, Assets, BoxedError, GlobalTransform, GpuContext, Handle, Image, Mesh,
    NotShadowCaster, NotShadowReceiver, Plugin, Resources, Stage,
};

/// Extracts, prepares and draws every entity that has a material `M`, a `Handle<Mesh>` and a
/// transform. Add it after [`crate::RenderPlugin`]; adding it twice is harmless.
pub struct MaterialPlugin<M> {
    draws_meshes_without_material: bool,
    _material: PhantomData<fn() -> M>,
}

impl<M> std::fmt::Debug for MaterialPlugin<M> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("MaterialPlugin")
            .field("material", &std::any::type_name::<M>())
            .field(
                "draws_meshes_without_material",
                &self.draws_meshes_without_material,
            )
            .finish()
    }
}

impl<M> Default for MaterialPlugin<M> {
    fn default() -> Self {
        Self {
            draws_meshes_without_material: false,
            _material: PhantomData,
        }
    }
}

impl<M: Material> MaterialPlugin<M> {
    /// The plugin that also draws, with `M::default()`, every mesh entity that has none of the
    /// app's registered materials.
    pub fn for_meshes_without_material() -> Self {
        Self {
            draws_meshes_without_material: true,
            _material: PhantomData,
        }
    }
}

/// Why a material plugin could not start.
#[derive(Debug, thiserror::Error)]
#[error("a material plugin needs RenderPlugin: add RenderPlugin before it")]
pub struct MissingRenderPlugin;

/// A material declares more texture slots than a material can bind.
#[derive(Debug, thiserror::Error)]
#[error("material {material} declares {slots} texture slots; at most {max} are bound", max = super::MAX_MATERIAL_TEXTURES)]
pub struct TooManyTextureSlots {
    /// The material's name.
    pub material: &'static str,
    /// Its slot count.
    pub slots: usize,
}

/// A material declares more derived texture slots than a material can bind.
#[derive(Debug, thiserror::Error)]
#[error("material {material} declares {slots} derived texture slots; at most {max} are bound", max = crate::render::MAX_DERIVED_TEXTURES)]
pub struct TooManyDerivedTextureSlots {
    /// The material's name.
    pub material: &'static str,
    /// Its derived slot count.
    pub slots: usize,
}

/// Makes material `M`'s plugin (added already) also draw meshes that have no registered
/// material, with `M::default()`. Plugin groups call it, since adding the same plugin type twice
/// is ignored.
pub fn draw_meshes_without_material<M: Material>(app: &mut App) {
    if let Some(entry) = app
        .resources
        .get_or_default::<MaterialRegistry>()
        .entry_mut::<M>()
    {
        entry.draws_meshes_without_material = true;
    }
}

/// Pipelines rebuilt from a recompiled shader, not yet swapped in (hot reload).
#[cfg(feature = "dev-tools")]
pub(crate) type RebuiltPipelines = Box<dyn Any>;

/// One registered material type.
pub(crate) struct MaterialEntry {
    type_id: TypeId,
    name: &'static str,
    /// Its shader as compiled (its deferred shader where it has one and the adapter the
    /// visibility pass).
    #[cfg(feature = "dev-tools")]
    pub(crate) shader: ComposedShader,
    /// Whether its pipelines can draw the visibility pass (it compiled its deferred shader).
    deferred: bool,
    /// Whether entities of an archetype have it.
    has: fn(&hecs::Archetype) -> bool,
    /// Whether it also draws, with its default, meshes that have no registered material.
    draws_meshes_without_material: bool,
    /// Builds every pipeline in use from a recompiled shader module.
    #[cfg(feature = "dev-tools")]
    pub(crate) rebuild:
        fn(&Resources, &wgpu::Device, wgpu::ShaderModule) -> Option<RebuiltPipelines>,
    /// Swaps pipelines from `rebuild` in.
    #[cfg(feature = "dev-tools")]
    pub(crate) swap: fn(&mut Resources, RebuiltPipelines),
}

/// The material types of the app, in the order their plugins were added. A resource.
#[derive(Default)]
pub(crate) struct MaterialRegistry {
    pub(crate) entries: Vec<MaterialEntry>,
}

impl MaterialRegistry {
    fn entry_mut<M: 'static>(&mut self) -> Option<&mut MaterialEntry> {
        self.entries
            .iter_mut()
            .find(|entry| entry.type_id == TypeId::of::<M>())
    }

    fn draws_meshes_without_material<M: 'static>(&self) -> bool {
        self.entries
            .iter()
            .any(|entry| entry.type_id == TypeId::of::<M>() && entry.draws_meshes_without_material)
    }

    /// Whether entities of `archetype` have any registered material.
    fn has_any(&self, archetype: &hecs::Archetype) -> bool {
        self.entries.iter().any(|entry| (entry.has)(archetype))
    }
}

/// Whether `owner` is a registered material whose pipelines draw the visibility pass.
pub(crate) fn is_deferred_material(resources: &Resources, owner: TypeId) -> bool {
    resources.get::<MaterialRegistry>().is_some_and(|registry| {
        registry
            .entries
            .iter()
            .any(|entry| entry.type_id == owner && entry.deferred)
    })
}

/// The first of the app's materials that cannot draw the visibility pass, if any: the deferred
/// path needs them all.
pub(crate) fn material_without_deferred_shader(resources: &Resources) -> Option<&'static str> {
    resources
        .get::<MaterialRegistry>()?
        .entries
        .iter()
        .find(|entry| !entry.deferred)
        .map(|entry| entry.name)
}

/// This frame's draws of `M`, as extracted. A resource.
pub(crate) struct ExtractedMaterials<M> {
    pub(crate) draws: Vec<ExtractedDraw<M>>,
}

/// The problems last logged for each entity whose material of type `M` is being clamped, so a
/// bad value is logged once per change, not every frame. Problems are compared as text: a NaN
/// never equals itself, a material holding one would be "changed" every frame. A resource.
#[derive(Debug)]
pub struct MaterialWarnings<M>(HashMap<Entity, Vec<String>>, PhantomData<fn() -> M>);

impl<M> MaterialWarnings<M> {
    /// Number of entities whose material is being clamped.
    pub fn len(&self) -> usize {
        self.0.len()
    }

    /// Whether no material needed clamping.
    pub fn is_empty(&self) -> bool {
        self.0.is_empty()
    }
}

impl<M: Material> Plugin for MaterialPlugin<M> {
    fn build(&self, app: &mut App) {
        let registry = app.resources.get_or_default::<MaterialRegistry>();
        if let Some(entry) = registry.entry_mut::<M>() {
            entry.draws_meshes_without_material |= self.draws_meshes_without_material;
            return;
        }
        registry.entries.push(MaterialEntry {
            type_id: TypeId::of::<M>(),
            name: M::NAME,
            deferred: false,
            has: |archetype| archetype.has::<M>(),
            draws_meshes_without_material: self.draws_meshes_without_material,
            #[cfg(feature = "dev-tools")]
            shader: M::shader(),
            #[cfg(feature = "dev-tools")]
            rebuild: |resources, device, module| {
                let batches = resources.get::<MaterialBatches<M>>()?;
                Some(Box::new(batches.pipelines.rebuilt(device, module)))
            },
            #[cfg(feature = "dev-tools")]
            swap: |resources, rebuilt| {
                if let (Ok(pipelines), Some(batches)) = (
                    rebuilt.downcast(),
                    resources.get_mut::<MaterialBatches<M>>(),
                ) {
                    batches.pipelines = *pipelines;
                }
            },
        });
        app.add_system(Stage::Extract, extract_materials::<M>)
            .add_system(Stage::Prepare, prepare_materials::<M>);
        let phases = app.resources.get_or_default::<RenderPhases>();
        phases.add_draw::<M>(DrawPhase::Prepass, |resources, pass| {
            draw_materials::<M>(resources, pass, DrawPhase::Prepass);
        });
        phases.add_draw_when::<M>(
            DrawPhase::Opaque,
            |resources, pass| draw_materials::<M>(resources, pass, DrawPhase::Opaque),
            |resources| {
                resources
                    .get::<MaterialBatches<M>>()
                    .is_some_and(|batches| batches.draws_in(DrawPhase::Opaque))
            },
        );
        phases.add_transparent::<M>(|resources, pass, batches| {
            if let (Some(material), Some(renderer)) = (
                resources.get::<MaterialBatches<M>>(),
                resources.get::<Renderer>(),
            ) {
                material.draw_blended(pass, &renderer.assets, batches);
            }
        });
        phases.add_resolve::<M>(
            |resources, pass| {
                if let Some(batches) = resources.get::<MaterialBatches<M>>() {
                    batches.dispatch_resolves(pass);
                }
            },
            |resources| {
                resources
                    .get::<MaterialBatches<M>>()
                    .is_some_and(MaterialBatches::has_resolves)
            },
        );
        phases.add_shadow_draw::<M>(|resources, pass, slot| {
            if let (Some(batches), Some(renderer)) = (
                resources.get::<MaterialBatches<M>>(),
                resources.get::<Renderer>(),
            ) {
                batches.draw_shadow_casters(pass, renderer.frame.offset(slot), &renderer.assets);
            }
        });
    }

    fn finish(&self, app: &mut App) -> Result<(), BoxedError> {
        if app.resources.contains::<MaterialBatches<M>>() {
            return Ok(());
        }
        if M::TEXTURE_SLOTS.len() > super::MAX_MATERIAL_TEXTURES {
            return Err(TooManyTextureSlots {
                material: M::NAME,
                slots: M::TEXTURE_SLOTS.len(),
            }
            .into());
        }
        if M::DERIVED_TEXTURE_SLOTS > crate::render::MAX_DERIVED_TEXTURES {
            return Err(TooManyDerivedTextureSlots {
                material: M::NAME,
                slots: M::DERIVED_TEXTURE_SLOTS,
            }
            .into());
        }
        let (Some(gpu), Some(target), Some(renderer)) = (
            app.resources.get::<GpuContext>(),
            app.resources.get::<RenderTarget>(),
            app.resources.get::<Renderer>(),
        ) else {
            return Err(MissingRenderPlugin.into());
        };
        let counter = app
            .resources
            .get::<FragmentInvocationCounter>()
            .map(|counter| counter.buffer().clone());
        // The deferred shader where the material has one and the adapter the visibility pass.
        let shader = match M::deferred_shader() {
            Some(composed)
                if gpu
                    .device
                    .features()
                    .contains(crate::render::DEFERRED_FEATURES) =>
            {
                MaterialShader {
                    composed,
                    deferred: true,
                }
            }
            _ => MaterialShader {
                composed: M::shader(),
                deferred: false,
            },
        };
        let batches = MaterialBatches::<M>::new(
            gpu,
            &renderer.frame,
            shader,
            target.scene_format(),
            renderer.depth_prepass,
            &depth_bindings(
                renderer.depth_prepass,
                &renderer.dummy_depth,
                &renderer.shadow_maps,
                (renderer.visibility.as_ref(), &renderer.dummy_visibility),
                target,
            ),
            counter,
        );
        app.insert_resource(batches);
        if let Some(entry) = app
            .resources
            .get_or_default::<MaterialRegistry>()
            .entry_mut::<M>()
        {
            entry.deferred = shader.deferred;
            #[cfg(feature = "dev-tools")]
            {
                entry.shader = shader.composed;
            }
        }
        Ok(())
    }
}

/// Whether a draw casts and receives scene shadows (its marker components).
#[derive(Clone, Copy)]
struct ShadowRoles {
    casts: bool,
    receives: bool,
}

/// The Extract stage's system of material `M`: copies each drawable entity's mesh, transform
/// and material, and logs a material's problems once per change.
fn extract_materials<M: Material>(world: &mut World, resources: &mut Resources) {
    let fallback = resources
        .get::<MaterialRegistry>()
        .is_some_and(MaterialRegistry::draws_meshes_without_material::<M>);
    if !resources.contains::<ExtractedMaterials<M>>() {
        resources.insert(ExtractedMaterials::<M> { draws: Vec::new() });
    }
    if !resources.contains::<MaterialWarnings<M>>() {
        resources.insert(MaterialWarnings::<M>(HashMap::new(), PhantomData));
    }
    resources.scope(|resources, extracted: &mut ExtractedMaterials<M>| {
        resources.scope(|resources, warnings: &mut MaterialWarnings<M>| {
            extract_into(world, resources, fallback, extracted, warnings);
        })
    });
}

fn extract_into<M: Material>(
    world: &World,
    resources: &Resources,
    fallback: bool,
    extracted: &mut ExtractedMaterials<M>,
    warnings: &mut MaterialWarnings<M>,
) {
    // Draws are rewritten in place: a material equal to the one in the same slot last frame is
    // not cloned again (a clone bumps every texture handle's reference count, and dropping the
    // old one lowers it: tens of thousands of atomic operations a frame for nothing).
    let mut count = 0;
    // `entity` is `None` for meshes drawn with the default material (found by archetype).
    let mut push = |entity: Option<Entity>,
                    mesh: &Handle<Mesh>,
                    transform: &GlobalTransform,
                    material: &M,
                    shadows: ShadowRoles| {
        let model = transform.to_mat4();
        if !model.is_finite() {
            log::warn!(
                "{} mesh {:?} has a non-finite transform: not drawn",
                M::NAME,
                mesh.id()
            );
            return;
        }
        if let Some(entity) = entity {
            let problems = material.problems();
            if problems.is_empty() {
                // Valid again: forget it, so a later bad value is logged anew.
                if !warnings.0.is_empty() {
                    warnings.0.remove(&entity);
                }
            } else if warnings.0.get(&entity) != Some(&problems) {
                for problem in &problems {
                    log::warn!("{} material of {entity:?}: {problem}; clamped", M::NAME);
                }
                warnings.0.insert(entity, problems);
            }
        }
        match extracted.draws.get_mut(count) {
            Some(draw) => {
                draw.mesh = mesh.id();
                draw.model = model;
                draw.casts_shadows = shadows.casts;
                draw.receives_shadows = shadows.receives;
                if draw.material != *material {
                    draw.material = material.clone();
                }
            }
            None => extracted.draws.push(ExtractedDraw {
                mesh: mesh.id(),
                model,
                material: material.clone(),
                casts_shadows: shadows.casts,
                receives_shadows: shadows.receives,
            }),
        }
        count += 1;
    };
    for (entity, mesh, transform, material, not_caster, not_receiver) in world
        .query::<(
            Entity,
            &Handle<Mesh>,
            &GlobalTransform,
            &M,
            Option<&NotShadowCaster>,
            Option<&NotShadowReceiver>,
        )>()
        .iter()
    {
        let shadows = ShadowRoles {
            casts: not_caster.is_none(),
            receives: not_receiver.is_none(),
        };
        push(Some(entity), mesh, transform, material, shadows);
    }
    if fallback && let Some(registry) = resources.get::<MaterialRegistry>() {
        let default = M::default();
        // Whole archetypes at a time: an entity with any registered material is skipped
        // without looking it up.
        for archetype in world.archetypes() {
            if registry.has_any(archetype) {
                continue;
            }
            if let (Some(meshes), Some(transforms)) = (
                archetype.get::<&Handle<Mesh>>(),
                archetype.get::<&GlobalTransform>(),
            ) {
                let shadows = ShadowRoles {
                    casts: !archetype.has::<NotShadowCaster>(),
                    receives: !archetype.has::<NotShadowReceiver>(),
                };
                for (mesh, transform) in meshes.iter().zip(transforms.iter()) {
                    push(None, mesh, transform, &default, shadows);
                }
            }
        }
    }
    extracted.draws.truncate(count);
    warnings.0.retain(|entity, _| world.contains(*entity));
}

/// The Prepare stage's system of material `M`.
fn prepare_materials<M: Material>(
    _: &mut World,
    resources: &mut Resources,
) -> Result<(), AppError> {
    resources
        .scope(|resources, batches: &mut MaterialBatches<M>| {
            resources
                .scope(|resources, renderer: &mut Renderer| {
                    resources
                        .scope(|resources, lod_cache: &mut MeshLodCache| {
                            let extracted = resources.require::<ExtractedMaterials<M>>()?;
                            let frame = resources.require::<ExtractedFrame>()?;
                            let target = resources.require::<RenderTarget>()?;
                            let depth: DepthBindings<'_> = depth_bindings(
                                renderer.depth_prepass,
                                &renderer.dummy_depth,
                                &renderer.shadow_maps,
                                (renderer.visibility.as_ref(), &renderer.dummy_visibility),
                                target,
                            );
                            let deferred = renderer
                                .visibility
                                .as_ref()
                                .filter(|_| renderer.deferred)
                                .map(|visibility| ResolveTargets {
                                    visibility: &visibility.keys,
                                    scene: &target.scene_view,
                                    target: target.id(),
                                    size: target.size(),
                                    view_projection: glam::Mat4::from_cols_array_2d(
                                        &frame.frame.view_projection,
                                    ),
                                });
                            let inputs = PrepareInputs {
                                gpu: resources.require::<GpuContext>()?,
                                frame: &renderer.frame,
                                depth: &depth,
                                meshes: resources.require::<Assets<Mesh>>()?,
                                images: resources.require::<Assets<Image>>()?,
                                footprint: frame.footprint.as_ref(),
                                eye: (
                                    glam::Vec4::from(frame.frame.camera_position).truncate(),
                                    glam::Vec4::from(frame.frame.view_direction).truncate(),
                                ),
                                shadow_maps: !frame.shadow_views.is_empty(),
                                deferred,
                            };
                            let mut stats = UploadStats::default();
                            batches.prepare(
                                &inputs,
                                &extracted.draws,
                                &mut renderer.assets,
                                lod_cache,
                                &mut stats,
                                &mut renderer.visibility_ids,
                            );
                            renderer.transparent.replace::<M>(batches.blended());
                            lod_cache.retain_existing(inputs.meshes);
                            renderer.last_upload.meshes += stats.meshes;
                            renderer.last_upload.images += stats.images;
                            renderer.last_upload.derived += stats.derived;
                            renderer.last_upload.uniform_bytes += stats.uniform_bytes;
                            Ok(())
                        })
                        .unwrap_or_else(|| Err(AppError::missing::<MeshLodCache>()))
                })
                .unwrap_or_else(|| Err(AppError::missing::<Renderer>()))
        })
        .unwrap_or_else(|| Err(AppError::missing::<MaterialBatches<M>>()))
}

/// Material `M`'s draws in `phase` (registered in [`RenderPhases`]).
fn draw_materials<M: Material>(
    resources: &Resources,
    pass: &mut wgpu::RenderPass<'_>,
    phase: DrawPhase,
) {
    if let (Some(batches), Some(renderer)) = (
        resources.get::<MaterialBatches<M>>(),
        resources.get::<Renderer>(),
    ) {
        batches.draw(phase, pass, &renderer.assets);
    }
}

/// The pipeline keys of material `M`'s batches in the last prepared frame, in draw order: which
/// variant each object drew with (one entry per batch of instances).
pub fn drawn_keys<M: Material>(resources: &Resources) -> Vec<M::Key> {
    resources
        .get::<MaterialBatches<M>>()
        .map(|batches| batches.batches.iter().map(|batch| batch.key).collect())
        .unwrap_or_default()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{ParallaxOcclusionMaterial, PomPlugin, RenderPlugin};

    #[test]
    fn adding_the_material_plugins_twice_registers_each_draw_once() {
        let mut app = App::new();
        app.add_plugin(RenderPlugin::headless(8, 8))
            .add_plugin(PomPlugin)
            .add_plugin(PomPlugin)
            .add_plugin(MaterialPlugin::<ParallaxOcclusionMaterial>::default());
        // The lit material (brought by PomPlugin) and the parallax material.
        let phases = app.resources.get::<RenderPhases>().unwrap();
        assert_eq!(phases.draw_count(DrawPhase::Opaque), 2);
        assert_eq!(phases.draw_count(DrawPhase::Prepass), 2);
        assert_eq!(phases.transparent_draw_count(), 2);
        assert_eq!(
            app.resources
                .get::<MaterialRegistry>()
                .unwrap()
                .entries
                .len(),
            2
        );
        assert_eq!(app.schedule.len(Stage::Extract), 3, "core + two materials");
    }

    /// A material that asks for one texture slot too many.
    #[derive(Clone, Debug, Default, PartialEq)]
    struct TooManyTextures;

    impl Material for TooManyTextures {
        type Uniform = crate::LitParams;
        type Key = ();
        const NAME: &'static str = "too many textures";
        const UNIFORM_WGSL_NAME: &'static str = "LitParams";
        const TEXTURE_SLOTS: &'static [crate::render::DefaultTexture] =
            &[crate::render::DefaultTexture::WhiteSrgb; super::super::MAX_MATERIAL_TEXTURES + 1];
        fn shader() -> crate::render::shaders::ComposedShader {
            crate::lit::LIT_SHADER
        }
        fn textures(&self) -> super::super::MaterialTextures {
            [None; super::super::MAX_MATERIAL_TEXTURES]
        }
        fn key(&self) {}
        fn fragment(_: ()) -> super::super::FragmentVariant {
            super::super::FragmentVariant::entry("fs_main")
        }
        fn uniform(
            &self,
            _: &[Option<super::super::TextureFacts>; super::super::MAX_MATERIAL_TEXTURES],
        ) -> crate::LitParams {
            crate::LitMaterial::default().gpu_params()
        }
    }

    #[test]
    fn too_many_texture_slots_is_an_error_naming_the_material() {
        let mut app = App::new();
        app.add_plugin(MaterialPlugin::<TooManyTextures>::default());
        let error = app.finish().unwrap_err().to_string();
        let expected = format!(
            "material too many textures declares {} texture slots; at most {}",
            super::super::MAX_MATERIAL_TEXTURES + 1,
            super::super::MAX_MATERIAL_TEXTURES
        );
        assert!(error.contains(&expected), "{error}");
    }
}
