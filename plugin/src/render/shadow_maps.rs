//! The shadow maps on the GPU: one depth texture array holding every map of the frame (a
//! layer each; smaller maps use a corner of theirs), the views receivers read, and the
//! comparison sampler that filters them.

use glam::Vec3;

use super::gpu_types::ShadowViewGpu;
use crate::gpu::GpuContext;
use crate::shadows::ShadowCasterChanges;

/// Most shadow maps one frame renders (a directional light takes 3, a spot 1, a point light
/// 6); lights past it cast no scene shadow, with a warning.
pub const MAX_SHADOW_VIEWS: usize = 32;

/// One shadow map to render: where it looks from and what receivers read of it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShadowViewPlan {
    /// What receivers read (its `layer` is assigned with the others).
    pub gpu: ShadowViewGpu,
    /// The light's eye: its position, or for a directional light a point behind the cascade.
    pub eye: Vec3,
    /// The direction the light looks (shines).
    pub forward: Vec3,
    /// Whether the view's rays are parallel (a directional light).
    pub orthographic: bool,
    /// Texels along each side of the map.
    pub map_size: u32,
}

/// The maps' depth format.
pub const SHADOW_MAP_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;

/// The shadow maps and what reads them. Part of the renderer.
#[derive(Debug)]
pub struct ShadowMaps {
    texture: Option<wgpu::Texture>,
    /// One view per layer, to render into.
    layer_views: Vec<wgpu::TextureView>,
    /// All layers, to sample (a 1 × 1 × 1 dummy until a light casts shadows).
    array_view: wgpu::TextureView,
    /// The same dummy, bound where the maps are being written.
    dummy_view: wgpu::TextureView,
    views: wgpu::Buffer,
    uploaded: Vec<ShadowViewGpu>,
    sampler: wgpu::Sampler,
    /// Changes whenever the texture is replaced (bind groups holding it must follow).
    generation: u64,
    /// What the maps show, as this frame's materials prepared it.
    pub(crate) casters: ShadowCasterChanges,
}

fn depth_array(gpu: &GpuContext, size: u32, layers: u32, label: &str) -> wgpu::Texture {
    gpu.device.create_texture(&wgpu::TextureDescriptor {
        label: Some(label),
        size: wgpu::Extent3d {
            width: size,
            height: size,
            depth_or_array_layers: layers,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format: SHADOW_MAP_FORMAT,
        usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::RENDER_ATTACHMENT,
        view_formats: &[],
    })
}

fn array_view(texture: &wgpu::Texture) -> wgpu::TextureView {
    texture.create_view(&wgpu::TextureViewDescriptor {
        dimension: Some(wgpu::TextureViewDimension::D2Array),
        ..Default::default()
    })
}

impl ShadowMaps {
    /// No maps yet: the dummy is bound.
    pub fn new(gpu: &GpuContext) -> Self {
        let dummy_view = array_view(&depth_array(gpu, 1, 1, "dummy shadow maps"));
        Self {
            texture: None,
            layer_views: Vec::new(),
            array_view: dummy_view.clone(),
            dummy_view,
            views: gpu.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("shadow views"),
                size: (MAX_SHADOW_VIEWS * std::mem::size_of::<ShadowViewGpu>()) as u64,
                usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            }),
            uploaded: Vec::new(),
            sampler: gpu.device.create_sampler(&wgpu::SamplerDescriptor {
                label: Some("shadow map sampler"),
                mag_filter: wgpu::FilterMode::Linear,
                min_filter: wgpu::FilterMode::Linear,
                compare: Some(wgpu::CompareFunction::LessEqual),
                ..Default::default()
            }),
            generation: 0,
            casters: ShadowCasterChanges::default(),
        }
    }

    /// Makes room for `plans` (the texture grows to the largest map and to their count, never
    /// shrinks) and uploads what receivers read of them, with each map's share of its layer.
    /// Returns the bytes written.
    pub fn prepare(&mut self, gpu: &GpuContext, plans: &[ShadowViewPlan]) -> u64 {
        let needed_size = plans.iter().map(|plan| plan.map_size).max().unwrap_or(0);
        let needed_layers = plans.len() as u32;
        let (size, layers) = self.texture.as_ref().map_or((0, 0), |texture| {
            (texture.width(), texture.depth_or_array_layers())
        });
        if needed_layers > 0 && (needed_size > size || needed_layers > layers) {
            let limit = gpu.device.limits().max_texture_dimension_2d;
            let size = needed_size.max(size).min(limit);
            let layers = needed_layers
                .max(layers)
                .min(gpu.device.limits().max_texture_array_layers);
            let texture = depth_array(gpu, size, layers, "shadow maps");
            self.layer_views = (0..layers)
                .map(|layer| {
                    texture.create_view(&wgpu::TextureViewDescriptor {
                        label: Some("shadow map layer"),
                        dimension: Some(wgpu::TextureViewDimension::D2),
                        base_array_layer: layer,
                        array_layer_count: Some(1),
                        ..Default::default()
                    })
                })
                .collect();
            self.array_view = array_view(&texture);
            self.texture = Some(texture);
            self.generation += 1;
        }
        let layer_size = self.layer_size() as f32;
        let views: Vec<ShadowViewGpu> = plans
            .iter()
            .map(|plan| ShadowViewGpu {
                uv_scale: plan.map_size.min(self.layer_size()) as f32 / layer_size,
                ..plan.gpu
            })
            .collect();
        if views == self.uploaded {
            return 0;
        }
        gpu.write_buffer(&self.views, 0, bytemuck::cast_slice(&views));
        self.uploaded = views;
        std::mem::size_of_val(self.uploaded.as_slice()) as u64
    }

    /// Texels along each side of a layer (0 before any map).
    pub fn layer_size(&self) -> u32 {
        self.texture.as_ref().map_or(0, wgpu::Texture::width)
    }

    /// The view to render map `layer` into.
    pub fn layer_view(&self, layer: u32) -> Option<&wgpu::TextureView> {
        self.layer_views.get(layer as usize)
    }

    /// What receivers sample: every layer (the dummy before any map).
    pub fn array_view(&self) -> &wgpu::TextureView {
        &self.array_view
    }

    /// A 1 × 1 × 1 stand-in, bound while the maps are being written.
    pub fn dummy_view(&self) -> &wgpu::TextureView {
        &self.dummy_view
    }

    /// The views receivers read (`shadow_views` in shadows.wgsl); never replaced.
    pub fn views_buffer(&self) -> &wgpu::Buffer {
        &self.views
    }

    /// The comparison sampler.
    pub fn sampler(&self) -> &wgpu::Sampler {
        &self.sampler
    }

    /// Changes whenever the texture is replaced.
    pub fn generation(&self) -> u64 {
        self.generation
    }
}
