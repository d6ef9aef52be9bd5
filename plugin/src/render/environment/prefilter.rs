//! The environment on the GPU and its prefiltering (prefilter.wgsl), run when the environment
//! is set or changes: the source is captured into a cube with a full mip chain, whose mips
//! give the radiance cube's GGX-blurred mips and the irradiance's harmonics; the split-sum
//! table is made once (split_sum.rs).

use std::sync::Arc;

use wgpu::util::DeviceExt;

use super::gpu_textures::{Cubes, cube_view, image_texture, level_view};

use super::SPHERICAL_HARMONICS;
use super::sky::SkyParams;
use super::source::{EquirectImage, SourceKind, SourceParams};
use super::split_sum::{SPLIT_SUM_SIZE, split_sum_table};
use crate::gpu::{GpuContext, PassTimestamps};
use crate::render::EnvironmentTextures;
use crate::render::shaders::{ComposedShader, WgslFile};

/// Preetham's sky in WGSL.
pub const SKY: WgslFile = crate::wgsl_file!(nested "render/environment/sky.wgsl");
/// The environment's source as WGSL reads it (group 1).
pub const ENVIRONMENT_SOURCE: WgslFile =
    crate::wgsl_file!(nested "render/environment/environment_source.wgsl");
/// The prefilter's entry points.
pub const PREFILTER_ENTRY: WgslFile = crate::wgsl_file!(nested "render/environment/prefilter.wgsl");

/// The prefilter's shader.
pub const PREFILTER: ComposedShader = ComposedShader {
    name: "prefilter.wgsl",
    constants: &[],
    files: &[
        SKY,
        ENVIRONMENT_SOURCE,
        SPHERICAL_HARMONICS,
        PREFILTER_ENTRY,
    ],
};

/// GGX samples per texel of the radiance cube's blurred mips.
const SPECULAR_SAMPLES: u32 = 256;

/// Largest side of the cube mip the irradiance is projected from.
const IRRADIANCE_SIDE: u32 = 32;

/// Mirrors `PrefilterParams` in prefilter.wgsl.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub(crate) struct PrefilterParams {
    size: u32,
    source_size: u32,
    source_levels: u32,
    samples: u32,
    roughness: f32,
    image_level: f32,
    radiance_scale: f32,
    _padding: u32,
}

crate::wgsl_layout!(PrefilterParams {
    size,
    source_size,
    source_levels,
    samples,
    roughness,
    image_level,
    radiance_scale,
    _padding
});

/// The radiance cube's mips for a largest mip of `size` texels a side: down to 4 × 4.
pub fn radiance_levels(size: u32) -> u32 {
    (size.max(4).ilog2()).saturating_sub(1).max(1)
}

/// What one prefiltering makes from: the source and the cube's size.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Capture {
    /// Which source.
    pub kind: SourceKind,
    /// A uniform source's radiance.
    pub uniform: [f32; 3],
    /// The sky's parameters (a sky source).
    pub sky: SkyParams,
    /// The image (an equirect source).
    pub image: Option<Arc<EquirectImage>>,
    /// Texels along a side of the radiance cube's largest mip.
    pub size: u32,
    /// What the source is multiplied with before it is stored in half floats.
    pub radiance_scale: f32,
}

impl Capture {
    /// Whether `other` prefilters to the same maps (an image compared by identity).
    fn same_as(&self, other: &Capture) -> bool {
        let image = |capture: &Capture| capture.image.as_ref().map(Arc::as_ptr);
        self.kind == other.kind
            && self.uniform == other.uniform
            && self.sky == other.sky
            && image(self) == image(other)
            && self.size == other.size
    }
}

/// The environment's GPU state. A resource of the environment plugin.
pub(crate) struct EnvironmentGpu {
    device: wgpu::Device,
    pipelines: [wgpu::ComputePipeline; 4],
    split_sum: wgpu::TextureView,
    image_sampler: wgpu::Sampler,
    cube_sampler: wgpu::Sampler,
    sky: wgpu::Buffer,
    source: wgpu::Buffer,
    /// The equirect image on the GPU (a 1-texel stand-in without one) and the image it holds.
    image: (Option<Arc<EquirectImage>>, wgpu::Texture),
    cubes: Option<Cubes>,
    /// What the cubes hold, once prefiltered.
    built: Option<Capture>,
    /// The capture to record this frame.
    pending: Option<Capture>,
    /// Counts the images uploaded (groups binding the image follow it).
    image_generation: u64,
}

fn pipeline(gpu: &GpuContext, module: &wgpu::ShaderModule, entry: &str) -> wgpu::ComputePipeline {
    gpu.device
        .create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some(entry),
            layout: None,
            module,
            entry_point: Some(entry),
            compilation_options: Default::default(),
            cache: None,
        })
}

/// A buffer of parameters the shaders read as storage (see environment_source.wgsl).
fn parameters(gpu: &GpuContext, label: &str, size: u64) -> wgpu::Buffer {
    gpu.device.create_buffer(&wgpu::BufferDescriptor {
        label: Some(label),
        size,
        usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    })
}

impl EnvironmentGpu {
    /// The pipelines, the split-sum table and the stand-in image, on `gpu`'s device.
    pub(crate) fn new(gpu: &GpuContext) -> Self {
        let module = PREFILTER.create_module(&gpu.device);
        let pipelines = [
            "cs_capture",
            "cs_downsample",
            "cs_specular",
            "cs_irradiance",
        ]
        .map(|entry| pipeline(gpu, &module, entry));
        let table: Vec<half::f16> = split_sum_table()
            .iter()
            .flatten()
            .map(|value| half::f16::from_f32(*value))
            .collect();
        let side = SPLIT_SUM_SIZE as u32;
        let split_sum = image_texture(gpu, "split-sum table", &[(side, side, table)])
            .create_view(&Default::default());
        let sampler = |label, repeat_u| {
            gpu.device.create_sampler(&wgpu::SamplerDescriptor {
                label: Some(label),
                address_mode_u: if repeat_u {
                    wgpu::AddressMode::Repeat
                } else {
                    wgpu::AddressMode::ClampToEdge
                },
                mag_filter: wgpu::FilterMode::Linear,
                min_filter: wgpu::FilterMode::Linear,
                mipmap_filter: wgpu::MipmapFilterMode::Linear,
                ..Default::default()
            })
        };
        let stand_in = vec![half::f16::ZERO; 4];
        Self {
            device: gpu.device.clone(),
            pipelines,
            split_sum,
            image_sampler: sampler("environment image sampler", true),
            cube_sampler: sampler("environment cube sampler", false),
            sky: parameters(
                gpu,
                "environment sky",
                std::mem::size_of::<SkyParams>() as u64,
            ),
            source: parameters(
                gpu,
                "environment source",
                std::mem::size_of::<SourceParams>() as u64,
            ),
            image: (
                None,
                image_texture(gpu, "environment image stand-in", &[(1, 1, stand_in)]),
            ),
            cubes: None,
            built: None,
            pending: None,
            image_generation: 0,
        }
    }

    /// Whether this state was made on `gpu`'s device.
    pub(crate) fn made_on(&self, gpu: &GpuContext) -> bool {
        self.device == gpu.device
    }

    /// Readies `capture` to be recorded this frame, unless the cubes hold it already: uploads
    /// its image and parameters, and makes cubes of its size. Returns the maps to bind when
    /// they are new, and the bytes uploaded.
    pub(crate) fn prepare(
        &mut self,
        gpu: &GpuContext,
        capture: Capture,
    ) -> (Option<EnvironmentTextures>, u64) {
        self.pending = None;
        if self
            .built
            .as_ref()
            .is_some_and(|built| built.same_as(&capture))
        {
            return (None, 0);
        }
        let mut uploaded = 0;
        let image_is_new = match (&self.image.0, &capture.image) {
            (Some(old), Some(new)) => !Arc::ptr_eq(old, new),
            (None, Some(_)) => true,
            _ => false,
        };
        if let (true, Some(image)) = (image_is_new, &capture.image) {
            let limit = gpu.device.limits().max_texture_dimension_2d;
            let levels = image.mip_chain(limit);
            if let Some(&(width, height, _)) = levels.first()
                && (width, height) != image.size()
            {
                let (full_width, full_height) = image.size();
                log::warn!(
                    "environment {}: {full_width} × {full_height} is larger than the GPU's \
                     {limit}-texel textures: averaged down to {width} × {height}",
                    image.name()
                );
            }
            uploaded += levels
                .iter()
                .map(|(_, _, texels)| texels.len() as u64 * 2)
                .sum::<u64>();
            self.image = (
                Some(image.clone()),
                image_texture(gpu, image.name(), &levels),
            );
            self.image_generation += 1;
        }
        let source = SourceParams {
            uniform_radiance: [
                capture.uniform[0],
                capture.uniform[1],
                capture.uniform[2],
                0.0,
            ],
            kind: [capture.kind as u32, 0, 0, 0],
        };
        gpu.write_buffer(&self.source, 0, bytemuck::bytes_of(&source));
        gpu.write_buffer(&self.sky, 0, bytemuck::bytes_of(&capture.sky));
        uploaded += (std::mem::size_of::<SourceParams>() + std::mem::size_of::<SkyParams>()) as u64;
        let mut installed = None;
        if self.cubes.as_ref().map(|cubes| cubes.size) != Some(capture.size) {
            let cubes = Cubes::new(gpu, capture.size, &self.split_sum);
            installed = Some(cubes.textures.clone());
            self.cubes = Some(cubes);
        }
        self.pending = Some(capture.clone());
        self.built = Some(capture);
        (installed, uploaded)
    }

    /// Records nothing this frame (the environment is off).
    pub(crate) fn skip(&mut self) {
        self.pending = None;
    }

    /// The maps of the last prefiltering, if any.
    pub(crate) fn textures(&self) -> Option<EnvironmentTextures> {
        self.cubes.as_ref().map(|cubes| cubes.textures.clone())
    }

    /// Changes whenever another image is uploaded.
    pub(crate) fn image_generation(&self) -> u64 {
        self.image_generation
    }

    /// Whether a prefiltering is to be recorded this frame.
    pub(crate) fn has_pending(&self) -> bool {
        self.pending.is_some() && self.cubes.is_some()
    }

    /// The image the source reads (the stand-in without one), the sampler, and the source's
    /// uniforms: group 1 of the capture and the background.
    pub(crate) fn source_group(&self, layout: &wgpu::BindGroupLayout) -> wgpu::BindGroup {
        let image = self.image.1.create_view(&Default::default());
        self.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("environment source"),
            layout,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: self.source.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: self.sky.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 2,
                    resource: wgpu::BindingResource::TextureView(&image),
                },
                wgpu::BindGroupEntry {
                    binding: 3,
                    resource: wgpu::BindingResource::Sampler(&self.image_sampler),
                },
            ],
        })
    }

    /// The mip of the source image whose texels are about the size of the cube's.
    fn image_level(&self, size: u32) -> f32 {
        let width = self.image.1.width();
        // An equirect texel spans 2π / width; a cube texel about (π / 2) / size.
        (width as f32 / (4.0 * size as f32)).max(1.0).log2()
    }

    /// Records the pending prefiltering, timed by `time`.
    pub(crate) fn record(&self, encoder: &mut wgpu::CommandEncoder, time: Option<&PassTimestamps>) {
        let (Some(capture), Some(cubes)) = (&self.pending, &self.cubes) else {
            return;
        };
        let size = cubes.size;
        let params = |level_size: u32, roughness: f32| PrefilterParams {
            size: level_size,
            source_size: size,
            source_levels: cubes.source.mip_level_count(),
            samples: SPECULAR_SAMPLES,
            roughness,
            image_level: self.image_level(size),
            radiance_scale: capture.radiance_scale,
            _padding: 0,
        };
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("environment prefilter"),
            timestamp_writes: time.map(PassTimestamps::compute),
        });
        self.capture(&mut pass, cubes, &params);
        self.blur_and_project(&mut pass, cubes, &params);
        drop(pass);
        // The radiance cube's sharpest mip is the source itself.
        let face = |texture| wgpu::TexelCopyTextureInfo {
            texture,
            mip_level: 0,
            origin: wgpu::Origin3d::ZERO,
            aspect: wgpu::TextureAspect::All,
        };
        encoder.copy_texture_to_texture(
            face(&cubes.source),
            face(&cubes.radiance),
            wgpu::Extent3d {
                width: size,
                height: size,
                depth_or_array_layers: 6,
            },
        );
    }

    /// The source captured into the source cube's largest mip, and each mip averaged into the
    /// next.
    fn capture(
        &self,
        pass: &mut wgpu::ComputePass<'_>,
        cubes: &Cubes,
        params: &impl Fn(u32, f32) -> PrefilterParams,
    ) {
        let [capture, downsample, ..] = &self.pipelines;
        let source_group = self.source_group(&capture.get_bind_group_layout(1));
        pass.set_bind_group(1, &source_group, &[]);
        let size = cubes.size;
        let first = [(1, Binding::Output(&cubes.source, 0))];
        self.dispatch(pass, capture, params(size, 0.0), &first);
        for level in 1..cubes.source.mip_level_count() {
            let bindings = [
                (1, Binding::Output(&cubes.source, level)),
                (2, Binding::Level(&cubes.source, level - 1)),
            ];
            self.dispatch(
                pass,
                downsample,
                params((size >> level).max(1), 0.0),
                &bindings,
            );
        }
    }

    /// The radiance cube's mips past the first, each blurred by a GGX lobe of its roughness,
    /// and the irradiance's harmonics from a small mip of the source.
    fn blur_and_project(
        &self,
        pass: &mut wgpu::ComputePass<'_>,
        cubes: &Cubes,
        params: &impl Fn(u32, f32) -> PrefilterParams,
    ) {
        let [_, _, specular, irradiance] = &self.pipelines;
        let size = cubes.size;
        let cube = cube_view(&cubes.source);
        let levels = cubes.radiance.mip_level_count();
        for level in 1..levels {
            let roughness = level as f32 / (levels - 1) as f32;
            let bindings = [
                (1, Binding::Output(&cubes.radiance, level)),
                (3, Binding::Cube(&cube)),
                (4, Binding::Sampler(&self.cube_sampler)),
            ];
            self.dispatch(
                pass,
                specular,
                params((size >> level).max(1), roughness),
                &bindings,
            );
        }
        let level = size.ilog2().saturating_sub(IRRADIANCE_SIDE.ilog2());
        let bindings = [
            (2, Binding::Level(&cubes.source, level)),
            (5, Binding::Buffer(&cubes.textures.irradiance)),
        ];
        self.dispatch(
            pass,
            irradiance,
            params((size >> level).max(1), 0.0),
            &bindings,
        );
    }

    /// One dispatch of `pipeline` over a mip of `params.size` texels a side and six faces (one
    /// workgroup for the irradiance), with `params` at binding 0 and `bindings`.
    fn dispatch(
        &self,
        pass: &mut wgpu::ComputePass<'_>,
        pipeline: &wgpu::ComputePipeline,
        params: PrefilterParams,
        bindings: &[(u32, Binding<'_>)],
    ) {
        let params_buffer = self
            .device
            .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("environment prefilter parameters"),
                contents: bytemuck::bytes_of(&params),
                usage: wgpu::BufferUsages::STORAGE,
            });
        let views: Vec<Option<wgpu::TextureView>> = bindings
            .iter()
            .map(|(_, binding)| match binding {
                Binding::Output(texture, level) | Binding::Level(texture, level) => {
                    Some(level_view(texture, *level))
                }
                _ => None,
            })
            .collect();
        let mut entries = vec![wgpu::BindGroupEntry {
            binding: 0,
            resource: params_buffer.as_entire_binding(),
        }];
        for ((index, binding), view) in bindings.iter().zip(&views) {
            let resource = match (binding, view) {
                (_, Some(view)) => wgpu::BindingResource::TextureView(view),
                (Binding::Cube(view), None) => wgpu::BindingResource::TextureView(view),
                (Binding::Sampler(sampler), None) => wgpu::BindingResource::Sampler(sampler),
                (Binding::Buffer(buffer), None) => buffer.as_entire_binding(),
                _ => continue,
            };
            entries.push(wgpu::BindGroupEntry {
                binding: *index,
                resource,
            });
        }
        let group = self.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("environment prefilter"),
            layout: &pipeline.get_bind_group_layout(0),
            entries: &entries,
        });
        pass.set_pipeline(pipeline);
        pass.set_bind_group(0, &group, &[]);
        if matches!(bindings.last(), Some((_, Binding::Buffer(_)))) {
            pass.dispatch_workgroups(1, 1, 1);
        } else {
            let groups = params.size.div_ceil(8);
            pass.dispatch_workgroups(groups, groups, 6);
        }
    }
}

/// What a prefilter dispatch binds besides its parameters.
enum Binding<'a> {
    /// A cube's mip, written.
    Output(&'a wgpu::Texture, u32),
    /// A cube's mip, loaded from.
    Level(&'a wgpu::Texture, u32),
    /// A whole cube, sampled.
    Cube(&'a wgpu::TextureView),
    Sampler(&'a wgpu::Sampler),
    Buffer(&'a wgpu::Buffer),
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_prefilter_params_match_their_wgsl() {
        let source = PREFILTER.source();
        for result in [
            crate::shader::check_wgsl_layout::<PrefilterParams>(&source, "PrefilterParams"),
            crate::shader::check_wgsl_layout::<SourceParams>(&source, "SourceParams"),
            crate::shader::check_wgsl_layout::<SkyParams>(&source, "SkyParams"),
        ] {
            assert_eq!(result, Ok(()));
        }
    }

    #[test]
    fn the_radiance_cube_keeps_mips_down_to_four_texels() {
        assert_eq!(radiance_levels(256), 7);
        assert_eq!(radiance_levels(16), 3);
        assert_eq!(radiance_levels(4), 1);
        assert_eq!(radiance_levels(1), 1);
    }
}
