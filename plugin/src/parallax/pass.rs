//! The parallax material's pipelines, buffers and bind groups inside the main pass.

use super::extract::ExtractedPom;
use super::gpu::PomObject;
use crate::render::{
    DefaultTexture, FrameUniformBuffer, GpuAssets, GpuContext, ObjectBuffer, TextureBindGroups,
    mesh_pipeline, shaders,
};

/// Pipelines (with and without depth offset), the per-draw buffer and the texture bind groups.
#[derive(Debug)]
pub struct PomPass {
    pipeline: wgpu::RenderPipeline,
    depth_offset_pipeline: wgpu::RenderPipeline,
    pipeline_layout: wgpu::PipelineLayout,
    color_format: wgpu::TextureFormat,
    frame_layout: wgpu::BindGroupLayout,
    objects: ObjectBuffer<PomObject>,
    frame_bind_group: wgpu::BindGroup,
    materials: TextureBindGroups<3>,
}

fn frame_bind_group(
    gpu: &GpuContext,
    layout: &wgpu::BindGroupLayout,
    frame: &FrameUniformBuffer,
    objects: &wgpu::Buffer,
) -> wgpu::BindGroup {
    gpu.device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("parallax frame bind group"),
        layout,
        entries: &[
            wgpu::BindGroupEntry {
                binding: 0,
                resource: frame.buffer().as_entire_binding(),
            },
            wgpu::BindGroupEntry {
                binding: 1,
                resource: objects.as_entire_binding(),
            },
        ],
    })
}

/// The pass's pipelines: without and with depth offset.
fn parallax_pipelines(
    device: &wgpu::Device,
    layout: &wgpu::PipelineLayout,
    shader: &wgpu::ShaderModule,
    color_format: wgpu::TextureFormat,
) -> [wgpu::RenderPipeline; 2] {
    let pipeline = |label: &str, entry_point: &str| {
        mesh_pipeline(device, label, layout, shader, entry_point, color_format)
    };
    [
        pipeline("parallax pipeline", "fs_main"),
        pipeline("parallax depth-offset pipeline", "fs_main_depth_offset"),
    ]
}

impl PomPass {
    /// Compiles `pom.wgsl` and creates both pipelines for targets of `color_format`.
    pub fn new(
        gpu: &GpuContext,
        frame: &FrameUniformBuffer,
        color_format: wgpu::TextureFormat,
    ) -> Self {
        let device = &gpu.device;
        let shader = shaders::PARALLAX.create_module(device);
        let frame_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("parallax frame layout"),
            entries: &[
                FrameUniformBuffer::layout_entry(),
                ObjectBuffer::<PomObject>::layout_entry(1),
            ],
        });
        let materials = TextureBindGroups::new(
            gpu,
            "parallax material",
            [
                DefaultTexture::WhiteSrgb,
                DefaultTexture::FlatNormal,
                DefaultTexture::WhiteLinear,
            ],
        );
        let layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("parallax pipeline layout"),
            bind_group_layouts: &[Some(&frame_layout), Some(materials.layout())],
            immediate_size: 0,
        });
        let [pipeline, depth_offset_pipeline] =
            parallax_pipelines(device, &layout, &shader, color_format);
        let objects = ObjectBuffer::new(gpu, "parallax object buffer", 16);
        let frame_bind_group = frame_bind_group(gpu, &frame_layout, frame, objects.buffer());
        Self {
            pipeline,
            depth_offset_pipeline,
            pipeline_layout: layout,
            color_format,
            frame_layout,
            objects,
            frame_bind_group,
            materials,
        }
    }

    /// Pipelines like the pass's own (without and with depth offset) from `shader` (a
    /// recompiled `pom.wgsl`), for shader hot reload: check them in an error scope before
    /// [`PomPass::set_pipelines`].
    pub fn build_pipelines(
        &self,
        device: &wgpu::Device,
        shader: &wgpu::ShaderModule,
    ) -> [wgpu::RenderPipeline; 2] {
        parallax_pipelines(device, &self.pipeline_layout, shader, self.color_format)
    }

    /// Replaces both pipelines with those from [`PomPass::build_pipelines`].
    pub fn set_pipelines(&mut self, [pipeline, depth_offset]: [wgpu::RenderPipeline; 2]) {
        self.pipeline = pipeline;
        self.depth_offset_pipeline = depth_offset;
    }

    /// Uploads the per-draw data that changed and prepares texture bind groups. Returns the
    /// bytes written.
    pub fn prepare(
        &mut self,
        gpu: &GpuContext,
        frame: &FrameUniformBuffer,
        extracted: &ExtractedPom,
        assets: &GpuAssets,
    ) -> u64 {
        let objects: Vec<PomObject> = extracted.draws.iter().map(|draw| draw.object).collect();
        let (written, grew) = self.objects.upload(gpu, &objects);
        if grew {
            self.frame_bind_group =
                frame_bind_group(gpu, &self.frame_layout, frame, self.objects.buffer());
        }
        self.materials.prepare(
            gpu,
            assets,
            extracted.draws.iter().map(|draw| draw.textures),
        );
        written
    }

    /// Records one draw per extracted POM entity whose mesh is on the GPU.
    pub fn draw(
        &self,
        pass: &mut wgpu::RenderPass<'_>,
        extracted: &ExtractedPom,
        assets: &GpuAssets,
    ) {
        pass.set_bind_group(0, &self.frame_bind_group, &[]);
        let mut depth_offset = None;
        for (index, draw) in extracted.draws.iter().enumerate() {
            let (Some(mesh), Some(material)) =
                (assets.mesh(draw.mesh), self.materials.get(&draw.textures))
            else {
                continue;
            };
            if depth_offset != Some(draw.depth_offset) {
                pass.set_pipeline(if draw.depth_offset {
                    &self.depth_offset_pipeline
                } else {
                    &self.pipeline
                });
                depth_offset = Some(draw.depth_offset);
            }
            pass.set_bind_group(1, material, &[]);
            pass.set_vertex_buffer(0, mesh.vertices.slice(..));
            pass.set_index_buffer(mesh.indices.slice(..), wgpu::IndexFormat::Uint32);
            let instance = index as u32;
            pass.draw_indexed(0..mesh.index_count, 0, instance..instance + 1);
        }
    }
}
