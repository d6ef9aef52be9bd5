//! The parallax material's pipelines, buffers and bind groups inside the main pass.

use super::extract::ExtractedPom;
use super::gpu::PomObject;
use super::pipelines::PomPipelines;
use crate::render::{
    DefaultTexture, FrameUniformBuffer, GpuAssets, GpuContext, ObjectBuffer, TextureBindGroups,
    shaders,
};

/// The specialized pipelines, the per-draw buffer and the texture bind groups.
#[derive(Debug)]
pub struct PomPass {
    pipelines: PomPipelines,
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

impl PomPass {
    /// Compiles `pom.wgsl` for targets of `color_format`; pipelines follow on first use.
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
        let objects = ObjectBuffer::new(gpu, "parallax object buffer", 16);
        let frame_bind_group = frame_bind_group(gpu, &frame_layout, frame, objects.buffer());
        Self {
            pipelines: PomPipelines::new(shader, layout, color_format),
            frame_layout,
            objects,
            frame_bind_group,
            materials,
        }
    }

    /// The pipelines in use rebuilt from `shader` (a recompiled `pom.wgsl`), for shader hot
    /// reload: check them in an error scope before [`PomPass::set_pipelines`].
    pub fn build_pipelines(
        &self,
        device: &wgpu::Device,
        shader: wgpu::ShaderModule,
    ) -> PomPipelines {
        self.pipelines.rebuilt(device, shader)
    }

    /// Replaces the pipelines with those from [`PomPass::build_pipelines`].
    pub fn set_pipelines(&mut self, pipelines: PomPipelines) {
        self.pipelines = pipelines;
    }

    /// Uploads the per-draw data that changed, prepares texture bind groups and compiles the
    /// pipelines of modes seen for the first time. Returns the bytes written.
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
        for draw in &extracted.draws {
            self.pipelines.ensure(&gpu.device, draw.pipeline);
        }
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
        let mut bound = None;
        for (index, draw) in extracted.draws.iter().enumerate() {
            let (Some(mesh), Some(material), Some(pipeline)) = (
                assets.mesh(draw.mesh),
                self.materials.get(&draw.textures),
                self.pipelines.get(&draw.pipeline),
            ) else {
                continue;
            };
            // Draws come sorted by pipeline: switch only where the key changes.
            if bound != Some(draw.pipeline) {
                pass.set_pipeline(pipeline);
                bound = Some(draw.pipeline);
            }
            pass.set_bind_group(1, material, &[]);
            pass.set_vertex_buffer(0, mesh.vertices.slice(..));
            pass.set_index_buffer(mesh.indices.slice(..), wgpu::IndexFormat::Uint32);
            let instance = index as u32;
            pass.draw_indexed(0..mesh.index_count, 0, instance..instance + 1);
        }
    }
}
