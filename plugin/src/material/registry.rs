//! [`MaterialRegistry`]: the material types of the app, which the extraction of meshes without
//! a material, the deferred path and shader hot reload consult.

#[cfg(feature = "dev-tools")]
use std::any::Any;
use std::any::TypeId;

use super::Material;
#[cfg(feature = "dev-tools")]
use super::batches::MaterialBatches;
#[cfg(feature = "dev-tools")]
use crate::Resources;
#[cfg(feature = "dev-tools")]
use crate::render::shaders::ComposedShader;

/// Pipelines rebuilt from a recompiled shader, not yet swapped in (hot reload).
#[cfg(feature = "dev-tools")]
pub(crate) type RebuiltPipelines = Box<dyn Any>;

/// One registered material type.
pub(crate) struct MaterialEntry {
    type_id: TypeId,
    /// Its shader as compiled (its deferred shader where it has one and the adapter the
    /// visibility pass).
    #[cfg(feature = "dev-tools")]
    pub(crate) shader: ComposedShader,
    /// Whether entities of an archetype have it, of their own or shared (a handle to one).
    has: fn(&hecs::Archetype) -> bool,
    /// Whether it also draws, with its default, meshes that have no registered material.
    pub(super) draws_meshes_without_material: bool,
    /// Builds every pipeline in use from a recompiled shader module.
    #[cfg(feature = "dev-tools")]
    pub(crate) rebuild:
        fn(&Resources, &wgpu::Device, wgpu::ShaderModule) -> Option<RebuiltPipelines>,
    /// Swaps pipelines from `rebuild` in.
    #[cfg(feature = "dev-tools")]
    pub(crate) swap: fn(&mut Resources, RebuiltPipelines),
}

impl MaterialEntry {
    /// Material `M`'s entry, as registered before its shader is compiled.
    pub(super) fn new<M: Material>(draws_meshes_without_material: bool) -> Self {
        Self {
            type_id: TypeId::of::<M>(),
            has: |archetype| archetype.has::<M>() || archetype.has::<crate::Handle<M>>(),
            draws_meshes_without_material,
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
        }
    }

    /// Records the shader the material compiled (hot reload recompiles it).
    #[cfg(feature = "dev-tools")]
    pub(super) fn set_compiled(&mut self, shader: ComposedShader) {
        self.shader = shader;
    }
}

/// The material types of the app, in the order their plugins were added. A resource.
#[derive(Default)]
pub(crate) struct MaterialRegistry {
    pub(crate) entries: Vec<MaterialEntry>,
}

impl MaterialRegistry {
    /// Material `M`'s entry, if its plugin was added.
    pub(super) fn entry_mut<M: 'static>(&mut self) -> Option<&mut MaterialEntry> {
        self.entries
            .iter_mut()
            .find(|entry| entry.type_id == TypeId::of::<M>())
    }

    /// Whether material `M` also draws meshes that have no registered material.
    pub(super) fn draws_meshes_without_material<M: 'static>(&self) -> bool {
        self.entries
            .iter()
            .any(|entry| entry.type_id == TypeId::of::<M>() && entry.draws_meshes_without_material)
    }

    /// Whether entities of `archetype` have any registered material.
    pub(super) fn has_any(&self, archetype: &hecs::Archetype) -> bool {
        self.entries.iter().any(|entry| (entry.has)(archetype))
    }
}
