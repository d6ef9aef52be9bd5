//! [`MaterialPlugin`]: what adding a [`Material`] registers (its entry in the registry, its
//! Extract and Prepare systems, its draws in each render phase) and builds when the app starts
//! (its batches and shader).

use std::marker::PhantomData;

use hecs::World;

use super::Material;
use super::batches::CompileOptions;
use super::batches::{FrameNumbers, MaterialBatches, MaterialShader, PrepareInputs};
use super::deferred::{ResolveRound, ResolveTargets};
use super::extract::{ExtractedMaterials, extract_materials};
use super::pipelines::FrameVariant;
use super::registry::{MaterialEntry, MaterialRegistry};
use super::shader_check::check_material_shader;
use super::{MeshLodCache, PixelFootprint};
use crate::gpu::{FragmentInvocationCounter, PipelineCompilation, UploadStats};
use crate::render::PhaseBindings;
use crate::render::anti_aliasing::{AntiAliasingFrame, ObjectMotions};
use crate::render::{
    DrawPhase, ExtractedFrame, RenderPhases, RenderTarget, Renderer, SortedDraws, VisibilityBuffer,
    VisiblePolygons, phase_bindings,
};
use crate::{
    App, AppError, Assets, BoxedError, GpuContext, Image, Mesh, Plugin, Resources, Stage,
    free_unused_assets,
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
#[error("material {material} declares {slots} derived texture slots; at most {max} are bound", max = crate::gpu::MAX_DERIVED_TEXTURES)]
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

impl<M: Material> Plugin for MaterialPlugin<M> {
    fn build(&self, app: &mut App) {
        let registry = app.resources.get_or_default::<MaterialRegistry>();
        if let Some(entry) = registry.entry_mut::<M>() {
            entry.draws_meshes_without_material |= self.draws_meshes_without_material;
            return;
        }
        registry
            .entries
            .push(MaterialEntry::new::<M>(self.draws_meshes_without_material));
        // The store of materials shared by handle, freed like meshes and images.
        app.resources.get_or_default::<Assets<M>>();
        app.add_system(Stage::PostUpdate, free_unused_assets::<M>)
            .add_system(Stage::Extract, extract_materials::<M>)
            .add_system(Stage::Prepare, prepare_materials::<M>);
        app.resources.get_or_default::<MeshLodCache>();
        let phases = app.resources.get_or_default::<RenderPhases>();
        add_phase_draws::<M>(phases);
        phases.declare_owner::<M>(M::NAME, false);
    }

    fn finish(&self, app: &mut App) -> Result<(), BoxedError> {
        if app.resources.contains::<MaterialBatches<M>>() {
            return Ok(());
        }
        check_texture_slots::<M>()?;
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
        let shader = material_shader::<M>(&gpu.device);
        // The shader that will compile, checked once before any GPU work: one that cannot
        // work leaves nothing half-built.
        check_material_shader(M::NAME, &shader.composed, M::SURFACE_ON_POLYGON)?;
        let mut batches = MaterialBatches::<M>::new(
            gpu,
            &renderer.frame,
            shader,
            target.scene_format(),
            renderer.depth_prepass,
            &phase_bindings(
                renderer.depth_prepass,
                &renderer.dummy_depth,
                (
                    &renderer.shadow_maps,
                    &renderer.environment,
                    &renderer.lights,
                ),
                (renderer.visibility.as_ref(), &renderer.dummy_visibility),
                target,
            ),
            CompileOptions {
                counter,
                background: app
                    .resources
                    .get::<PipelineCompilation>()
                    .and_then(PipelineCompilation::background_counter),
            },
        );
        // With background compiles, what stands in for a variant not ready is ready itself.
        batches.pipelines.compile_stand_in(&gpu.device);
        app.insert_resource(batches);
        app.resources
            .get_or_default::<RenderPhases>()
            .declare_owner::<M>(M::NAME, shader.deferred);
        #[cfg(feature = "dev-tools")]
        if let Some(entry) = app
            .resources
            .get_or_default::<MaterialRegistry>()
            .entry_mut::<M>()
        {
            entry.set_compiled(shader.composed);
        }
        Ok(())
    }
}

/// Registers material `M`'s draws in every phase: prepass, opaque, transparent, deferred
/// resolve and shadow maps.
fn add_phase_draws<M: Material>(phases: &mut RenderPhases) {
    phases.add_sorted::<M>(DrawPhase::Prepass, |resources, pass, batches| {
        draw_listed::<M>(resources, pass, DrawPhase::Prepass, batches);
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
    phases.add_sorted::<M>(DrawPhase::Transparent, |resources, pass, batches| {
        draw_listed::<M>(resources, pass, DrawPhase::Transparent, batches);
    });
    phases.add_draw_when::<M>(
        DrawPhase::Motion,
        |resources, pass| draw_materials::<M>(resources, pass, DrawPhase::Motion),
        |resources| {
            resources
                .get::<MaterialBatches<M>>()
                .is_some_and(|batches| batches.draws_in(DrawPhase::Motion))
        },
    );
    phases.add_sorted::<M>(DrawPhase::Candidates, |resources, pass, batches| {
        draw_listed::<M>(resources, pass, DrawPhase::Candidates, batches);
    });
    phases.add_draw::<M>(DrawPhase::SettledDepth, |resources, pass| {
        draw_materials::<M>(resources, pass, DrawPhase::SettledDepth);
    });
    phases.add_settling_resolve::<M>(|resources, pass| {
        if let Some(batches) = resources.get::<MaterialBatches<M>>() {
            batches.dispatch_resolves(pass, ResolveRound::Settling);
        }
    });
    phases.add_resolve::<M>(
        |resources, pass| {
            if let Some(batches) = resources.get::<MaterialBatches<M>>() {
                batches.dispatch_resolves(pass, ResolveRound::Shading);
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

/// Whether material `M` declares no more texture slots (plain and derived) than are bound.
fn check_texture_slots<M: Material>() -> Result<(), BoxedError> {
    if M::TEXTURE_SLOTS.len() > super::MAX_MATERIAL_TEXTURES {
        return Err(TooManyTextureSlots {
            material: M::NAME,
            slots: M::TEXTURE_SLOTS.len(),
        }
        .into());
    }
    if M::DERIVED_TEXTURE_SLOTS > crate::gpu::MAX_DERIVED_TEXTURES {
        return Err(TooManyDerivedTextureSlots {
            material: M::NAME,
            slots: M::DERIVED_TEXTURE_SLOTS,
        }
        .into());
    }
    Ok(())
}

/// The shader material `M` compiles on `device`: its deferred shader where it has one and the
/// adapter the visibility pass, else its forward one.
fn material_shader<M: Material>(device: &wgpu::Device) -> MaterialShader {
    match M::deferred_shader() {
        Some(composed) if device.features().contains(crate::gpu::DEFERRED_FEATURES) => {
            MaterialShader {
                composed,
                deferred: true,
            }
        }
        _ => MaterialShader {
            composed: M::shader(),
            deferred: false,
        },
    }
}

/// The Prepare stage's system of material `M`.
fn prepare_materials<M: Material>(
    _: &mut World,
    resources: &mut Resources,
) -> Result<(), AppError> {
    let prepare = |resources: &mut Resources, motions: Option<&mut ObjectMotions>| {
        resources.require_scope(|resources, batches: &mut MaterialBatches<M>| {
            resources.require_scope(|resources, renderer: &mut Renderer| {
                resources.require_scope(|resources, lod_cache: &mut MeshLodCache| {
                    prepare_frame(resources, batches, (renderer, lod_cache), motions)
                })
            })
        })
    };
    // With TAA's list of moving draws, where the anti-aliasing plugin keeps one.
    match resources
        .scope(|resources, motions: &mut ObjectMotions| prepare(resources, Some(motions)))
    {
        Some(prepared) => prepared,
        None => prepare(resources, None),
    }
}

/// Prepares `batches` for this frame's extracted draws of `M`, hands the prepass its batches
/// (nearest first) and the transparent phase its blended ones, and adds what was uploaded to the renderer's count.
fn prepare_frame<M: Material>(
    resources: &Resources,
    batches: &mut MaterialBatches<M>,
    (renderer, lod_cache): (&mut Renderer, &mut MeshLodCache),
    motions: Option<&mut ObjectMotions>,
) -> Result<(), AppError> {
    let extracted = resources.require::<ExtractedMaterials<M>>()?;
    let frame = resources.require::<ExtractedFrame>()?;
    let target = resources.require::<RenderTarget>()?;
    let depth: PhaseBindings<'_> = phase_bindings(
        renderer.depth_prepass,
        &renderer.dummy_depth,
        (
            &renderer.shadow_maps,
            &renderer.environment,
            &renderer.lights,
        ),
        (renderer.visibility.as_ref(), &renderer.dummy_visibility),
        target,
    );
    let visibility = renderer.visibility.as_ref().filter(|_| renderer.deferred);
    let footprint = frame
        .camera
        .map(|(camera, transform)| PixelFootprint::new(&camera, &transform, target.size()));
    let inputs = PrepareInputs {
        gpu: resources.require::<GpuContext>()?,
        frame: &renderer.frame,
        depth: &depth,
        meshes: resources.require::<Assets<Mesh>>()?,
        images: resources.require::<Assets<Image>>()?,
        footprint: footprint.as_ref(),
        eye: (
            glam::Vec4::from(frame.frame.camera_position).truncate(),
            glam::Vec4::from(frame.frame.view_direction).truncate(),
        ),
        variant: FrameVariant {
            scene_shadows: !frame.shadow_views.is_empty(),
            environment: frame.frame.environment[1] > 0.0,
        },
        deferred: visibility.map(|visibility| resolve_targets(visibility, target, frame)),
    };
    let mut stats = UploadStats::default();
    batches.prepare(
        &inputs,
        extracted,
        &mut renderer.assets,
        lod_cache,
        &mut stats,
        FrameNumbers {
            ids: &mut renderer.visibility_ids,
            motions: motions.filter(|_| {
                resources
                    .get::<AntiAliasingFrame>()
                    .is_some_and(|aa| aa.temporal.is_some())
            }),
        },
    );
    renderer.resolves_write_background |= batches.resolve_writes_background();
    let polygon_pass = renderer.polygon_pass;
    let lists = (
        [&mut renderer.polygons, &mut renderer.candidate_polygons],
        &mut renderer.prepass_order,
        &mut renderer.candidate_order,
        &mut renderer.transparent,
    );
    hand_over_draws(batches, lists, &inputs, polygon_pass);
    lod_cache.retain_existing(inputs.meshes);
    let assets_uploaded = stats.meshes + stats.images + stats.derived > 0;
    renderer.shadow_maps.casters.add(
        batches.shadow_casters_signature(),
        batches.casters_data_changed() || assets_uploaded,
        extracted.casters_read_frame_noise,
    );
    renderer.last_upload.meshes += stats.meshes;
    renderer.last_upload.images += stats.images;
    renderer.last_upload.derived += stats.derived;
    renderer.last_upload.uniform_bytes += stats.uniform_bytes;
    Ok(())
}

/// Hands the frame's lists their draws of `M`: the polygon pass its triangles (where it may
/// run), the prepass and the candidates their batches nearest first, the transparent phase its
/// blended ones. The lists come one by one: `inputs` borrows other fields of the renderer.
fn hand_over_draws<M: Material>(
    batches: &mut MaterialBatches<M>,
    ([polygons, candidate_polygons], prepass, candidates, transparent): (
        [&mut VisiblePolygons; 2],
        &mut SortedDraws,
        &mut SortedDraws,
        &mut SortedDraws,
    ),
    inputs: &PrepareInputs<'_>,
    polygon_pass: bool,
) {
    let listed = match &inputs.deferred {
        Some(targets) if polygon_pass => batches.list_polygons(inputs.meshes, targets),
        _ => batches.list_no_polygons(),
    };
    polygons.replace::<M>(listed.visible);
    candidate_polygons.replace::<M>(listed.candidates);
    prepass.replace_marked::<M>(batches.nearest_first(DrawPhase::Prepass));
    candidates.replace_marked::<M>(batches.nearest_first(DrawPhase::Candidates));
    transparent.replace::<M>(batches.blended());
}

/// What the deferred resolve reads and writes on a frame that runs the deferred path.
fn resolve_targets<'a>(
    visibility: &'a VisibilityBuffer,
    target: &'a RenderTarget,
    frame: &ExtractedFrame,
) -> ResolveTargets<'a> {
    ResolveTargets {
        visibility: &visibility.keys,
        scene: &target.scene_view,
        target: target.id(),
        size: target.size(),
        view_projection: glam::Mat4::from_cols_array_2d(&frame.frame.view_projection),
        background: crate::render::clear_value(frame.clear_color),
    }
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

/// Records material `M`'s `listed` batches of `phase`, in the order the frame's sorted list of
/// the phase gave them.
fn draw_listed<M: Material>(
    resources: &Resources,
    pass: &mut wgpu::RenderPass<'_>,
    phase: DrawPhase,
    listed: &[u32],
) {
    if let (Some(batches), Some(renderer)) = (
        resources.get::<MaterialBatches<M>>(),
        resources.get::<Renderer>(),
    ) {
        batches.draw_listed(phase, pass, &renderer.assets, listed);
    }
}

/// The pipeline keys of material `M`'s batches in the last prepared frame, in draw order: which
/// variant each object drew with (one entry per batch of instances).
/// Whether every pipeline `key` of material `M` needs in the last prepared frame's setting is
/// compiled (not standing in for it: [`crate::gpu::PipelineCompilation::background`]).
#[doc(hidden)] // A test hook.
pub fn pipelines_ready<M: Material>(resources: &Resources, key: M::Key) -> bool {
    resources
        .get::<MaterialBatches<M>>()
        .is_some_and(|batches| batches.pipelines.ready(key))
}

#[doc(hidden)] // A test hook.
pub fn drawn_keys<M: Material>(resources: &Resources) -> Vec<M::Key> {
    resources
        .get::<MaterialBatches<M>>()
        .map(|batches| batches.batches.iter().map(|batch| batch.key).collect())
        .unwrap_or_default()
}

#[doc(hidden)] // A test hook: whether material `M`'s last prepared frame draws in the opaque
// raster pass, and whether it shades pixels in the deferred resolve.
pub fn drawn_in_opaque_and_resolve<M: Material>(resources: &Resources) -> (bool, bool) {
    resources
        .get::<MaterialBatches<M>>()
        .map_or((false, false), |batches| {
            (batches.draws_in(DrawPhase::Opaque), batches.has_resolves())
        })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{ParallaxOcclusionMaterial, PomPlugin, RenderPlugin};

    #[test]
    fn adding_the_material_plugins_twice_registers_each_draw_once() {
        let mut app = App::new();
        app.add_plugin(RenderPlugin::new(8, 8))
            .add_plugin(PomPlugin)
            .add_plugin(PomPlugin)
            .add_plugin(MaterialPlugin::<ParallaxOcclusionMaterial>::default());
        // The lit material (brought by PomPlugin) and the parallax material.
        let phases = app.resources.get::<RenderPhases>().unwrap();
        assert_eq!(phases.draw_count(DrawPhase::Opaque), 2);
        assert_eq!(phases.sorted_draw_count(DrawPhase::Prepass), 2);
        assert_eq!(phases.sorted_draw_count(DrawPhase::Transparent), 2);
        assert_eq!(
            app.resources
                .get::<MaterialRegistry>()
                .unwrap()
                .entries
                .len(),
            2
        );
        assert_eq!(
            app.schedule.len(Stage::Extract),
            9,
            "core + lights + tonemapping + shadows + anti-aliasing + environment + two materials + the curved silhouette's mesh check"
        );
    }

    /// A material that asks for one texture slot too many.
    #[derive(Clone, Debug, Default, PartialEq)]
    struct TooManyTextures;

    impl Material for TooManyTextures {
        type PerDraw = crate::LitParams;
        type Key = ();
        const NAME: &'static str = "too many textures";
        const PER_DRAW_WGSL_NAME: &'static str = "LitParams";
        const TEXTURE_SLOTS: &'static [crate::gpu::DefaultTexture] =
            &[crate::gpu::DefaultTexture::WhiteSrgb; super::super::MAX_MATERIAL_TEXTURES + 1];
        fn shader() -> crate::render::shaders::ComposedShader {
            crate::lit::LIT_SHADER
        }
        fn textures(&self) -> super::super::MaterialTextures {
            [None; super::super::MAX_MATERIAL_TEXTURES]
        }
        fn key(&self) {}
        fn fragment(_: ()) -> super::super::ShaderEntry {
            super::super::ShaderEntry::entry("fs_main")
        }
        fn per_draw(
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
