//! The forward pass: one pipeline drawing every mesh with the lit, normal-mapped material.

use std::collections::HashMap;

use bytemuck::Zeroable;
use wgpu::util::DeviceExt;

use super::GpuContext;
use super::extract::ExtractedFrame;
use super::gpu_assets::GpuAssets;
use super::gpu_types::{FrameUniform, ObjectUniform, Vertex};
use super::target::{COLOR_FORMAT, DEPTH_FORMAT, RenderTarget};
use crate::{AssetId, Image};

/// The WGSL source of the forward pass.
pub const SHADER_SOURCE: &str = include_str!("forward.wgsl");

type MaterialKey = (Option<AssetId<Image>>, Option<AssetId<Image>>);

struct MaterialBindGroup {
    // Upload serials of the textures it was built from (0 = the default texture).
    serials: (u64, u64),
    bind_group: wgpu::BindGroup,
}

/// Pipeline, buffers and bind groups of the forward pass.
pub struct ForwardPass {
    pipeline: wgpu::RenderPipeline,
    frame_layout: wgpu::BindGroupLayout,
    material_layout: wgpu::BindGroupLayout,
    sampler: wgpu::Sampler,
    white_view: wgpu::TextureView,
    flat_normal_view: wgpu::TextureView,
    frame_buffer: wgpu::Buffer,
    object_buffer: wgpu::Buffer,
    frame_bind_group: wgpu::BindGroup,
    material_bind_groups: HashMap<MaterialKey, MaterialBindGroup>,
    uploaded_frame: Option<FrameUniform>,
    uploaded_objects: Vec<ObjectUniform>,
}

impl std::fmt::Debug for ForwardPass {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("ForwardPass")
            .field("objects", &self.uploaded_objects.len())
            .finish_non_exhaustive()
    }
}

const OBJECT_SIZE: u64 = std::mem::size_of::<ObjectUniform>() as u64;

fn solid_texture(
    gpu: &GpuContext,
    label: &str,
    rgba: [u8; 4],
    format: wgpu::TextureFormat,
) -> wgpu::TextureView {
    gpu.device
        .create_texture_with_data(
            &gpu.queue,
            &wgpu::TextureDescriptor {
                label: Some(label),
                size: wgpu::Extent3d::default(),
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format,
                usage: wgpu::TextureUsages::TEXTURE_BINDING,
                view_formats: &[],
            },
            wgpu::util::TextureDataOrder::LayerMajor,
            &rgba,
        )
        .create_view(&wgpu::TextureViewDescriptor {
            label: Some(&format!("{label} view")),
            ..Default::default()
        })
}

fn object_buffer(gpu: &GpuContext, capacity: u64) -> wgpu::Buffer {
    gpu.device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("forward object buffer"),
        size: capacity.max(1) * OBJECT_SIZE,
        usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    })
}

fn frame_bind_group(
    gpu: &GpuContext,
    layout: &wgpu::BindGroupLayout,
    frame_buffer: &wgpu::Buffer,
    object_buffer: &wgpu::Buffer,
) -> wgpu::BindGroup {
    gpu.device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("forward frame bind group"),
        layout,
        entries: &[
            wgpu::BindGroupEntry {
                binding: 0,
                resource: frame_buffer.as_entire_binding(),
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
    pub fn new(gpu: &GpuContext) -> Self {
        let device = &gpu.device;
        let shader = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("forward.wgsl"),
            source: wgpu::ShaderSource::Wgsl(SHADER_SOURCE.into()),
        });
        let frame_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("forward frame layout"),
            entries: &[
                wgpu::BindGroupLayoutEntry {
                    binding: 0,
                    visibility: wgpu::ShaderStages::VERTEX_FRAGMENT,
                    ty: wgpu::BindingType::Buffer {
                        ty: wgpu::BufferBindingType::Uniform,
                        has_dynamic_offset: false,
                        min_binding_size: wgpu::BufferSize::new(
                            std::mem::size_of::<FrameUniform>() as u64,
                        ),
                    },
                    count: None,
                },
                wgpu::BindGroupLayoutEntry {
                    binding: 1,
                    visibility: wgpu::ShaderStages::VERTEX_FRAGMENT,
                    ty: wgpu::BindingType::Buffer {
                        ty: wgpu::BufferBindingType::Storage { read_only: true },
                        has_dynamic_offset: false,
                        min_binding_size: wgpu::BufferSize::new(OBJECT_SIZE),
                    },
                    count: None,
                },
            ],
        });
        let texture_entry = |binding| wgpu::BindGroupLayoutEntry {
            binding,
            visibility: wgpu::ShaderStages::FRAGMENT,
            ty: wgpu::BindingType::Texture {
                sample_type: wgpu::TextureSampleType::Float { filterable: true },
                view_dimension: wgpu::TextureViewDimension::D2,
                multisampled: false,
            },
            count: None,
        };
        let material_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("forward material layout"),
            entries: &[
                texture_entry(0),
                texture_entry(1),
                wgpu::BindGroupLayoutEntry {
                    binding: 2,
                    visibility: wgpu::ShaderStages::FRAGMENT,
                    ty: wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Filtering),
                    count: None,
                },
            ],
        });
        let layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("forward pipeline layout"),
            bind_group_layouts: &[Some(&frame_layout), Some(&material_layout)],
            immediate_size: 0,
        });
        let pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some("forward pipeline"),
            layout: Some(&layout),
            vertex: wgpu::VertexState {
                module: &shader,
                entry_point: Some("vs_main"),
                compilation_options: Default::default(),
                buffers: &[Some(Vertex::LAYOUT)],
            },
            primitive: wgpu::PrimitiveState {
                cull_mode: Some(wgpu::Face::Back),
                ..Default::default()
            },
            depth_stencil: Some(wgpu::DepthStencilState {
                format: DEPTH_FORMAT,
                depth_write_enabled: Some(true),
                depth_compare: Some(wgpu::CompareFunction::Less),
                stencil: Default::default(),
                bias: Default::default(),
            }),
            multisample: Default::default(),
            fragment: Some(wgpu::FragmentState {
                module: &shader,
                entry_point: Some("fs_main"),
                compilation_options: Default::default(),
                targets: &[Some(COLOR_FORMAT.into())],
            }),
            multiview_mask: None,
            cache: None,
        });
        let sampler = device.create_sampler(&wgpu::SamplerDescriptor {
            label: Some("forward material sampler"),
            address_mode_u: wgpu::AddressMode::Repeat,
            address_mode_v: wgpu::AddressMode::Repeat,
            mag_filter: wgpu::FilterMode::Linear,
            min_filter: wgpu::FilterMode::Linear,
            mipmap_filter: wgpu::MipmapFilterMode::Linear,
            ..Default::default()
        });
        let frame_buffer = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("forward frame uniform"),
            contents: bytemuck::bytes_of(&FrameUniform::zeroed()),
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
        });
        let object_buffer = object_buffer(gpu, 64);
        let frame_bind_group = frame_bind_group(gpu, &frame_layout, &frame_buffer, &object_buffer);
        Self {
            pipeline,
            white_view: solid_texture(
                gpu,
                "default base colour",
                [255; 4],
                wgpu::TextureFormat::Rgba8UnormSrgb,
            ),
            flat_normal_view: solid_texture(
                gpu,
                "default flat normal",
                [128, 128, 255, 255],
                wgpu::TextureFormat::Rgba8Unorm,
            ),
            frame_layout,
            material_layout,
            sampler,
            frame_buffer,
            object_buffer,
            frame_bind_group,
            material_bind_groups: HashMap::new(),
            uploaded_frame: None,
            uploaded_objects: Vec::new(),
        }
    }

    /// Writes the frame uniform and the per-object data that changed since the last frame, and
    /// makes sure every draw has a material bind group. Returns the bytes written.
    pub fn prepare(
        &mut self,
        gpu: &GpuContext,
        extracted: &ExtractedFrame,
        assets: &GpuAssets,
    ) -> u64 {
        let mut written = 0;
        if self.uploaded_frame.as_ref() != Some(&extracted.frame) {
            gpu.queue
                .write_buffer(&self.frame_buffer, 0, bytemuck::bytes_of(&extracted.frame));
            self.uploaded_frame = Some(extracted.frame);
            written += std::mem::size_of::<FrameUniform>() as u64;
        }
        written += self.upload_objects(gpu, extracted);
        self.prepare_material_bind_groups(gpu, extracted, assets);
        written
    }

    fn upload_objects(&mut self, gpu: &GpuContext, extracted: &ExtractedFrame) -> u64 {
        let objects: Vec<ObjectUniform> = extracted.draws.iter().map(|draw| draw.object).collect();
        let capacity = self.object_buffer.size() / OBJECT_SIZE;
        if objects.len() as u64 > capacity {
            let new_capacity = (objects.len() as u64).next_power_of_two();
            self.object_buffer = object_buffer(gpu, new_capacity);
            self.frame_bind_group = frame_bind_group(
                gpu,
                &self.frame_layout,
                &self.frame_buffer,
                &self.object_buffer,
            );
            // The new buffer holds nothing yet.
            self.uploaded_objects.clear();
        }
        // Write each run of consecutive changed objects with one call.
        let mut written = 0;
        let mut index = 0;
        while index < objects.len() {
            if self.uploaded_objects.get(index) == Some(&objects[index]) {
                index += 1;
                continue;
            }
            let start = index;
            while index < objects.len() && self.uploaded_objects.get(index) != Some(&objects[index])
            {
                index += 1;
            }
            let bytes: &[u8] = bytemuck::cast_slice(&objects[start..index]);
            gpu.queue
                .write_buffer(&self.object_buffer, start as u64 * OBJECT_SIZE, bytes);
            written += bytes.len() as u64;
        }
        self.uploaded_objects = objects;
        written
    }

    fn prepare_material_bind_groups(
        &mut self,
        gpu: &GpuContext,
        extracted: &ExtractedFrame,
        assets: &GpuAssets,
    ) {
        let mut previous = std::mem::take(&mut self.material_bind_groups);
        for draw in &extracted.draws {
            let key = (draw.base_color_texture, draw.normal_map);
            if self.material_bind_groups.contains_key(&key) {
                continue;
            }
            let base = key.0.and_then(|id| assets.image(id));
            let normal = key.1.and_then(|id| assets.image(id));
            let serials = (
                base.map_or(0, |image| image.upload_serial),
                normal.map_or(0, |image| image.upload_serial),
            );
            let entry = match previous.remove(&key) {
                Some(existing) if existing.serials == serials => existing,
                _ => MaterialBindGroup {
                    serials,
                    bind_group: gpu.device.create_bind_group(&wgpu::BindGroupDescriptor {
                        label: Some("forward material bind group"),
                        layout: &self.material_layout,
                        entries: &[
                            wgpu::BindGroupEntry {
                                binding: 0,
                                resource: wgpu::BindingResource::TextureView(
                                    base.map_or(&self.white_view, |image| &image.view),
                                ),
                            },
                            wgpu::BindGroupEntry {
                                binding: 1,
                                resource: wgpu::BindingResource::TextureView(
                                    normal.map_or(&self.flat_normal_view, |image| &image.view),
                                ),
                            },
                            wgpu::BindGroupEntry {
                                binding: 2,
                                resource: wgpu::BindingResource::Sampler(&self.sampler),
                            },
                        ],
                    }),
                },
            };
            self.material_bind_groups.insert(key, entry);
        }
    }

    /// Records the pass: clear, then one draw per extracted mesh that is on the GPU.
    pub fn draw(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        target: &RenderTarget,
        extracted: &ExtractedFrame,
        assets: &GpuAssets,
    ) {
        let clear = extracted.clear_color;
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("forward pass"),
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view: &target.color_view,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations {
                    load: wgpu::LoadOp::Clear(wgpu::Color {
                        r: f64::from(clear.r),
                        g: f64::from(clear.g),
                        b: f64::from(clear.b),
                        a: f64::from(clear.a),
                    }),
                    store: wgpu::StoreOp::Store,
                },
            })],
            depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                view: &target.depth_view,
                depth_ops: Some(wgpu::Operations {
                    load: wgpu::LoadOp::Clear(1.0),
                    store: wgpu::StoreOp::Discard,
                }),
                stencil_ops: None,
            }),
            timestamp_writes: None,
            occlusion_query_set: None,
            multiview_mask: None,
        });
        if !extracted.has_camera {
            return;
        }
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, &self.frame_bind_group, &[]);
        for (index, draw) in extracted.draws.iter().enumerate() {
            let (Some(mesh), Some(material)) = (
                assets.mesh(draw.mesh),
                self.material_bind_groups
                    .get(&(draw.base_color_texture, draw.normal_map)),
            ) else {
                continue;
            };
            pass.set_bind_group(1, &material.bind_group, &[]);
            pass.set_vertex_buffer(0, mesh.vertices.slice(..));
            pass.set_index_buffer(mesh.indices.slice(..), wgpu::IndexFormat::Uint32);
            let instance = index as u32;
            pass.draw_indexed(0..mesh.index_count, 0, instance..instance + 1);
        }
    }
}
