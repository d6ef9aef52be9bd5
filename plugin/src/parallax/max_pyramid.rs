//! The maximum pyramid of a height texture, which MaxMip marches over hierarchically: a
//! [`TextureDeriver`] of the parallax material's, built on the GPU (`max_pyramid.wgsl`) with one
//! dispatch per level, recorded at the start of the frame that first uses it and of every frame
//! after a change of the height.

use bytemuck::{Pod, Zeroable};
use wgpu::util::DeviceExt;

use crate::gpu::layout;
use crate::gpu::{
    ComputeDispatch, ComputeDispatches, DerivedStorage, DerivedTextureBuilder, TextureDerivation,
    TextureDeriver,
};
use crate::render::shaders::{ComposedShader, WgslFile};
use crate::{Channel, GpuContext, HeightConvention};

/// Heights in Tatarchuk's convention from one channel of a texture (`height_in_channel`).
pub const HEIGHT_CHANNEL: WgslFile = crate::wgsl_file!("parallax/height_channel.wgsl");

/// The pyramid build's shader.
pub const MAX_PYRAMID_SHADER: ComposedShader = ComposedShader {
    name: "max_pyramid.wgsl",
    constants: &[],
    files: &[HEIGHT_CHANNEL, MAX_PYRAMID],
};

const MAX_PYRAMID: WgslFile = crate::wgsl_file!("parallax/max_pyramid.wgsl");

/// The maximum-height pyramid (`R32Float`, read with `textureLoad`): level 0 holds, per cell
/// between four texel centres (wrapping), the highest corner with 1 = top; each level above the
/// maximum of 2 × 2 cells, while both sides stay even.
pub struct MaxHeightPyramid;

impl MaxHeightPyramid {
    /// The pyramid of the height in `channel` of a source, inverted where white means deepest
    /// (depth maps).
    pub fn derivation(channel: Channel, convention: HeightConvention) -> TextureDerivation {
        let depth = convention == HeightConvention::Depth;
        TextureDerivation {
            deriver: &MaxHeightPyramid,
            parameters: [channel.index() as u32, u32::from(depth)],
        }
    }
}

impl TextureDeriver for MaxHeightPyramid {
    fn name(&self) -> &'static str {
        "max height pyramid"
    }

    fn compile(&self, gpu: &GpuContext) -> Box<dyn DerivedTextureBuilder> {
        Box::new(MaxPyramidBuilder::new(gpu))
    }
}

impl DerivedTextureBuilder for MaxPyramidBuilder {
    fn create(
        &self,
        gpu: &GpuContext,
        (width, height): (u32, u32),
        parameters: [u32; 2],
    ) -> DerivedStorage {
        let texture = create_pyramid(gpu, width, height);
        let levels = self.levels(gpu, &texture, parameters);
        DerivedStorage {
            texture,
            shared: Box::new(levels),
        }
    }

    fn build(
        &self,
        gpu: &GpuContext,
        source: &wgpu::Texture,
        storage: &DerivedStorage,
    ) -> ComputeDispatches {
        match storage.shared.downcast_ref::<PyramidLevels>() {
            Some(levels) => self.build_levels(gpu, source, &storage.texture, levels),
            // Only this builder makes its storage; nothing to build into anything else.
            None => ComputeDispatches::default(),
        }
    }
}

/// Mirrors `PyramidLevel` in max_pyramid.wgsl (checked by a test).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
struct PyramidLevel {
    size: [u32; 2],
    channel: u32,
    depth_convention: u32,
}

crate::wgsl_layout!(PyramidLevel {
    size,
    channel,
    depth_convention
});

/// Levels of the pyramid of a `width` × `height` map: they halve while both sides stay even,
/// so that every level repeats with the texture (1024² → 11, 96 × 64 → 6, 1000 × 600 → 4).
fn pyramid_levels(width: u32, height: u32) -> u32 {
    let (mut width, mut height, mut levels) = (width.max(1), height.max(1), 1);
    while width % 2 == 0 && height % 2 == 0 {
        width /= 2;
        height /= 2;
        levels += 1;
    }
    levels
}

/// The two pipelines (level 0 from the height texture, each level above from the one below).
struct MaxPyramidBuilder {
    layout: wgpu::BindGroupLayout,
    cell_maxima: wgpu::ComputePipeline,
    reduce_level: wgpu::ComputePipeline,
}

impl MaxPyramidBuilder {
    fn new(gpu: &GpuContext) -> Self {
        let device = &gpu.device;
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("max pyramid layout"),
            entries: &[
                layout::unfilterable_texture_2d(0),
                layout::compute_storage_texture(1, wgpu::TextureFormat::R32Float),
                layout::compute_uniform_buffer(2, false),
            ],
        });
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("max pyramid pipeline layout"),
            bind_group_layouts: &[Some(&layout)],
            immediate_size: 0,
        });
        let module = MAX_PYRAMID_SHADER.create_module(device);
        let pipeline = |entry_point: &str| {
            device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                label: Some(entry_point),
                layout: Some(&pipeline_layout),
                module: &module,
                entry_point: Some(entry_point),
                compilation_options: Default::default(),
                cache: None,
            })
        };
        Self {
            cell_maxima: pipeline("cell_maxima"),
            reduce_level: pipeline("reduce_level"),
            layout,
        }
    }

    /// The dispatches of a pyramid's levels above 0 (they read only `pyramid`, so they are made
    /// once per pyramid texture) and level 0's parameters (`[channel, depth_convention]`), for
    /// [`MaxPyramidBuilder::build_levels`].
    fn levels(
        &self,
        gpu: &GpuContext,
        pyramid: &wgpu::Texture,
        [channel, depth_convention]: [u32; 2],
    ) -> PyramidLevels {
        let (width, height) = (pyramid.width(), pyramid.height());
        let params = |level: u32| {
            gpu.device
                .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                    label: Some("max pyramid level"),
                    contents: bytemuck::bytes_of(&PyramidLevel {
                        size: [(width >> level).max(1), (height >> level).max(1)],
                        channel,
                        depth_convention,
                    }),
                    usage: wgpu::BufferUsages::UNIFORM,
                })
        };
        let upper = (1..pyramid.mip_level_count())
            .map(|level| {
                let below = level_view(pyramid, level - 1);
                self.level_build(
                    gpu,
                    &self.reduce_level,
                    level,
                    &below,
                    pyramid,
                    params(level),
                )
            })
            .collect();
        PyramidLevels {
            first_params: params(0),
            upper,
        }
    }

    /// The build of `heights`' pyramid into `pyramid`, whose `levels` are made by
    /// [`MaxPyramidBuilder::levels`] for it: only level 0, which reads `heights` (a re-upload
    /// replaces that texture), gets a new bind group. The frame records it before any phase
    /// that may read the pyramid.
    fn build_levels(
        &self,
        gpu: &GpuContext,
        heights: &wgpu::Texture,
        pyramid: &wgpu::Texture,
        levels: &PyramidLevels,
    ) -> ComputeDispatches {
        let first = self.level_build(
            gpu,
            &self.cell_maxima,
            0,
            &level_view(heights, 0),
            pyramid,
            levels.first_params.clone(),
        );
        ComputeDispatches(
            std::iter::once(first)
                .chain(levels.upper.iter().cloned())
                .collect(),
        )
    }

    /// The dispatch writing `pyramid`'s `level` from `below` with `pipeline`.
    fn level_build(
        &self,
        gpu: &GpuContext,
        pipeline: &wgpu::ComputePipeline,
        level: u32,
        below: &wgpu::TextureView,
        pyramid: &wgpu::Texture,
        params: wgpu::Buffer,
    ) -> ComputeDispatch {
        let bind_group = gpu.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("max pyramid level"),
            layout: &self.layout,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: wgpu::BindingResource::TextureView(below),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: wgpu::BindingResource::TextureView(&level_view(pyramid, level)),
                },
                wgpu::BindGroupEntry {
                    binding: 2,
                    resource: params.as_entire_binding(),
                },
            ],
        });
        let size = [
            (pyramid.width() >> level).max(1),
            (pyramid.height() >> level).max(1),
        ];
        // 8 × 8 workgroups (max_pyramid.wgsl).
        ComputeDispatch {
            pipeline: pipeline.clone(),
            bind_group,
            workgroups: [size[0].div_ceil(8), size[1].div_ceil(8), 1],
        }
    }
}

/// A view of `texture`'s `level` alone.
fn level_view(texture: &wgpu::Texture, level: u32) -> wgpu::TextureView {
    texture.create_view(&wgpu::TextureViewDescriptor {
        base_mip_level: level,
        mip_level_count: Some(1),
        ..Default::default()
    })
}

/// What a pyramid texture's builds share: level 0's parameters and the dispatches of the
/// levels above it.
#[derive(Debug)]
struct PyramidLevels {
    first_params: wgpu::Buffer,
    upper: Vec<ComputeDispatch>,
}

/// An empty pyramid for a `width` × `height` height texture: [`pyramid_levels`] levels of
/// `R32Float`. A pyramid with few levels for its size is logged: its cells are large, and a
/// hierarchical march over it tests many of them.
fn create_pyramid(gpu: &GpuContext, width: u32, height: u32) -> wgpu::Texture {
    let levels = pyramid_levels(width, height);
    let (coarsest_width, coarsest_height) = (width >> (levels - 1), height >> (levels - 1));
    if coarsest_width.max(coarsest_height) > 16 {
        log::warn!(
            "a {width}×{height} height map's maximum pyramid stops at {coarsest_width}×{coarsest_height} \
             cells (levels halve while both sides are even): hierarchical marches over it are slow"
        );
    }
    gpu.device.create_texture(&wgpu::TextureDescriptor {
        label: Some("max pyramid"),
        size: wgpu::Extent3d {
            width,
            height,
            depth_or_array_layers: 1,
        },
        mip_level_count: levels,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format: wgpu::TextureFormat::R32Float,
        // Copied from by tests that read it back.
        usage: wgpu::TextureUsages::TEXTURE_BINDING
            | wgpu::TextureUsages::STORAGE_BINDING
            | wgpu::TextureUsages::COPY_SRC,
        view_formats: &[],
    })
}

/// The maximum pyramid the renderer derives from `image` for `channel` and the convention,
/// read back: (width, height, maxima row by row) per level, finest first. For tests against a
/// CPU reference.
#[cfg(feature = "scene-tests")]
pub fn read_max_pyramid(
    gpu: &GpuContext,
    image: crate::Image,
    channel: Channel,
    convention: HeightConvention,
) -> Result<Vec<(u32, u32, Vec<f32>)>, crate::gpu::CaptureError> {
    let mut images = crate::Assets::default();
    let source = images.add(image).id();
    let mut assets = crate::gpu::GpuAssets::new(gpu);
    assets.prepare_image(gpu, &images, source);
    let derived = crate::gpu::DerivedTexture {
        source,
        derivation: MaxHeightPyramid::derivation(channel, convention),
    };
    assets.prepare_derived(gpu, derived);
    assets.pending_derived_builds().submit(gpu);
    assets.derived_builds_submitted();
    let pyramid = assets
        .derived(&derived)
        .ok_or_else(|| crate::gpu::CaptureError::Map("the image was not uploaded".into()))?
        .texture();
    (0..pyramid.mip_level_count())
        .map(|level| {
            let texels = crate::gpu::read_texture_level(gpu, pyramid, level)?;
            let size = pyramid.size().mip_level_size(level, pyramid.dimension());
            let maxima = bytemuck::pod_collect_to_vec::<u8, f32>(&texels);
            Ok((size.width, size.height, maxima))
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn levels_halve_while_both_sides_are_even() {
        assert_eq!(pyramid_levels(1024, 1024), 11);
        assert_eq!(pyramid_levels(96, 64), 6);
        assert_eq!(pyramid_levels(1000, 600), 4);
        assert_eq!(pyramid_levels(1, 1), 1);
        assert_eq!(pyramid_levels(0, 0), 1);
    }

    #[test]
    fn pyramid_level_matches_its_wgsl() {
        let source = MAX_PYRAMID_SHADER.source();
        assert_eq!(
            crate::shader::check_wgsl_layout::<PyramidLevel>(&source, "PyramidLevel"),
            Ok(())
        );
    }
}
