//! One draw's entry in the frame: its uniform, key and place in the order, and the textures and
//! bounds they are computed from; every draw's, gathered for the full preparation.

use glam::Mat4;

use super::{ExtractedDraw, MaterialBatches, PrepareInputs};
use crate::gpu::{BoundTextures, GpuAssets, MAX_DERIVED_TEXTURES, UploadStats};
use crate::material::draw_order::{SortEntry, view_depth};
use crate::material::extract::ExtractedMaterials;
use crate::material::{
    DrawView, MAX_MATERIAL_TEXTURES, Material, MeshLodBounds, MeshLodCache, TextureFacts,
};

impl<M: Material> MaterialBatches<M> {
    /// Uploads each draw's mesh and textures, and computes its uniform (from the textures as
    /// bound), key and sort entry, in extraction order. Where the draws are last frame's
    /// entities, a draw whose material did not change keeps its uniform (it depends on the
    /// material and its textures alone), unless a texture was uploaded since.
    pub(super) fn gather(
        &mut self,
        inputs: &PrepareInputs<'_>,
        extracted: &ExtractedMaterials<M>,
        assets: &mut GpuAssets,
        lod_cache: &mut MeshLodCache,
        stats: &mut UploadStats,
    ) {
        let draws = &extracted.draws;
        self.order.clear();
        let keeps_uniforms = extracted.same_entities && self.uniform_data.len() == draws.len();
        if !keeps_uniforms {
            self.uniform_data.clear();
        }
        let mut new_materials = extracted.changed_materials.iter().peekable();
        // Neighbouring draws mostly share mesh and textures: look each up once per run.
        let mut last_mesh = None;
        let mut bounds = None;
        let mut last_textures = None;
        let mut facts = [None; MAX_MATERIAL_TEXTURES];
        for (index, (draw, material)) in draws.iter().zip(&extracted.materials).enumerate() {
            if last_mesh != Some(draw.mesh) {
                stats.meshes +=
                    u32::from(assets.prepare_mesh(inputs.gpu, inputs.meshes, draw.mesh));
                bounds = lod_cache.bounds(inputs.meshes, draw.mesh);
                last_mesh = Some(draw.mesh);
            }
            let textures = bound_textures(material);
            if last_textures != Some(textures) {
                facts = prepare_textures(inputs, textures, assets, stats);
                last_textures = Some(textures);
            }
            let new_material = new_materials.next_if_eq(&&index).is_some();
            let facts_kept = self.uniforms_serial == Some(assets.upload_serial());
            let uniform = if keeps_uniforms && !new_material && facts_kept {
                self.uniform_data[index]
            } else {
                material.per_draw(&facts)
            };
            let entry = draw_entry(inputs, (draw, material, index), bounds, &uniform, textures);
            if keeps_uniforms {
                self.uniform_data[index] = uniform;
            } else {
                self.uniform_data.push(uniform);
            }
            self.order.push(entry);
        }
        self.uniforms_serial = Some(assets.upload_serial());
    }
}

/// Draw `index`'s entry in the order, seen from the frame's eye, its uniform being `uniform`
/// (what [`Material::per_draw`] made of `material` with the textures as bound).
pub(super) fn draw_entry<M: Material>(
    inputs: &PrepareInputs<'_>,
    (draw, material, index): (&ExtractedDraw<M>, &M, usize),
    bounds: Option<MeshLodBounds>,
    uniform: &M::PerDraw,
    textures: BoundTextures,
) -> SortEntry<M::Key> {
    let mut view = DrawView {
        model: draw.model,
        bounds,
        footprint: inputs.footprint,
    };
    let key = material.draw_key(material.key(), uniform, &mut view);
    // Blended draws are ordered by their centre, as a mesh placed away from its origin (a glTF
    // primitive with its vertices where it stands) has it elsewhere; the prepass by the nearest
    // point of the bounding sphere (a floor reaching the eye is near, wherever its centre is).
    let (centre, radius) = bounding_sphere(draw.model, bounds.as_ref());
    let centre_view_depth = view_depth(centre, inputs.eye);
    SortEntry::new(
        draw,
        index,
        (key, textures),
        inputs.eye,
        centre_view_depth - radius,
        M::blends(key).then_some(centre_view_depth),
    )
}

/// The world-space centre and radius of the bounding sphere of a mesh with `bounds` drawn with
/// `model` (without bounds: its origin, radius 0).
fn bounding_sphere(model: Mat4, bounds: Option<&MeshLodBounds>) -> (glam::Vec3, f32) {
    bounds.map_or((model.w_axis.truncate(), 0.0), |bounds| {
        let scale = model
            .x_axis
            .length()
            .max(model.y_axis.length())
            .max(model.z_axis.length());
        (model.transform_point3(bounds.center), bounds.radius * scale)
    })
}

/// The textures `material` binds; entries past the declared derived slots are not bound, so
/// they must not split batches.
pub(super) fn bound_textures<M: Material>(material: &M) -> BoundTextures {
    let derived_slots = M::DERIVED_TEXTURE_SLOTS.min(MAX_DERIVED_TEXTURES);
    let mut derived = material.derived_textures();
    derived[derived_slots..].fill(None);
    BoundTextures {
        images: material.textures(),
        derived,
    }
}

/// Uploads `textures` where needed (images, then the textures derived from them) and returns
/// each slot's image as the GPU holds it.
pub(super) fn prepare_textures(
    inputs: &PrepareInputs<'_>,
    textures: BoundTextures,
    assets: &mut GpuAssets,
    stats: &mut UploadStats,
) -> [Option<TextureFacts>; MAX_MATERIAL_TEXTURES] {
    let mut facts = [None; MAX_MATERIAL_TEXTURES];
    for (slot, image) in textures.images.iter().enumerate() {
        facts[slot] = image.and_then(|image| {
            stats.images += u32::from(assets.prepare_image(inputs.gpu, inputs.images, image));
            assets.image(image).map(|image| image.facts())
        });
    }
    // Their sources are among the images: uploaded (or re-uploaded) just above.
    for derived in textures.derived.iter().flatten() {
        stats.derived += u32::from(assets.prepare_derived(inputs.gpu, *derived));
    }
    facts
}
