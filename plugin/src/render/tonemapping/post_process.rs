//! The post-processing phase: tonemapping from the (pre-exposed) HDR scene target into the
//! display target, as a compute pass where the adapter can write the display format from
//! compute, else as a full-screen triangle.
//!
//! Why compute first: on the GPUs we measure, a full-screen fragment pass that only writes a
//! colour costs far more than the same pass in compute (sandbox/BENCHMARKS.md, "What the
//! numbers mean").

use bytemuck::{Pod, Zeroable};

use super::Tonemapping;
use crate::gpu::{BindGroupCache, FullScreenPipeline};
use crate::gpu::{GpuContext, PassTimestamps, layout};
use crate::render::shaders::{self, ComposedShader, WgslFile};
use crate::render::{
    FullScreenStage, PostImage, RenderTarget, TargetFormat, display_referred_wgsl,
};
use crate::shader::Choice;

/// Shared post-processing functions (settings, tonemapping, sRGB encoding).
pub const POST_PROCESS: WgslFile = crate::wgsl_file!(nested "render/tonemapping/post_process.wgsl");
/// The tonemapping operators.
pub const TONEMAPPING: WgslFile = crate::wgsl_file!(nested "render/tonemapping/tonemapping.wgsl");
/// The compute entry point.
pub const POST_COMPUTE_ENTRY: WgslFile =
    crate::wgsl_file!(nested "render/tonemapping/post_compute.wgsl");
/// The full-screen triangle fallback.
pub const POST_FRAGMENT_ENTRY: WgslFile =
    crate::wgsl_file!(nested "render/tonemapping/post_fragment.wgsl");

pub(crate) fn rgba8_output() -> String {
    "@group(0) @binding(2) var output: texture_storage_2d<rgba8unorm, write>;\n".to_owned()
}

pub(crate) fn rgba32f_output() -> String {
    "@group(0) @binding(2) var output: texture_storage_2d<rgba32float, write>;\n".to_owned()
}

/// Post-processing in compute, writing an 8-bit display target.
pub const POST_COMPUTE_RGBA8: ComposedShader = ComposedShader {
    name: "post_compute.wgsl (rgba8unorm)",
    constants: &[
        Tonemapping::wgsl_constants,
        display_referred_wgsl,
        rgba8_output,
    ],
    files: &[shaders::SRGB, TONEMAPPING, POST_PROCESS, POST_COMPUTE_ENTRY],
};

/// Post-processing in compute, writing a float display target.
pub const POST_COMPUTE_RGBA32F: ComposedShader = ComposedShader {
    name: "post_compute.wgsl (rgba32float)",
    constants: &[
        Tonemapping::wgsl_constants,
        display_referred_wgsl,
        rgba32f_output,
    ],
    files: &[shaders::SRGB, TONEMAPPING, POST_PROCESS, POST_COMPUTE_ENTRY],
};

/// Post-processing as a full-screen triangle.
pub const POST_FRAGMENT: ComposedShader = ComposedShader {
    name: "post_fragment.wgsl",
    constants: &[Tonemapping::wgsl_constants, display_referred_wgsl],
    files: &[
        shaders::SRGB,
        TONEMAPPING,
        POST_PROCESS,
        shaders::FULLSCREEN_TRIANGLE,
        POST_FRAGMENT_ENTRY,
    ],
};

/// The post-processing uniform; mirrors `PostSettings` in post_process.wgsl.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct PostSettings {
    /// `TONEMAP_*` code of the operator.
    pub tonemapping: u32,
    /// 1: encode with the sRGB curve; 0: write linear floats.
    pub encode_srgb: u32,
    /// Padding to 16 bytes.
    pub _padding: [u32; 2],
}

crate::wgsl_layout!(PostSettings {
    tonemapping,
    encode_srgb,
    _padding
});

impl PostSettings {
    /// The settings for a camera's operator, writing `format` (exposure is applied to the
    /// lights before the scene is drawn).
    pub fn new(tonemapping: Tonemapping, format: TargetFormat) -> Self {
        Self {
            tonemapping: tonemapping.code(),
            encode_srgb: u32::from(format == TargetFormat::Srgb8),
            _padding: [0; 2],
        }
    }
}

/// The tonemapping pass: pipeline, settings buffer, and the bind groups of the current target
/// (by what they read and write).
#[derive(Debug)]
pub struct PostProcess {
    pipeline: FullScreenPipeline,
    layout: wgpu::BindGroupLayout,
    settings: wgpu::Buffer,
    uploaded: Option<PostSettings>,
    // Bind groups by what they bind: the target, the colour read (the scene, or an HDR
    // effect's image) and the image written (the display, or the chain's image before a
    // display effect). A few at most: TAA's two histories take turns.
    bind_groups: BindGroupCache<BindingKey>,
    format: TargetFormat,
}

/// What one bind group of the pass binds: (target id, colour source id, output id).
type BindingKey = (u64, u64, u64);

impl PostProcess {
    /// The pass for display targets of `format`, run in `stage`.
    pub fn new(gpu: &GpuContext, format: TargetFormat, stage: FullScreenStage) -> Self {
        let device = &gpu.device;
        let display = format.texture_format();
        let layout = bind_group_layout(device, display, stage);
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("post-process pipeline layout"),
            bind_group_layouts: &[Some(&layout)],
            immediate_size: 0,
        });
        let pipeline = pipeline(device, &pipeline_layout, format, stage);
        let settings = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("post-process settings"),
            size: std::mem::size_of::<PostSettings>() as u64,
            // Bound as a read-only storage buffer (post_process.wgsl says why).
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        Self {
            pipeline,
            layout,
            settings,
            uploaded: None,
            bind_groups: BindGroupCache::default(),
            format,
        }
    }

    /// Whether the pass was made for display targets of `format`.
    pub(crate) fn is_for(&self, format: TargetFormat) -> bool {
        self.format == format
    }

    /// Writes `settings` if they changed; returns the bytes written.
    pub(crate) fn upload(&mut self, gpu: &GpuContext, settings: PostSettings) -> u64 {
        gpu.write_changed(&self.settings, &mut self.uploaded, settings)
    }

    /// The bind group reading `colour` (alpha from `target`'s scene) and writing `output`,
    /// made unless one exists.
    fn bind_group(
        &mut self,
        gpu: &GpuContext,
        target: &RenderTarget,
        (colour, output): (&PostImage, &PostImage),
    ) -> wgpu::BindGroup {
        // Groups of other targets are stale; a few of this one's are kept.
        self.bind_groups.retain(|(id, _, _)| *id == target.id());
        let (pipeline, layout, settings) = (&self.pipeline, &self.layout, &self.settings);
        self.bind_groups
            .get_or_make((target.id(), colour.id, output.id), || {
                let entries = vec![
                    wgpu::BindGroupEntry {
                        binding: 0,
                        resource: wgpu::BindingResource::TextureView(&target.scene_view),
                    },
                    wgpu::BindGroupEntry {
                        binding: 1,
                        resource: settings.as_entire_binding(),
                    },
                    wgpu::BindGroupEntry {
                        binding: 3,
                        resource: wgpu::BindingResource::TextureView(&colour.view),
                    },
                ];
                pipeline.bind_group(
                    &gpu.device,
                    ("post-process bind group", layout),
                    entries,
                    &output.view,
                )
            })
    }

    /// Records the pass: `colour` (with the alpha of `target`'s scene) tonemapped into
    /// `output`.
    pub(crate) fn record(
        &mut self,
        gpu: &GpuContext,
        target: &RenderTarget,
        (colour, output): (&PostImage, &PostImage),
        encoder: &mut wgpu::CommandEncoder,
        timestamps: Option<&PassTimestamps>,
    ) {
        let bind_group = self.bind_group(gpu, target, (colour, output));
        self.pipeline.record(
            "post-process pass",
            encoder,
            (&bind_group, &output.view),
            target.size(),
            timestamps,
        );
    }
}

/// Every post-processing shader, for validation.
pub(crate) const POST_SHADERS: [ComposedShader; 3] =
    [POST_COMPUTE_RGBA8, POST_COMPUTE_RGBA32F, POST_FRAGMENT];

/// The pass's bind group layout: the scene, the settings, the colour to tonemap and, in
/// compute, the image written.
fn bind_group_layout(
    device: &wgpu::Device,
    display: wgpu::TextureFormat,
    stage: FullScreenStage,
) -> wgpu::BindGroupLayout {
    let mut entries = vec![
        layout::unfilterable_texture_2d(0),
        layout::read_only_storage_buffer(1, std::mem::size_of::<PostSettings>() as u64),
        layout::unfilterable_texture_2d(3),
    ];
    if stage == FullScreenStage::Compute {
        entries.push(layout::compute_storage_texture(2, display));
    }
    device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("post-process layout"),
        entries: &entries,
    })
}

/// The pass's pipeline: compute where it can store the display format, else a full-screen
/// triangle.
fn pipeline(
    device: &wgpu::Device,
    pipeline_layout: &wgpu::PipelineLayout,
    format: TargetFormat,
    stage: FullScreenStage,
) -> FullScreenPipeline {
    let display = format.texture_format();
    if stage == FullScreenStage::Compute {
        let shader = match format {
            TargetFormat::Float32 => POST_COMPUTE_RGBA32F,
            _ => POST_COMPUTE_RGBA8,
        }
        .create_module(device);
        FullScreenPipeline::Compute(device.create_compute_pipeline(
            &wgpu::ComputePipelineDescriptor {
                label: Some("post-process compute pipeline"),
                layout: Some(pipeline_layout),
                module: &shader,
                entry_point: Some("post_main"),
                compilation_options: Default::default(),
                cache: None,
            },
        ))
    } else {
        let shader = POST_FRAGMENT.create_module(device);
        FullScreenPipeline::Fragment(layout::fullscreen_pipeline(
            device,
            "post-process fragment pipeline",
            Some(pipeline_layout),
            &shader,
            "post_fragment",
            display,
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_settings_match_their_wgsl() {
        for shader in POST_SHADERS {
            let layout =
                crate::shader::check_wgsl_layout::<PostSettings>(&shader.source(), "PostSettings");
            assert_eq!(layout, Ok(()), "{}", shader.name);
        }
    }
}
