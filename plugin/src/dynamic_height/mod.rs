//! Dynamic height fields (Tatarchuk 2006 §5.5): heights that change every frame, with normals
//! re-derived on the GPU by a Sobel compute pass, never read back to the CPU.

use std::collections::HashMap;

use bytemuck::{Pod, Zeroable};
use hecs::{Entity, World};
use wgpu::util::DeviceExt;

use crate::gpu::{GpuContext, PassTimestamps, layout, time_pass};
use crate::render::{Renderer, shaders};
use crate::{AppError, Assets, Handle, HeightField, Image, ImageError, Resources, TextureKind};

/// A height field that changes while the game runs. User code rewrites the `height` image (through
/// `Assets<Image>::get_mut`, which re-uploads it), and every frame the plugin derives `normal`
/// from it on the GPU. Put it next to a [`crate::ParallaxOcclusionMaterial`] whose height map is
/// `height` and whose normal map is `normal`.
#[derive(Clone, Debug, PartialEq)]
pub struct DynamicHeightField {
    /// The heights (one channel, 8 or 16 bits).
    pub height: Handle<Image>,
    /// The normal map the Sobel pass writes, made with [`Image::gpu_written`].
    pub normal: Handle<Image>,
    /// Height of 1.0 in texture-coordinate units, for the slopes (the material's height scale).
    pub height_scale: f32,
}

impl DynamicHeightField {
    /// Adds the initial heights and a flat normal map to `images`.
    pub fn new(
        images: &mut Assets<Image>,
        initial: &HeightField,
        height_scale: f32,
    ) -> Result<Self, ImageError> {
        let (width, height) = initial.size();
        Ok(Self {
            height: images.add(initial.to_image_16()),
            normal: images.add(Image::gpu_written(
                width,
                height,
                TextureKind::Normal,
                [128, 128, 255, 255],
            )?),
            height_scale,
        })
    }
}

#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
struct SobelParams {
    size: [u32; 2],
    height_scale: f32,
    padding: f32,
}

impl SobelParams {
    /// The parameters of a field of `size`; a height scale that is not a finite number ≥ 0
    /// derives flat normals (0).
    fn new(size: [u32; 2], height_scale: f32) -> Self {
        Self {
            size,
            height_scale: if height_scale.is_finite() {
                height_scale.max(0.0)
            } else {
                0.0
            },
            padding: 0.0,
        }
    }
}

struct SobelBinding {
    // Upload serials of the height and normal textures the group was made for.
    serials: (u64, u64),
    params: wgpu::Buffer,
    bind_group: wgpu::BindGroup,
}

/// The Sobel compute pipeline and one bind group per dynamic field. A resource.
pub struct SobelPass {
    pipeline: wgpu::ComputePipeline,
    layout: wgpu::BindGroupLayout,
    bindings: HashMap<Entity, SobelBinding>,
}

impl std::fmt::Debug for SobelPass {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("SobelPass")
            .field("fields", &self.bindings.len())
            .finish()
    }
}

impl SobelPass {
    /// Compiles the compute shader.
    pub fn new(gpu: &GpuContext) -> Self {
        let device = &gpu.device;
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("sobel layout"),
            entries: &[
                layout::unfilterable_texture_2d(0),
                layout::compute_storage_texture(1, wgpu::TextureFormat::Rgba8Unorm),
                layout::compute_uniform_buffer(2, false),
            ],
        });
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("sobel pipeline layout"),
            bind_group_layouts: &[Some(&layout)],
            immediate_size: 0,
        });
        let module = shaders::SOBEL.create_module(device);
        let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some("sobel pipeline"),
            layout: Some(&pipeline_layout),
            module: &module,
            entry_point: Some("derive_normals"),
            compilation_options: Default::default(),
            cache: None,
        });
        Self {
            pipeline,
            layout,
            bindings: HashMap::new(),
        }
    }

    /// A bind group reading level 0 of `height` and writing `normal`, with a parameter buffer
    /// holding `params`; `serials` are the uploads it is made for.
    fn create_binding(
        &self,
        gpu: &GpuContext,
        serials: (u64, u64),
        params: &SobelParams,
        height: &wgpu::Texture,
        normal: &wgpu::TextureView,
    ) -> SobelBinding {
        let params_buffer = gpu
            .device
            .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("sobel parameters"),
                contents: bytemuck::bytes_of(params),
                usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            });
        let height_view = height.create_view(&wgpu::TextureViewDescriptor {
            label: Some("sobel height level 0"),
            base_mip_level: 0,
            mip_level_count: Some(1),
            ..Default::default()
        });
        let bind_group = gpu.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("sobel bind group"),
            layout: &self.layout,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: wgpu::BindingResource::TextureView(&height_view),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: wgpu::BindingResource::TextureView(normal),
                },
                wgpu::BindGroupEntry {
                    binding: 2,
                    resource: params_buffer.as_entire_binding(),
                },
            ],
        });
        SobelBinding {
            serials,
            params: params_buffer,
            bind_group,
        }
    }

    /// Records the compute pass over a `width` × `rows` field, 8 × 8 texels a workgroup.
    fn record(&self, target: DispatchTarget<'_>, binding: &SobelBinding, width: u32, rows: u32) {
        let mut compute = target
            .encoder
            .begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some("sobel pass"),
                timestamp_writes: target.timestamps.map(PassTimestamps::compute),
            });
        compute.set_pipeline(&self.pipeline);
        compute.set_bind_group(0, &binding.bind_group, &[]);
        compute.dispatch_workgroups(width.div_ceil(8), rows.div_ceil(8), 1);
    }
}

/// Why a dynamic field could not be processed this frame.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum DynamicHeightError {
    /// The normal image was not made with [`Image::gpu_written`], or its size differs.
    #[error("dynamic height field of {entity:?}: {problem}")]
    Mismatch {
        /// The entity.
        entity: Entity,
        /// What does not fit.
        problem: String,
    },
}

impl DynamicHeightError {
    /// A [`DynamicHeightError::Mismatch`] of `entity`'s field.
    fn mismatch(entity: Entity, problem: &str) -> Self {
        Self::Mismatch {
            entity,
            problem: problem.to_owned(),
        }
    }
}

/// The Prepare stage's system that re-derives every dynamic field's normals on the GPU.
/// A field whose images do not fit together is logged once per frame and skipped.
pub fn derive_dynamic_normals(
    world: &mut World,
    resources: &mut Resources,
) -> Result<(), AppError> {
    resources.require_scope(|resources, pass: &mut SobelPass| {
        resources.require_scope(|resources, renderer: &mut Renderer| {
            run(world, resources, pass, renderer)
        })
    })
}

fn run(
    world: &World,
    resources: &mut Resources,
    pass: &mut SobelPass,
    renderer: &mut Renderer,
) -> Result<(), AppError> {
    let timestamps: Vec<Option<PassTimestamps>> = world
        .query::<&DynamicHeightField>()
        .iter()
        .map(|_| time_pass(resources, "sobel pass"))
        .collect();
    {
        let gpu = resources.require::<GpuContext>()?;
        let images = resources.require::<Assets<Image>>()?;
        let fields: Vec<(Entity, DynamicHeightField)> = world
            .query::<(Entity, &DynamicHeightField)>()
            .iter()
            .map(|(entity, field)| (entity, field.clone()))
            .collect();
        pass.bindings
            .retain(|entity, _| fields.iter().any(|(e, _)| e == entity));
        if fields.is_empty() {
            return Ok(());
        }
        let mut encoder = gpu
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("sobel encoder"),
            });
        for ((entity, field), timestamps) in fields.iter().zip(&timestamps) {
            renderer
                .assets
                .prepare_image(gpu, images, field.height.id());
            renderer
                .assets
                .prepare_image(gpu, images, field.normal.id());
            let target = DispatchTarget {
                encoder: &mut encoder,
                timestamps: timestamps.as_ref(),
            };
            if let Err(error) = dispatch(gpu, images, renderer, pass, target, *entity, field) {
                log::error!("{error}");
            }
        }
        gpu.queue.submit([encoder.finish()]);
        Ok(())
    }
}

// Where one field's Sobel pass is recorded, and its timestamp pair if timing is on.
struct DispatchTarget<'a> {
    encoder: &'a mut wgpu::CommandEncoder,
    timestamps: Option<&'a PassTimestamps>,
}

/// Records `field`'s Sobel pass on `target`, making its bind group where its textures are new.
fn dispatch(
    gpu: &GpuContext,
    images: &Assets<Image>,
    renderer: &Renderer,
    pass: &mut SobelPass,
    target: DispatchTarget<'_>,
    entity: Entity,
    field: &DynamicHeightField,
) -> Result<(), DynamicHeightError> {
    let (width, rows) = checked_size(images, entity, field)?;
    let (Some(height), Some(normal)) = (
        renderer.assets.image(field.height.id()),
        renderer.assets.image(field.normal.id()),
    ) else {
        return Err(DynamicHeightError::mismatch(
            entity,
            "its images are not on the GPU",
        ));
    };
    let params = SobelParams::new([width, rows], field.height_scale);
    let serials = (height.upload_serial, normal.upload_serial);
    let binding = match pass.bindings.remove(&entity) {
        Some(binding) if binding.serials == serials => binding,
        _ => pass.create_binding(gpu, serials, &params, &height.texture, &normal.view),
    };
    gpu.write_buffer(&binding.params, 0, bytemuck::bytes_of(&params));
    pass.record(target, &binding, width, rows);
    pass.bindings.insert(entity, binding);
    Ok(())
}

/// The size of `field`, whose images must exist and fit together: a normal image made with
/// [`Image::gpu_written`], of the height image's size.
fn checked_size(
    images: &Assets<Image>,
    entity: Entity,
    field: &DynamicHeightField,
) -> Result<(u32, u32), DynamicHeightError> {
    let mismatch = |problem| DynamicHeightError::mismatch(entity, problem);
    let (Some(height_image), Some(normal_image)) =
        (images.get(&field.height), images.get(&field.normal))
    else {
        return Err(mismatch("its images are gone"));
    };
    if !normal_image.is_gpu_written() {
        return Err(mismatch(
            "the normal image was not made with Image::gpu_written",
        ));
    }
    if height_image.size() != normal_image.size() {
        return Err(mismatch("the height and normal images differ in size"));
    }
    Ok(height_image.size())
}
