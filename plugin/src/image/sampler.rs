//! How a texture is sampled: wrap and filter modes, as glTF samplers give them.

use serde::{Deserialize, Serialize};

/// What happens outside 0..1 along one texture axis.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum WrapMode {
    /// Tiles (glTF's default).
    #[default]
    Repeat,
    /// Tiles, every other copy mirrored.
    MirroredRepeat,
    /// Holds the edge texel.
    ClampToEdge,
}

/// How texels are blended.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum FilterMode {
    /// The nearest texel (or mip level): hard pixel edges.
    Nearest,
    /// Linear blending.
    #[default]
    Linear,
}

/// An image's sampler. The default is trilinear and repeating, what a material expects.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub struct ImageSampler {
    /// Along u.
    pub wrap_u: WrapMode,
    /// Along v.
    pub wrap_v: WrapMode,
    /// When a texel covers more than a pixel.
    pub mag_filter: FilterMode,
    /// When a pixel covers more than a texel.
    pub min_filter: FilterMode,
    /// Between mip levels.
    pub mipmap_filter: FilterMode,
}

impl WrapMode {
    fn address_mode(self) -> wgpu::AddressMode {
        match self {
            WrapMode::Repeat => wgpu::AddressMode::Repeat,
            WrapMode::MirroredRepeat => wgpu::AddressMode::MirrorRepeat,
            WrapMode::ClampToEdge => wgpu::AddressMode::ClampToEdge,
        }
    }
}

impl FilterMode {
    fn filter(self) -> wgpu::FilterMode {
        match self {
            FilterMode::Nearest => wgpu::FilterMode::Nearest,
            FilterMode::Linear => wgpu::FilterMode::Linear,
        }
    }

    fn mipmap_filter(self) -> wgpu::MipmapFilterMode {
        match self {
            FilterMode::Nearest => wgpu::MipmapFilterMode::Nearest,
            FilterMode::Linear => wgpu::MipmapFilterMode::Linear,
        }
    }
}

impl ImageSampler {
    /// A wgpu sampler with these settings.
    pub(crate) fn create(&self, device: &wgpu::Device, label: &str) -> wgpu::Sampler {
        device.create_sampler(&wgpu::SamplerDescriptor {
            label: Some(label),
            address_mode_u: self.wrap_u.address_mode(),
            address_mode_v: self.wrap_v.address_mode(),
            mag_filter: self.mag_filter.filter(),
            min_filter: self.min_filter.filter(),
            mipmap_filter: self.mipmap_filter.mipmap_filter(),
            ..Default::default()
        })
    }
}
