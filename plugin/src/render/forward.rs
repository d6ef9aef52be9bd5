//! The forward pass: one pipeline drawing every mesh with the lit, normal-mapped material.

use super::GpuContext;
use super::extract::ExtractedFrame;
use super::frame_uniform::FrameUniformBuffer;
use super::gpu_assets::DefaultTexture;
use super::gpu_assets::GpuAssets;
use super::gpu_types::ObjectUniform;
use super::object_buffer::ObjectBuffer;
use super::texture_bind_groups::TextureBindGroups;
use super::{layout, shaders};

/// Pipeline, buffers and bind groups of the forward pass.
pub struct ForwardPass {
    pipeline: wgpu::RenderPipeline,
    pipeline_layout: wgpu::PipelineLayout,
    color_format: wgpu::TextureFormat,
    frame_layout: wgpu::BindGroupLayout,
    objects: ObjectBuffer<ObjectUniform>,
    frame_bind_group: wgpu::BindGroup,
    materials: TextureBindGroups<2>,
}

impl std::fmt::Debug for ForwardPass {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("ForwardPass")
            .field("materials", &self.materials)
            .finish_non_exhaustive()
    }
}

fn frame_bind_group(
    gpu: &GpuContext,
    layout: &wgpu::BindGroupLayout,
    frame: &FrameUniformBuffer,
    object_buffer: &wgpu::Buffer,
) -> wgpu::BindGroup {
    gpu.device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("forward frame bind group"),
        layout,
        entries: &[
            wgpu::BindGroupEntry {
                binding: 0,
                resource: frame.buffer().as_entire_binding(),
            },
            wgpu::BindGroupEntry {
                binding: 1,
                resource: object_buffer.as_entire_binding(),
            },
        ],
    })
}

impl ForwardPass {
    /// Compiles the shader and creates the pipeline and its fixed resources.
    /// `color_format` is the format of the target the pass draws into.
    pub fn new(
        gpu: &GpuContext,
        frame: &FrameUniformBuffer,
        color_format: wgpu::TextureFormat,
    ) -> Self {
        let device = &gpu.device;
        let shader = shaders::FORWARD.create_module(device);
        let frame_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("forward frame layout"),
            entries: &[
                FrameUniformBuffer::layout_entry(),
                ObjectBuffer::<ObjectUniform>::layout_entry(1),
            ],
        });
        let materials = TextureBindGroups::new(
            gpu,
            "forward material",
            [DefaultTexture::WhiteSrgb, DefaultTexture::FlatNormal],
        );
        let layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("forward pipeline layout"),
            bind_group_layouts: &[Some(&frame_layout), Some(materials.layout())],
            immediate_size: 0,
        });
        let pipeline = layout::mesh_pipeline(
            device,
            "forward pipeline",
            &layout,
            &shader,
            "fs_main",
            &[],
            color_format,
        );
        let objects = ObjectBuffer::new(gpu, "forward object buffer", 64);
        let frame_bind_group = frame_bind_group(gpu, &frame_layout, frame, objects.buffer());
        Self {
            pipeline,
            pipeline_layout: layout,
            color_format,
            frame_layout,
            objects,
            frame_bind_group,
            materials,
        }
    }

    /// A pipeline like the pass's own, from `shader` (a recompiled `forward.wgsl`), for shader
    /// hot reload: check it in an error scope before [`ForwardPass::set_pipeline`].
    pub fn build_pipeline(
        &self,
        device: &wgpu::Device,
        shader: &wgpu::ShaderModule,
    ) -> wgpu::RenderPipeline {
        layout::mesh_pipeline(
            device,
            "forward pipeline",
            &self.pipeline_layout,
            shader,
            "fs_main",
            &[],
            self.color_format,
        )
    }

    /// Replaces the pipeline with one from [`ForwardPass::build_pipeline`].
    pub fn set_pipeline(&mut self, pipeline: wgpu::RenderPipeline) {
        self.pipeline = pipeline;
    }

    /// Writes the per-object data that changed since the last frame and makes sure every draw
    /// has a material bind group. Returns the bytes written.
    pub fn prepare(
        &mut self,
        gpu: &GpuContext,
        frame: &FrameUniformBuffer,
        extracted: &ExtractedFrame,
        assets: &GpuAssets,
    ) -> u64 {
        let written = self.upload_objects(gpu, frame, extracted);
        self.materials.prepare(
            gpu,
            assets,
            extracted
                .draws
                .iter()
                .map(|draw| [draw.base_color_texture, draw.normal_map]),
        );
        written
    }

    fn upload_objects(
        &mut self,
        gpu: &GpuContext,
        frame: &FrameUniformBuffer,
        extracted: &ExtractedFrame,
    ) -> u64 {
        let objects: Vec<ObjectUniform> = extracted.draws.iter().map(|draw| draw.object).collect();
        let (written, grew) = self.objects.upload(gpu, &objects);
        if grew {
            self.frame_bind_group =
                frame_bind_group(gpu, &self.frame_layout, frame, self.objects.buffer());
        }
        written
    }

    /// Records one draw per extracted mesh that is on the GPU into the main pass.
    pub fn draw(
        &self,
        pass: &mut wgpu::RenderPass<'_>,
        extracted: &ExtractedFrame,
        assets: &GpuAssets,
    ) {
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, &self.frame_bind_group, &[]);
        for (index, draw) in extracted.draws.iter().enumerate() {
            let (Some(mesh), Some(material)) = (
                assets.mesh(draw.mesh),
                self.materials
                    .get(&[draw.base_color_texture, draw.normal_map]),
            ) else {
                continue;
            };
            pass.set_bind_group(1, material, &[]);
            pass.set_vertex_buffer(0, mesh.vertices.slice(..));
            pass.set_index_buffer(mesh.indices.slice(..), wgpu::IndexFormat::Uint32);
            let instance = index as u32;
            pass.draw_indexed(0..mesh.index_count, 0, instance..instance + 1);
        }
    }
}
