//! Bind groups of N material textures plus a sampler, cached by the images they hold.

use std::collections::HashMap;

use super::gpu_assets::{DefaultTexture, GpuAssets};
use super::{GpuContext, layout};
use crate::{AssetId, Image};

/// Which image goes in each texture slot; `None` binds the slot's default texture.
pub type TextureKey<const N: usize> = [Option<AssetId<Image>>; N];

struct Entry {
    // Upload serial of each slot's image when the group was built (0 = default texture), so a
    // re-uploaded image gets a new group.
    serials: Vec<u64>,
    bind_group: wgpu::BindGroup,
}

/// A layout of N filterable 2D textures (bindings 0..N) and a trilinear repeating sampler
/// (binding N), and the bind groups built with it.
pub struct TextureBindGroups<const N: usize> {
    label: &'static str,
    layout: wgpu::BindGroupLayout,
    sampler: wgpu::Sampler,
    defaults: [DefaultTexture; N],
    groups: HashMap<TextureKey<N>, Entry>,
}

impl<const N: usize> std::fmt::Debug for TextureBindGroups<N> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("TextureBindGroups")
            .field("label", &self.label)
            .field("groups", &self.groups.len())
            .finish()
    }
}

impl<const N: usize> TextureBindGroups<N> {
    /// Creates the layout; `defaults` names the texture bound for each slot left empty.
    pub fn new(gpu: &GpuContext, label: &'static str, defaults: [DefaultTexture; N]) -> Self {
        let mut entries: Vec<wgpu::BindGroupLayoutEntry> =
            (0..N as u32).map(layout::texture_2d).collect();
        entries.push(layout::filtering_sampler(N as u32));
        let layout = gpu
            .device
            .create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
                label: Some(label),
                entries: &entries,
            });
        Self {
            label,
            layout,
            sampler: layout::material_sampler(&gpu.device, label),
            defaults,
            groups: HashMap::new(),
        }
    }

    /// The layout, for pipeline layouts.
    pub fn layout(&self) -> &wgpu::BindGroupLayout {
        &self.layout
    }

    /// Makes sure every key has an up-to-date bind group, and drops the groups no key uses.
    pub fn prepare(
        &mut self,
        gpu: &GpuContext,
        assets: &GpuAssets,
        keys: impl IntoIterator<Item = TextureKey<N>>,
    ) {
        let mut previous = std::mem::take(&mut self.groups);
        for key in keys {
            if self.groups.contains_key(&key) {
                continue;
            }
            let images: Vec<_> = key
                .iter()
                .map(|id| id.and_then(|id| assets.image(id)))
                .collect();
            let serials: Vec<u64> = images
                .iter()
                .map(|image| image.map_or(0, |image| image.upload_serial))
                .collect();
            let entry = match previous.remove(&key) {
                Some(existing) if existing.serials == serials => existing,
                _ => {
                    let mut entries: Vec<wgpu::BindGroupEntry> = images
                        .iter()
                        .zip(self.defaults)
                        .enumerate()
                        .map(|(slot, (image, default))| wgpu::BindGroupEntry {
                            binding: slot as u32,
                            resource: wgpu::BindingResource::TextureView(
                                image.map_or(assets.defaults.view(default), |image| &image.view),
                            ),
                        })
                        .collect();
                    entries.push(wgpu::BindGroupEntry {
                        binding: N as u32,
                        resource: wgpu::BindingResource::Sampler(&self.sampler),
                    });
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
    pub fn get(&self, key: &TextureKey<N>) -> Option<&wgpu::BindGroup> {
        self.groups.get(key).map(|entry| &entry.bind_group)
    }
}
