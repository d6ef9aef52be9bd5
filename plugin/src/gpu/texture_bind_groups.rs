//! Bind groups of a material's textures plus a sampler, cached by the images they hold.

use std::collections::HashMap;

use super::assets::{DefaultTexture, GpuAssets};
use super::derived_textures::DerivedTextures;
use super::{GpuContext, layout};
use crate::ImageSampler;
use crate::{AssetId, Image};

/// Most texture slots one material binds: a layered parallax material's four layers' colour
/// and normal maps, their packed heights and their weights.
pub const MAX_MATERIAL_TEXTURES: usize = 10;

/// The image in each texture slot of a draw; `None` binds the slot's default texture.
pub type MaterialTextures = [Option<AssetId<Image>>; MAX_MATERIAL_TEXTURES];

/// What a draw binds at group 1: its images and the textures derived from them.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub(crate) struct BoundTextures {
    pub(crate) images: MaterialTextures,
    pub(crate) derived: DerivedTextures,
}

struct Entry {
    // Upload serial of each slot's image, then of each derived texture, when the group was
    // built (0 = default texture), so a re-uploaded image or a rebuild gets a new group.
    serials: Vec<u64>,
    bind_group: wgpu::BindGroup,
}

/// A layout of N filterable 2D textures (bindings 0..N), a sampler (binding N) and D derived
/// textures read without a sampler (bindings N + 1 ..), and the bind groups built with it. A
/// group samples with the sampler of its first image (trilinear and repeating without one):
/// glTF gives each texture its own, a material binds one.
pub(crate) struct TextureBindGroups {
    label: &'static str,
    layout: wgpu::BindGroupLayout,
    samplers: HashMap<ImageSampler, wgpu::Sampler>,
    defaults: &'static [DefaultTexture],
    derived_slots: usize,
    groups: HashMap<BoundTextures, Entry>,
}

impl std::fmt::Debug for TextureBindGroups {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("TextureBindGroups")
            .field("label", &self.label)
            .field("groups", &self.groups.len())
            .finish()
    }
}

impl TextureBindGroups {
    /// Creates the layout; `defaults` names the texture bound for each slot left empty (at most
    /// [`MAX_MATERIAL_TEXTURES`]), `derived_slots` counts the derived textures
    /// (at most [`super::MAX_DERIVED_TEXTURES`]).
    pub(crate) fn new(
        gpu: &GpuContext,
        label: &'static str,
        defaults: &'static [DefaultTexture],
        derived_slots: usize,
    ) -> Self {
        let n = defaults.len();
        let mut entries: Vec<wgpu::BindGroupLayoutEntry> =
            (0..n as u32).map(layout::texture_2d).collect();
        entries.push(layout::filtering_sampler(n as u32));
        entries.extend(
            (0..derived_slots as u32)
                .map(|slot| layout::unfilterable_texture_2d(n as u32 + 1 + slot)),
        );
        let layout = gpu
            .device
            .create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
                label: Some(label),
                entries: &entries,
            });
        Self {
            label,
            layout,
            samplers: HashMap::new(),
            defaults,
            derived_slots,
            groups: HashMap::new(),
        }
    }

    /// The layout, for pipeline layouts.
    pub(crate) fn layout(&self) -> &wgpu::BindGroupLayout {
        &self.layout
    }

    /// Makes sure every key has an up-to-date bind group, and drops the groups no key uses.
    pub(crate) fn prepare(
        &mut self,
        gpu: &GpuContext,
        assets: &GpuAssets,
        keys: impl IntoIterator<Item = BoundTextures>,
    ) {
        let mut previous = std::mem::take(&mut self.groups);
        for key in keys {
            if self.groups.contains_key(&key) {
                continue;
            }
            let images: Vec<_> = key.images[..self.defaults.len()]
                .iter()
                .map(|id| id.and_then(|id| assets.image(id)))
                .collect();
            let derived: Vec<_> = key.derived[..self.derived_slots]
                .iter()
                .map(|derived| derived.as_ref().and_then(|derived| assets.derived(derived)))
                .collect();
            let serials: Vec<u64> = images
                .iter()
                .map(|image| image.map_or(0, |image| image.upload_serial))
                .chain(
                    derived
                        .iter()
                        .map(|derived| derived.map_or(0, |derived| derived.serial)),
                )
                .collect();
            let entry = match previous.remove(&key) {
                Some(existing) if existing.serials == serials => existing,
                _ => {
                    let settings = images
                        .iter()
                        .flatten()
                        .next()
                        .map_or_else(ImageSampler::default, |image| image.sampler);
                    let sampler = self
                        .samplers
                        .entry(settings)
                        .or_insert_with(|| settings.create(&gpu.device, self.label));
                    let mut entries: Vec<wgpu::BindGroupEntry> = images
                        .iter()
                        .zip(self.defaults.iter().copied())
                        .enumerate()
                        .map(|(slot, (image, default))| wgpu::BindGroupEntry {
                            binding: slot as u32,
                            resource: wgpu::BindingResource::TextureView(
                                image.map_or(assets.defaults.view(default), |image| &image.view),
                            ),
                        })
                        .collect();
                    entries.push(wgpu::BindGroupEntry {
                        binding: self.defaults.len() as u32,
                        resource: wgpu::BindingResource::Sampler(sampler),
                    });
                    entries.extend(derived.iter().enumerate().map(|(slot, derived)| {
                        wgpu::BindGroupEntry {
                            binding: (self.defaults.len() + 1 + slot) as u32,
                            resource: wgpu::BindingResource::TextureView(
                                derived
                                    .map_or(assets.default_derived_view(), |derived| &derived.view),
                            ),
                        }
                    }));
                    Entry {
                        serials,
                        bind_group: gpu.device.create_bind_group(&wgpu::BindGroupDescriptor {
                            label: Some(self.label),
                            layout: &self.layout,
                            entries: &entries,
                        }),
                    }
                }
            };
            self.groups.insert(key, entry);
        }
    }

    /// The bind group prepared for `key`.
    pub(crate) fn get(&self, key: &BoundTextures) -> Option<&wgpu::BindGroup> {
        self.groups.get(key).map(|entry| &entry.bind_group)
    }
}
