//! The environment light's maps in every material's group 0 (bindings 10 to 13, read through
//! `environment/environment.wgsl`), which the environment feature fills; until it does,
//! 1-texel stand-ins are bound and `frame.environment.y` is 0 (the ambient term lights). Like
//! the shadow maps, the slots belong to the frame so that every material can read them.

use crate::gpu::GpuContext;

/// The format of the radiance cube and the split-sum table.
pub const ENVIRONMENT_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba16Float;

/// Bytes of the irradiance's nine spherical-harmonic coefficients, a `vec4` each.
pub const IRRADIANCE_BYTES: u64 = 9 * 16;

/// What the environment feature hands the frame's bindings.
#[derive(Debug, Clone)]
pub struct EnvironmentTextures {
    /// The radiance cube, mip `m` blurred by GGX of perceptual roughness `m / (mips − 1)`.
    pub radiance: wgpu::TextureView,
    /// The split-sum table: at (N·V, roughness), the scale (x) and bias (y) of F0.
    pub split_sum: wgpu::TextureView,
    /// Irradiance / π as nine spherical harmonics (a uniform of [`IRRADIANCE_BYTES`]).
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

impl EnvironmentMaps {
    /// No environment yet: the stand-ins are bound.
    pub fn new(gpu: &GpuContext) -> Self {
        // One black texel on six layers: a cube to one binding, a 2D texture to the other.
        let texture = gpu.device.create_texture(&wgpu::TextureDescriptor {
            label: Some("environment stand-in"),
            size: wgpu::Extent3d {
                width: 1,
                height: 1,
                depth_or_array_layers: 6,
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: ENVIRONMENT_FORMAT,
            usage: wgpu::TextureUsages::TEXTURE_BINDING,
            view_formats: &[],
        });
        let view = |dimension| {
            texture.create_view(&wgpu::TextureViewDescriptor {
                dimension: Some(dimension),
                array_layer_count: Some(if dimension == wgpu::TextureViewDimension::Cube {
                    6
                } else {
                    1
                }),
                ..Default::default()
            })
        };
        Self {
            installed: None,
            stand_in: EnvironmentTextures {
                radiance: view(wgpu::TextureViewDimension::Cube),
                split_sum: view(wgpu::TextureViewDimension::D2),
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
        let texture = |view_dimension| wgpu::BindingType::Texture {
            sample_type: wgpu::TextureSampleType::Float { filterable: true },
            view_dimension,
            multisampled: false,
        };
        let irradiance = wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Uniform,
            has_dynamic_offset: false,
            min_binding_size: wgpu::BufferSize::new(IRRADIANCE_BYTES),
        };
        let types = [
            texture(wgpu::TextureViewDimension::Cube),
            texture(wgpu::TextureViewDimension::D2),
            irradiance,
            wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Filtering),
        ];
        std::array::from_fn(|i| wgpu::BindGroupLayoutEntry {
            binding: BINDINGS[i],
            visibility: wgpu::ShaderStages::FRAGMENT.union(wgpu::ShaderStages::COMPUTE),
            ty: types[i],
            count: None,
        })
    }

    /// The bind group entries of bindings 10 to 13.
    pub fn entries(&self) -> [wgpu::BindGroupEntry<'_>; 4] {
        let bound = self.bound();
        let [radiance, split_sum, irradiance, sampler] = BINDINGS;
        let entry = |binding, resource| wgpu::BindGroupEntry { binding, resource };
        [
            entry(
                radiance,
                wgpu::BindingResource::TextureView(&bound.radiance),
            ),
            entry(
                split_sum,
                wgpu::BindingResource::TextureView(&bound.split_sum),
            ),
            entry(irradiance, bound.irradiance.as_entire_binding()),
            entry(sampler, wgpu::BindingResource::Sampler(&self.sampler)),
        ]
    }
}

/// The bindings of the radiance cube, the split-sum table, the irradiance and the sampler.
const BINDINGS: [u32; 4] = [
    super::frame_group::ENVIRONMENT_RADIANCE,
    super::frame_group::ENVIRONMENT_SPLIT_SUM,
    super::frame_group::ENVIRONMENT_IRRADIANCE,
    super::frame_group::ENVIRONMENT_SAMPLER,
];
