//! The environment light's maps as every material's group 0 binds them (bindings
//! [`frame_group::ENVIRONMENT_RADIANCE`](super::frame_group::ENVIRONMENT_RADIANCE) to
//! [`frame_group::ENVIRONMENT_SAMPLER`](super::frame_group::ENVIRONMENT_SAMPLER), read through
//! `environment.wgsl`): the prefiltered radiance cube, the split-sum table and the irradiance's
//! spherical harmonics. The environment feature (`render/environment/`) makes them; until it
//! installs some, 1-texel stand-ins are bound and the frame uniform's `environment.y` is 0, so
//! materials light with the ambient term alone. Like the shadow maps, the slots belong to the
//! frame's bindings so that every material reads them whether or not the feature is in the app.

use crate::gpu::GpuContext;

/// The format of the radiance cube and the split-sum table.
pub const ENVIRONMENT_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba16Float;

/// Bytes of the irradiance's nine spherical-harmonic coefficients, a `vec4` each
/// (`EnvironmentIrradiance` in environment.wgsl).
pub const IRRADIANCE_BYTES: u64 = 9 * 16;

/// What the environment feature hands the frame's bindings.
#[derive(Debug, Clone)]
pub struct EnvironmentTextures {
    /// The radiance cube: mip 0 the environment itself, mip `m` blurred by a GGX lobe of
    /// perceptual roughness `m / (mips − 1)`.
    pub radiance: wgpu::TextureView,
    /// The split-sum table: at (N·V, roughness), the scale (x) and bias (y) of F0.
    pub split_sum: wgpu::TextureView,
    /// A uniform buffer of [`IRRADIANCE_BYTES`]: irradiance / π as nine spherical-harmonic
    /// coefficients (rgb in each `vec4`), the cosine lobe's convolution folded in.
    pub irradiance: wgpu::Buffer,
}

/// The environment maps group 0 binds. Part of the renderer.
#[derive(Debug)]
pub struct EnvironmentMaps {
    installed: Option<EnvironmentTextures>,
    stand_in: EnvironmentTextures,
    sampler: wgpu::Sampler,
    /// Changes whenever the bound maps change (bind groups holding them must follow).
    generation: u64,
}

fn stand_in_texture(gpu: &GpuContext, layers: u32, label: &str) -> wgpu::Texture {
    gpu.device.create_texture(&wgpu::TextureDescriptor {
        label: Some(label),
        size: wgpu::Extent3d {
            width: 1,
            height: 1,
            depth_or_array_layers: layers,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format: ENVIRONMENT_FORMAT,
        usage: wgpu::TextureUsages::TEXTURE_BINDING,
        view_formats: &[],
    })
}

impl EnvironmentMaps {
    /// No environment yet: the stand-ins are bound.
    pub fn new(gpu: &GpuContext) -> Self {
        let cube = stand_in_texture(gpu, 6, "environment radiance stand-in");
        let table = stand_in_texture(gpu, 1, "environment split-sum stand-in");
        Self {
            installed: None,
            stand_in: EnvironmentTextures {
                radiance: cube.create_view(&wgpu::TextureViewDescriptor {
                    dimension: Some(wgpu::TextureViewDimension::Cube),
                    ..Default::default()
                }),
                split_sum: table.create_view(&Default::default()),
                irradiance: gpu.device.create_buffer(&wgpu::BufferDescriptor {
                    label: Some("environment irradiance stand-in"),
                    size: IRRADIANCE_BYTES,
                    usage: wgpu::BufferUsages::UNIFORM,
                    mapped_at_creation: false,
                }),
            },
            sampler: gpu.device.create_sampler(&wgpu::SamplerDescriptor {
                label: Some("environment sampler"),
                mag_filter: wgpu::FilterMode::Linear,
                min_filter: wgpu::FilterMode::Linear,
                mipmap_filter: wgpu::MipmapFilterMode::Linear,
                ..Default::default()
            }),
            generation: 0,
        }
    }

    /// Binds `textures` from the next frame on (`None`: the stand-ins again).
    pub fn install(&mut self, textures: Option<EnvironmentTextures>) {
        self.installed = textures;
        self.generation += 1;
    }

    /// Whether the environment feature's maps are bound (else the stand-ins).
    pub fn is_installed(&self) -> bool {
        self.installed.is_some()
    }

    /// What group 0 binds now.
    pub fn bound(&self) -> &EnvironmentTextures {
        self.installed.as_ref().unwrap_or(&self.stand_in)
    }

    /// The trilinear, edge-clamped sampler the maps are read with.
    pub fn sampler(&self) -> &wgpu::Sampler {
        &self.sampler
    }

    /// Changes whenever the bound maps change.
    pub fn generation(&self) -> u64 {
        self.generation
    }

    /// The layout entries of bindings 10 to 13 of group 0.
    pub fn layout_entries() -> [wgpu::BindGroupLayoutEntry; 4] {
        use super::frame_group::{
            ENVIRONMENT_IRRADIANCE, ENVIRONMENT_RADIANCE, ENVIRONMENT_SAMPLER,
            ENVIRONMENT_SPLIT_SUM,
        };
        let visibility = wgpu::ShaderStages::FRAGMENT.union(wgpu::ShaderStages::COMPUTE);
        let texture = |binding, view_dimension| wgpu::BindGroupLayoutEntry {
            binding,
            visibility,
            ty: wgpu::BindingType::Texture {
                sample_type: wgpu::TextureSampleType::Float { filterable: true },
                view_dimension,
                multisampled: false,
            },
            count: None,
        };
        [
            texture(ENVIRONMENT_RADIANCE, wgpu::TextureViewDimension::Cube),
            texture(ENVIRONMENT_SPLIT_SUM, wgpu::TextureViewDimension::D2),
            wgpu::BindGroupLayoutEntry {
                binding: ENVIRONMENT_IRRADIANCE,
                visibility,
                ty: wgpu::BindingType::Buffer {
                    ty: wgpu::BufferBindingType::Uniform,
                    has_dynamic_offset: false,
                    min_binding_size: wgpu::BufferSize::new(IRRADIANCE_BYTES),
                },
                count: None,
            },
            wgpu::BindGroupLayoutEntry {
                binding: ENVIRONMENT_SAMPLER,
                visibility,
                ty: wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Filtering),
                count: None,
            },
        ]
    }

    /// The bind group entries of bindings 10 to 13.
    pub fn entries(&self) -> [wgpu::BindGroupEntry<'_>; 4] {
        use super::frame_group::{
            ENVIRONMENT_IRRADIANCE, ENVIRONMENT_RADIANCE, ENVIRONMENT_SAMPLER,
            ENVIRONMENT_SPLIT_SUM,
        };
        let bound = self.bound();
        let entry = |binding, resource| wgpu::BindGroupEntry { binding, resource };
        [
            entry(
                ENVIRONMENT_RADIANCE,
                wgpu::BindingResource::TextureView(&bound.radiance),
            ),
            entry(
                ENVIRONMENT_SPLIT_SUM,
                wgpu::BindingResource::TextureView(&bound.split_sum),
            ),
            entry(ENVIRONMENT_IRRADIANCE, bound.irradiance.as_entire_binding()),
            entry(
                ENVIRONMENT_SAMPLER,
                wgpu::BindingResource::Sampler(&self.sampler),
            ),
        ]
    }
}
