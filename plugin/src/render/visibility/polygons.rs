//! The polygon pass (polygons.wgsl): on a deferred frame, the visibility keys of draws of a few
//! large triangles found in compute instead of rasterized. Where a GPU's raster and fragment
//! stages are few (the compute GPUs we measure), rasterizing a floor that fills the target
//! costs more than the resolve that shades it; casting each pixel's ray at a handful of
//! triangles costs next to nothing. Materials list such draws each frame
//! ([`VisiblePolygons::replace`]); the frame runs the pass only where no later pass tests
//! against the depth attachment, which the pass does not write (`FramePlan::polygons`).

use std::any::TypeId;

use bytemuck::{Pod, Zeroable};
use glam::Mat4;

use super::super::shaders::{self, ComposedShader, WgslFile};
use super::listed_triangle::VisiblePolygon;
use crate::gpu::GpuContext;
use crate::render::FrameUniform;

/// The pass's shader.
pub const POLYGON_PASS_SHADER: ComposedShader = ComposedShader {
    name: "polygons.wgsl",
    constants: &[shaders::deferred_header],
    files: &[
        shaders::FRAME,
        crate::render::lights::LIGHTS_WGSL,
        shaders::MESH_VERTEX,
        shaders::VISIBILITY,
        POLYGONS_ENTRY,
    ],
};

const POLYGONS_ENTRY: WgslFile = crate::wgsl_file!(nested "render/visibility/polygons.wgsl");

/// Pixels along each side of the pass's workgroups (`@workgroup_size` in WGSL).
const GROUP_SIDE: u32 = 8;

/// Triangles a draw may have (over all its instances) to be found by the pass.
pub(crate) const MAX_POLYGON_TRIANGLES: usize = 16;

/// Triangles one material lists a frame at most: every pixel of the pass loops over them all.
pub(crate) const MAX_LISTED_TRIANGLES: usize = 64;

/// Pixels a draw's triangles must span on screen (their rectangles together) for the pass to
/// pay: smaller draws rasterize as cheaply.
pub(crate) const MIN_POLYGON_PIXELS: u64 = 64 * 64;

/// The pass's parameters: the camera and target as the frame's uniform holds them (read from
/// storage, see polygons.wgsl), and the listed triangles. Mirrors `PolygonPass` in polygons.wgsl.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
struct PolygonPass {
    view_projection: [[f32; 4]; 4],
    inverse_view_projection: [[f32; 4]; 4],
    camera_position: [f32; 4],
    view_direction: [f32; 4],
    target_size: [u32; 2],
    origin: [u32; 2],
    count: u32,
    candidates: u32,
    _padding: [u32; 2],
}

crate::wgsl_layout!(PolygonPass {
    view_projection,
    inverse_view_projection,
    camera_position,
    view_direction,
    target_size,
    origin,
    count,
    candidates,
    _padding,
});

/// The pass's GPU side, made on the first frame that runs it.
#[derive(Debug)]
struct PolygonPipeline {
    pipeline: wgpu::ComputePipeline,
    uniform: wgpu::Buffer,
    polygons: wgpu::Buffer,
    /// Group 0 over the keys it was made with.
    keys_group: Option<(wgpu::Buffer, wgpu::BindGroup)>,
    polygons_group: wgpu::BindGroup,
}

/// Every material's listed triangles of this frame, and the pass that finds them.
#[derive(Debug)]
pub(crate) struct VisiblePolygons {
    /// The triangles are depth-offset polygons, found for the candidate keys.
    candidates: bool,
    lists: Vec<(TypeId, Vec<VisiblePolygon>)>,
    /// This frame's triangles of every list, and what the pass's buffers hold.
    listed: Vec<VisiblePolygon>,
    uploaded: (Vec<VisiblePolygon>, PolygonPass),
    gpu: Option<PolygonPipeline>,
    /// The pixels this frame's dispatch covers: origin, then workgroups across and down.
    dispatch: ([u32; 2], [u32; 2]),
}

impl VisiblePolygons {
    /// No triangles yet, found for the visibility keys or (`candidates`) the candidate keys.
    pub(crate) fn new(candidates: bool) -> Self {
        Self {
            candidates,
            lists: Vec::new(),
            listed: Vec::new(),
            uploaded: Default::default(),
            gpu: None,
            dispatch: Default::default(),
        }
    }

    /// Replaces `Owner`'s triangles of this frame.
    pub(crate) fn replace<Owner: 'static>(&mut self, polygons: Vec<VisiblePolygon>) {
        let owner = TypeId::of::<Owner>();
        self.lists.retain(|(listed, _)| *listed != owner);
        if !polygons.is_empty() {
            self.lists.push((owner, polygons));
        }
    }

    /// Whether no material listed a triangle this frame.
    pub(crate) fn is_empty(&self) -> bool {
        self.lists.is_empty()
    }

    /// The pass's pipeline, once a frame has prepared it.
    pub(crate) fn pipeline(&self) -> Option<&wgpu::ComputePipeline> {
        self.gpu.as_ref().map(|gpu_side| &gpu_side.pipeline)
    }

    /// Uploads what changed of this frame's triangles and of the camera and target `frame`
    /// (made where missing, with the `compiled` pipeline where another list has one) and binds
    /// `keys`, the visibility buffer the pass merges into.
    pub(crate) fn prepare(
        &mut self,
        gpu: &GpuContext,
        frame: &FrameUniform,
        keys: &wgpu::Buffer,
        compiled: Option<&wgpu::ComputePipeline>,
    ) {
        self.listed.clear();
        for (_, list) in &self.lists {
            self.listed.extend_from_slice(list);
        }
        // Nearest first: a pixel stops at the first triangle that cannot come nearer than what
        // it found (stable, so that a frame's order is the same as the last's where nothing moved).
        self.listed
            .sort_by(|a, b| a.nearest_depth().total_cmp(&b.nearest_depth()));
        let (low, high) = self
            .listed
            .iter()
            .fold(([u32::MAX; 2], [0; 2]), |(low, high), p| {
                (
                    [low[0].min(p.rect[0]), low[1].min(p.rect[1])],
                    [high[0].max(p.rect[2]), high[1].max(p.rect[3])],
                )
            });
        let origin = if self.listed.is_empty() { [0; 2] } else { low };
        let extent = [
            high[0].saturating_sub(origin[0]),
            high[1].saturating_sub(origin[1]),
        ];
        self.dispatch = (origin, extent.map(|pixels| pixels.div_ceil(GROUP_SIDE)));
        let view_projection = Mat4::from_cols_array_2d(&frame.view_projection);
        let pass = PolygonPass {
            view_projection: frame.view_projection,
            inverse_view_projection: view_projection.inverse().to_cols_array_2d(),
            camera_position: frame.camera_position,
            view_direction: frame.view_direction,
            target_size: [frame.target_size[0], frame.target_size[1]],
            origin,
            count: self.listed.len() as u32,
            candidates: u32::from(self.candidates),
            _padding: [0; 2],
        };
        let gpu_side = self.gpu.get_or_insert_with(|| {
            let pipeline = compiled.cloned().unwrap_or_else(|| polygon_pipeline(gpu));
            PolygonPipeline::with_room(gpu, pipeline, 1)
        });
        if gpu_side.polygons.size()
            < (self.listed.len() * std::mem::size_of::<VisiblePolygon>()) as u64
        {
            *gpu_side =
                PolygonPipeline::with_room(gpu, gpu_side.pipeline.clone(), self.listed.len());
            self.uploaded = Default::default();
        }
        if self.uploaded.0 != self.listed {
            gpu.write_buffer(&gpu_side.polygons, 0, bytemuck::cast_slice(&self.listed));
            self.uploaded.0.clone_from(&self.listed);
        }
        if self.uploaded.1 != pass {
            gpu.write_buffer(&gpu_side.uniform, 0, bytemuck::bytes_of(&pass));
            self.uploaded.1 = pass;
        }
        gpu_side.bind_keys(gpu, keys);
    }

    /// Records the pass into `pass` (after the keys are cleared).
    pub(crate) fn record(&self, pass: &mut wgpu::ComputePass<'_>) {
        let (Some(gpu_side), (_, [across, down])) = (&self.gpu, self.dispatch) else {
            return;
        };
        let Some((_, keys_group)) = &gpu_side.keys_group else {
            return;
        };
        if across == 0 || down == 0 {
            return;
        }
        pass.set_pipeline(&gpu_side.pipeline);
        pass.set_bind_group(0, keys_group, &[]);
        pass.set_bind_group(1, &gpu_side.polygons_group, &[]);
        pass.dispatch_workgroups(across, down, 1);
    }
}

/// Compiles the pass's pipeline (both lists share it).
fn polygon_pipeline(gpu: &GpuContext) -> wgpu::ComputePipeline {
    let module = POLYGON_PASS_SHADER.create_module(&gpu.device);
    gpu.device
        .create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some("polygon pass"),
            layout: None,
            module: &module,
            entry_point: Some("cs_visible_polygons"),
            compilation_options: Default::default(),
            cache: None,
        })
}

impl PolygonPipeline {
    /// Buffers for `count` triangles (a power of two of them) for `pipeline`.
    fn with_room(gpu: &GpuContext, pipeline: wgpu::ComputePipeline, count: usize) -> Self {
        let buffer = |label, size, usage| {
            gpu.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size,
                usage: usage | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            })
        };
        let uniform = buffer(
            "polygon pass",
            std::mem::size_of::<PolygonPass>() as u64,
            wgpu::BufferUsages::STORAGE,
        );
        let polygons = buffer(
            "polygon pass triangles",
            (count.next_power_of_two() * std::mem::size_of::<VisiblePolygon>()) as u64,
            wgpu::BufferUsages::STORAGE,
        );
        let polygons_group = gpu.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("polygon pass triangles"),
            layout: &pipeline.get_bind_group_layout(1),
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: uniform.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: polygons.as_entire_binding(),
                },
            ],
        });
        Self {
            pipeline,
            uniform,
            polygons,
            keys_group: None,
            polygons_group,
        }
    }

    /// Makes group 0 over `keys` unless it holds them already.
    fn bind_keys(&mut self, gpu: &GpuContext, keys: &wgpu::Buffer) {
        if self
            .keys_group
            .as_ref()
            .is_some_and(|(bound, _)| bound == keys)
        {
            return;
        }
        let group = gpu.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("polygon pass keys"),
            layout: &self.pipeline.get_bind_group_layout(0),
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 8,
                    resource: keys.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 9,
                    resource: keys.as_entire_binding(),
                },
            ],
        });
        self.keys_group = Some((keys.clone(), group));
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::render::visibility::listed_triangle::{
        CULL_BACK, CULL_FRONT, CULL_NONE, SUB_PIXEL_BITS,
    };
    use crate::shader::check_wgsl_layout;

    #[test]
    fn the_pass_inputs_match_their_wgsl() {
        let source = POLYGON_PASS_SHADER.source();
        assert_eq!(
            check_wgsl_layout::<VisiblePolygon>(&source, "VisiblePolygon"),
            Ok(())
        );
        assert_eq!(
            check_wgsl_layout::<PolygonPass>(&source, "PolygonPass"),
            Ok(())
        );
        let declaration = format!("@workgroup_size({GROUP_SIDE}, {GROUP_SIDE})");
        assert!(source.contains(&declaration));
        assert!(source.contains(&format!("const SUB_PIXEL_BITS: u32 = {SUB_PIXEL_BITS}u;")));
        for (name, value) in [
            ("CULL_NONE", CULL_NONE),
            ("CULL_FRONT", CULL_FRONT),
            ("CULL_BACK", CULL_BACK),
        ] {
            assert!(
                source.contains(&format!("const {name}: u32 = {value}u;")),
                "{name}"
            );
        }
    }
}
