//! The environment's textures on the GPU: the source image with its mips, and the two cubes of
//! one size the prefiltering writes (the captured source with its full mip chain, and the
//! radiance cube materials read), with views of one mip to write and the whole cube to sample.

use wgpu::util::DeviceExt;

use crate::gpu::GpuContext;
use crate::render::{ENVIRONMENT_FORMAT, EnvironmentTextures, IRRADIANCE_BYTES};

use super::prefilter::radiance_levels;

/// The cube textures of one size and what materials read of them.
pub(crate) struct Cubes {
    pub(crate) size: u32,
    /// The captured source with its full mip chain.
    pub(crate) source: wgpu::Texture,
    pub(crate) radiance: wgpu::Texture,
    pub(crate) textures: EnvironmentTextures,
}

impl Cubes {
    /// Cubes of `size` texels a side, with `split_sum` the table materials read beside them.
    pub(crate) fn new(gpu: &GpuContext, size: u32, split_sum: &wgpu::TextureView) -> Self {
        let source = cube_texture(gpu, "environment source cube", size, size.ilog2() + 1);
        let radiance = cube_texture(
            gpu,
            "environment radiance cube",
            size,
            radiance_levels(size),
        );
        let irradiance = gpu.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("environment irradiance"),
            size: IRRADIANCE_BYTES,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::STORAGE,
            mapped_at_creation: false,
        });
        let textures = EnvironmentTextures {
            radiance: cube_view(&radiance),
            split_sum: split_sum.clone(),
            irradiance,
        };
        Cubes {
            size,
            source,
            radiance,
            textures,
        }
    }
}

/// An RGBA half-float image texture with `levels` (width, height, texels), mip 0 first.
pub(crate) fn image_texture(
    gpu: &GpuContext,
    label: &str,
    levels: &[(u32, u32, Vec<half::f16>)],
) -> wgpu::Texture {
    let (width, height, _) = levels[0];
    let data: Vec<u16> = levels
        .iter()
        .flat_map(|(_, _, texels)| texels.iter().map(|value| value.to_bits()))
        .collect();
    gpu.device.create_texture_with_data(
        &gpu.queue,
        &wgpu::TextureDescriptor {
            label: Some(label),
            size: wgpu::Extent3d {
                width,
                height,
                depth_or_array_layers: 1,
            },
            mip_level_count: levels.len() as u32,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: ENVIRONMENT_FORMAT,
            usage: wgpu::TextureUsages::TEXTURE_BINDING,
            view_formats: &[],
        },
        wgpu::util::TextureDataOrder::MipMajor,
        bytemuck::cast_slice(&data),
    )
}

pub(crate) fn cube_texture(gpu: &GpuContext, label: &str, size: u32, levels: u32) -> wgpu::Texture {
    gpu.device.create_texture(&wgpu::TextureDescriptor {
        label: Some(label),
        size: wgpu::Extent3d {
            width: size,
            height: size,
            depth_or_array_layers: 6,
        },
        mip_level_count: levels,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format: ENVIRONMENT_FORMAT,
        usage: wgpu::TextureUsages::TEXTURE_BINDING
            | wgpu::TextureUsages::STORAGE_BINDING
            | wgpu::TextureUsages::COPY_SRC
            | wgpu::TextureUsages::COPY_DST,
        view_formats: &[],
    })
}

/// One mip of a cube as a 2D array (to write, or to load from).
pub(crate) fn level_view(texture: &wgpu::Texture, level: u32) -> wgpu::TextureView {
    texture.create_view(&wgpu::TextureViewDescriptor {
        dimension: Some(wgpu::TextureViewDimension::D2Array),
        base_mip_level: level,
        mip_level_count: Some(1),
        ..Default::default()
    })
}

pub(crate) fn cube_view(texture: &wgpu::Texture) -> wgpu::TextureView {
    texture.create_view(&wgpu::TextureViewDescriptor {
        dimension: Some(wgpu::TextureViewDimension::Cube),
        ..Default::default()
    })
}
