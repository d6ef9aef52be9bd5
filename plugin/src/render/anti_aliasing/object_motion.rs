//! Object motion for TAA: the draws that moved since the last frame, each one's motion as the
//! matrix that takes a point of it from this frame's world to last frame's, and the pass that
//! marks each pixel with the number of the moving draw it shows.
//!
//! TAA reprojects a pixel through its depth: the point it shows, back in the world, is where it
//! was a frame ago unless its draw moved, and then it was there through the draw's motion. The
//! point is the depth buffer's, so a parallax surface that writes its depth (depth offset) moves
//! by its displaced point, exactly. Only moving draws take part in the motion pass (a still one's
//! triangles collapse outside the clip volume), drawn against the frame's depth: a scene that
//! does not move runs no pass at all, as Unreal renders velocity for movable objects only.

use bytemuck::{Pod, Zeroable};

use crate::gpu::GpuContext;
use crate::gpu::ObjectBuffer;
use crate::render::{MOTION_ID_FORMAT, RenderTarget};

/// One moving draw's motion as TAA reads it; mirrors `ObjectMotion` in taa.wgsl.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct ObjectMotion {
    /// This frame's world space to last frame's: last frame's model times this one's inverse.
    pub previous_from_current: [[f32; 4]; 4],
}

crate::wgsl_layout!(ObjectMotion {
    previous_from_current
});

/// The per-target texture of motion numbers the pass writes.
#[derive(Debug)]
struct MotionIds {
    target: u64,
    view: wgpu::TextureView,
}

/// This frame's moving draws (the materials add theirs as they prepare), their buffer, and the
/// texture of motion numbers. A resource of the anti-aliasing plugin.
#[derive(Debug)]
pub(crate) struct ObjectMotions {
    /// The device its buffer and textures live on.
    device: wgpu::Device,
    entries: Vec<ObjectMotion>,
    buffer: ObjectBuffer<ObjectMotion>,
    /// Counts the buffer's replacements (a bind group of it must then be rebuilt).
    generation: u64,
    ids: Option<MotionIds>,
    /// A 1 × 1 texture of motion numbers, bound while nothing moves.
    still_ids: wgpu::TextureView,
}

impl ObjectMotions {
    pub(crate) fn new(gpu: &GpuContext) -> Self {
        Self {
            device: gpu.device.clone(),
            entries: Vec::new(),
            buffer: ObjectBuffer::new(gpu, "object motions", 16),
            generation: 0,
            ids: None,
            still_ids: motion_id_texture(gpu, (1, 1)),
        }
    }

    /// Whether its buffer and textures live on `gpu`'s device (not on one since replaced).
    pub(crate) fn made_on(&self, gpu: &GpuContext) -> bool {
        self.device == gpu.device
    }

    /// Forgets last frame's motions (the Prepare stage starts here).
    pub(crate) fn reset(&mut self) {
        self.entries.clear();
    }

    /// Adds the motion of a draw placed by `previous` last frame and by `current` now; returns
    /// its number for the draw's transform (0, still, where `current` has no inverse).
    pub(crate) fn push(&mut self, previous: glam::Mat4, current: glam::Mat4) -> u32 {
        let inverse = current.inverse();
        let motion = previous * inverse;
        if current.determinant().abs() <= f32::MIN_POSITIVE || !motion.is_finite() {
            return 0;
        }
        self.entries.push(ObjectMotion {
            previous_from_current: motion.to_cols_array_2d(),
        });
        self.entries.len() as u32
    }

    /// Whether any draw moved this frame.
    pub(crate) fn any(&self) -> bool {
        !self.entries.is_empty()
    }

    /// Uploads this frame's motions and, where some draw moved, makes the texture of motion
    /// numbers for `target` unless it has one.
    pub(crate) fn prepare(&mut self, gpu: &GpuContext, target: &RenderTarget) {
        if !self.any() {
            return;
        }
        if self.buffer.upload(gpu, &self.entries).1 {
            self.generation += 1;
        }
        if self
            .ids
            .as_ref()
            .is_none_or(|ids| ids.target != target.id())
        {
            self.ids = Some(MotionIds {
                target: target.id(),
                view: motion_id_texture(gpu, target.size()),
            });
        }
    }

    /// The texture the motion pass writes, once a frame with motion has made it.
    pub(crate) fn ids_view(&self) -> Option<&wgpu::TextureView> {
        self.ids.as_ref().map(|ids| &ids.view)
    }

    /// What TAA binds: the motion numbers (the still stand-in where nothing moved), the
    /// motions, and a key that changes whenever either is another resource.
    pub(crate) fn bindings(&self) -> (&wgpu::TextureView, &wgpu::Buffer, (u64, u64, bool)) {
        match (&self.ids, self.any()) {
            (Some(ids), true) => (
                &ids.view,
                self.buffer.buffer(),
                (ids.target, self.generation, true),
            ),
            _ => (
                &self.still_ids,
                self.buffer.buffer(),
                (0, self.generation, false),
            ),
        }
    }
}

fn motion_id_texture(gpu: &GpuContext, size: (u32, u32)) -> wgpu::TextureView {
    crate::render::plain_texture(
        gpu,
        "motion ids",
        size,
        MOTION_ID_FORMAT,
        wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::TEXTURE_BINDING,
    )
    .create_view(&wgpu::TextureViewDescriptor::default())
}
