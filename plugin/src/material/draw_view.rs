//! What a material may ask about one draw's place in the view, to pick a cheaper pipeline
//! variant for an object that is far away (see `lowest_mip.rs`).

use glam::Mat4;

use super::lowest_mip::{MeshLodBounds, PixelFootprint, lowest_mip};
use crate::gpu::TextureFacts;

/// One draw as the view sees it: its mesh's bounds, its transform and the camera's pixel size.
pub struct DrawView<'a> {
    pub(crate) model: Mat4,
    pub(crate) bounds: Option<MeshLodBounds>,
    pub(crate) footprint: Option<&'a PixelFootprint>,
}

impl DrawView<'_> {
    /// The lowest mip level any pixel of this draw can sample `texture` at (as the shaders'
    /// `mip_level` computes it), or `None` when it cannot be bounded (no camera, a mesh without
    /// area). Conservative: the true level of every pixel is at least this.
    pub fn lowest_mip(&mut self, texture: &TextureFacts) -> Option<f32> {
        let footprint = self.footprint?;
        let bounds = self.bounds?;
        lowest_mip(
            &bounds,
            &self.model,
            footprint,
            (texture.width, texture.height),
        )
    }
}
