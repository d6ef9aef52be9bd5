//! The post filter pass (fxaa.wgsl): FXAA on the tonemapped image, for frames that ask for
//! anti-aliasing without a history: a display effect of the post chain, in compute where the
//! adapter can store the display format, else as a full-screen triangle. The
//! bilinear reads of the edge search go through a sampler on an 8-bit image and are four loads
//! on a float one (not filterable); the 3 × 3 neighbourhood is loaded.

use crate::render::shaders::{self, ComposedShader, WgslFile};
use crate::render::tonemapping::{rgba8_output, rgba32f_output};
use crate::render::{
    FullScreenStage, GpuContext, PassTimestamps, PostImage, RenderTarget, TargetFormat,
    clearing_attachment, layout,
};

/// The pass's WGSL file.
pub const FXAA_ENTRY: WgslFile = crate::wgsl_file!(nested "render/anti_aliasing/fxaa.wgsl");

/// The compute and fragment entry points.
pub const FXAA_ENTRY_POINTS: WgslFile =
    crate::wgsl_file!(nested "render/anti_aliasing/fxaa_entry.wgsl");

fn srgb_input() -> String {
    "const LINEAR_INPUT: bool = false;\n".to_owned()
}

fn linear_input() -> String {
    "const LINEAR_INPUT: bool = true;\n".to_owned()
}

fn no_output() -> String {
    String::new()
}

/// FXAA's bilinear read with the sampler (8-bit displays).
pub const FXAA_FILTERED_READ: WgslFile =
    crate::wgsl_file!(nested "render/anti_aliasing/fxaa_filtered.wgsl");

/// FXAA's bilinear read from four loads (float displays, which do not filter).
pub const FXAA_LOADS_READ: WgslFile =
    crate::wgsl_file!(nested "render/anti_aliasing/fxaa_loads.wgsl");

/// FXAA in compute, writing an 8-bit display target.
pub const FXAA_COMPUTE_RGBA8: ComposedShader = ComposedShader {
    name: "fxaa.wgsl (rgba8unorm)",
    constants: &[rgba8_output, srgb_input],
    files: &[FXAA_ENTRY, FXAA_FILTERED_READ, FXAA_ENTRY_POINTS],
};

/// FXAA in compute, writing a float display target.
pub const FXAA_COMPUTE_RGBA32F: ComposedShader = ComposedShader {
    name: "fxaa.wgsl (rgba32float)",
    constants: &[rgba32f_output, linear_input],
    files: &[FXAA_ENTRY, FXAA_LOADS_READ, FXAA_ENTRY_POINTS],
};

/// FXAA as a full-screen triangle (8-bit display).
pub const FXAA_FRAGMENT: ComposedShader = ComposedShader {
    name: "fxaa.wgsl (fragment)",
    constants: &[no_output, srgb_input],
    files: &[
        FXAA_ENTRY,
        FXAA_FILTERED_READ,
        shaders::FULLSCREEN_TRIANGLE,
        FXAA_FRAGMENT_ENTRY,
    ],
};

/// FXAA as a full-screen triangle (float display).
pub const FXAA_FRAGMENT_LINEAR: ComposedShader = ComposedShader {
    name: "fxaa.wgsl (fragment, linear)",
    constants: &[no_output, linear_input],
    files: &[
        FXAA_ENTRY,
        FXAA_LOADS_READ,
        shaders::FULLSCREEN_TRIANGLE,
        FXAA_FRAGMENT_ENTRY,
    ],
};

/// The full-screen triangle's entry point.
pub const FXAA_FRAGMENT_ENTRY: WgslFile =
    crate::wgsl_file!(nested "render/anti_aliasing/fxaa_fragment.wgsl");

/// Every FXAA shader, for validation.
pub const FXAA_SHADERS: [ComposedShader; 4] = [
    FXAA_COMPUTE_RGBA8,
    FXAA_COMPUTE_RGBA32F,
    FXAA_FRAGMENT,
    FXAA_FRAGMENT_LINEAR,
];

#[derive(Debug)]
enum FxaaPipeline {
    Compute(wgpu::ComputePipeline),
    Fragment(wgpu::RenderPipeline),
}

/// The FXAA pipeline and the bind groups of the images it last read and wrote. Made on the
/// first frame that asks for it.
#[derive(Debug)]
pub(crate) struct FxaaPass {
    pipeline: FxaaPipeline,
    layout: wgpu::BindGroupLayout,
    /// The bilinear sampler of an 8-bit display's image (a float one is read with loads).
    sampler: Option<wgpu::Sampler>,
    format: TargetFormat,
    /// Bind groups by the ids of the image read and the image written: the chain's images
    /// change only with the target.
    bind_groups: Vec<((u64, u64), wgpu::BindGroup)>,
}

/// Whether FXAA reads images of `format` through a filtering sampler: all but float ones.
fn filters(format: TargetFormat) -> bool {
    format != TargetFormat::Float32
}

impl FxaaPass {
    /// The pass for display targets of `format`, run in `stage` (post-processing's own, so
    /// both run the same way).
    pub(crate) fn new(gpu: &GpuContext, format: TargetFormat, stage: FullScreenStage) -> Self {
        let fragment = stage == FullScreenStage::Fragment;
        let device = &gpu.device;
        let display = format.texture_format();
        // A float display is read with loads, an 8-bit one through the sampler at binding 1.
        let filtered = filters(format);
        let mut entries = if filtered {
            vec![layout::texture_2d(0), layout::filtering_sampler(1)]
        } else {
            vec![layout::unfilterable_texture_2d(0)]
        };
        if !fragment {
            // Binding 2: the output post-processing's prelude declares.
            entries.push(layout::compute_storage_texture(2, display));
        }
        let bind_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("fxaa layout"),
            entries: &entries,
        });
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("fxaa pipeline layout"),
            bind_group_layouts: &[Some(&bind_layout)],
            immediate_size: 0,
        });
        let pipeline = if fragment {
            let module = match format {
                TargetFormat::Float32 => FXAA_FRAGMENT_LINEAR,
                _ => FXAA_FRAGMENT,
            }
            .create_module(device);
            FxaaPipeline::Fragment(layout::fullscreen_pipeline(
                device,
                "fxaa fragment pipeline",
                Some(&pipeline_layout),
                &module,
                "fxaa_fragment",
                display,
            ))
        } else {
            let module = match format {
                TargetFormat::Float32 => FXAA_COMPUTE_RGBA32F,
                _ => FXAA_COMPUTE_RGBA8,
            }
            .create_module(device);
            FxaaPipeline::Compute(device.create_compute_pipeline(
                &wgpu::ComputePipelineDescriptor {
                    label: Some("fxaa compute pipeline"),
                    layout: Some(&pipeline_layout),
                    module: &module,
                    entry_point: Some("fxaa_main"),
                    compilation_options: Default::default(),
                    cache: None,
                },
            ))
        };
        let sampler = filtered.then(|| {
            device.create_sampler(&wgpu::SamplerDescriptor {
                label: Some("fxaa sampler"),
                // At the borders as the loads clamp (fxaa_filtered.wgsl).
                address_mode_u: wgpu::AddressMode::ClampToEdge,
                address_mode_v: wgpu::AddressMode::ClampToEdge,
                mag_filter: wgpu::FilterMode::Linear,
                min_filter: wgpu::FilterMode::Linear,
                ..Default::default()
            })
        });
        Self {
            pipeline,
            layout: bind_layout,
            sampler,
            format,
            bind_groups: Vec::new(),
        }
    }

    /// Whether the pass was made for targets of `format`.
    pub(crate) fn is_for(&self, format: TargetFormat) -> bool {
        self.format == format
    }

    /// The bind group reading `input` and, in compute, writing `output`, made unless the pass
    /// has one.
    fn bind_group(
        &mut self,
        gpu: &GpuContext,
        input: &PostImage,
        output: &PostImage,
    ) -> wgpu::BindGroup {
        let key = (input.id, output.id);
        if let Some((_, group)) = self.bind_groups.iter().find(|(k, _)| *k == key) {
            return group.clone();
        }
        let mut entries = vec![wgpu::BindGroupEntry {
            binding: 0,
            resource: wgpu::BindingResource::TextureView(&input.view),
        }];
        if let Some(sampler) = &self.sampler {
            entries.push(wgpu::BindGroupEntry {
                binding: 1,
                resource: wgpu::BindingResource::Sampler(sampler),
            });
        }
        if matches!(self.pipeline, FxaaPipeline::Compute(_)) {
            entries.push(wgpu::BindGroupEntry {
                binding: 2,
                resource: wgpu::BindingResource::TextureView(&output.view),
            });
        }
        let group = gpu.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("fxaa bind group"),
            layout: &self.layout,
            entries: &entries,
        });
        // Groups of earlier targets' images are stale; a target's chain has few.
        if self.bind_groups.len() >= 4 {
            self.bind_groups.remove(0);
        }
        self.bind_groups.push((key, group.clone()));
        group
    }

    /// Records the pass: the tonemapped `input`, the size of `target`, into `output`.
    pub(crate) fn record(
        &mut self,
        gpu: &GpuContext,
        target: &RenderTarget,
        (input, output): (&PostImage, &PostImage),
        encoder: &mut wgpu::CommandEncoder,
        timestamps: Option<&PassTimestamps>,
    ) {
        let bind_group = self.bind_group(gpu, input, output);
        let (width, height) = target.size();
        match &self.pipeline {
            FxaaPipeline::Compute(pipeline) => {
                let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                    label: Some("fxaa pass"),
                    timestamp_writes: timestamps.map(PassTimestamps::compute),
                });
                pass.set_pipeline(pipeline);
                pass.set_bind_group(0, &bind_group, &[]);
                pass.dispatch_workgroups(width.div_ceil(8), height.div_ceil(8), 1);
            }
            FxaaPipeline::Fragment(pipeline) => {
                let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                    label: Some("fxaa pass"),
                    color_attachments: &[Some(clearing_attachment(
                        &output.view,
                        wgpu::Color::TRANSPARENT,
                    ))],
                    depth_stencil_attachment: None,
                    timestamp_writes: timestamps.map(PassTimestamps::render),
                    occlusion_query_set: None,
                    multiview_mask: None,
                });
                pass.set_pipeline(pipeline);
                pass.set_bind_group(0, &bind_group, &[]);
                pass.draw(0..3, 0..1);
            }
        }
    }
}
