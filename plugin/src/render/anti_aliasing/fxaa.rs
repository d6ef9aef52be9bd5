//! The post filter pass (fxaa.wgsl): FXAA on the tonemapped image, for frames that ask for
//! anti-aliasing without a history: a display effect of the post chain, in compute where the
//! adapter can store the display format, else as a full-screen triangle. The
//! bilinear reads of the edge search go through a sampler on an 8-bit image and are four loads
//! on a float one (not filterable); the 3 × 3 neighbourhood is loaded. Its thresholds and
//! sub-pixel blend are the camera's [`FastApproximateAntiAliasing`], read from a small storage
//! buffer.

use bytemuck::{Pod, Zeroable};

use crate::gpu::{BindGroupCache, FullScreenPipeline};
use crate::gpu::{GpuContext, PassTimestamps, layout};
use crate::parameters::ParamSpec;
use crate::render::shaders::{self, ComposedShader, WgslFile};
use crate::render::tonemapping::{rgba8_output, rgba32f_output};
use crate::render::{FullScreenStage, PostImage, RenderTarget, TargetFormat};

crate::settings_parameters! {
    /// The parameters of FXAA, a component of the camera entity (the defaults, Lottes's
    /// "quality" ones, where it has none). Each is declared once, in
    /// [`FastApproximateAntiAliasing::PARAMETERS`]; values outside their limits are clamped,
    /// with one logged warning.
    #[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
    #[serde(default, deny_unknown_fields)]
    pub struct FastApproximateAntiAliasing {
        /// Edges of less luma contrast than this stay as they are (in dark regions, where the
        /// relative threshold is small): higher leaves more faint edges jagged.
        contrast_threshold: f32 = 0.0312, ParamSpec::float(0.0, 0.5);
        /// Edges of less luma contrast than this share of the neighbourhood's brightest luma
        /// stay as they are: higher filters fewer edges, lower softens more texture.
        relative_threshold: f32 = 0.125, ParamSpec::float(0.0, 0.5);
        /// How much of the sub-pixel blend a pixel standing out of its neighbourhood gets:
        /// higher removes more sub-pixel aliasing and softens more.
        subpixel_blending: f32 = 0.75, ParamSpec::float(0.0, 1.0);
    }
}

/// Puts `fxaa` on every active camera of `world` (replacing what they had); returns how many
/// cameras that was.
pub fn set_camera_fxaa(world: &mut hecs::World, fxaa: FastApproximateAntiAliasing) -> usize {
    let cameras = crate::camera::active_cameras(world);
    for camera in &cameras {
        // The entity was just found, so inserting cannot fail.
        let _ = world.insert_one(*camera, fxaa);
    }
    cameras.len()
}

/// FXAA's settings as the shader reads them; mirrors `FxaaSettings` in fxaa.wgsl.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct FxaaSettings {
    /// [`FastApproximateAntiAliasing::contrast_threshold`].
    pub contrast_threshold: f32,
    /// [`FastApproximateAntiAliasing::relative_threshold`].
    pub relative_threshold: f32,
    /// [`FastApproximateAntiAliasing::subpixel_blending`].
    pub subpixel_blending: f32,
    /// Padding to 16 bytes.
    pub _padding: f32,
}

crate::wgsl_layout!(FxaaSettings {
    contrast_threshold,
    relative_threshold,
    subpixel_blending,
    _padding
});

impl From<FastApproximateAntiAliasing> for FxaaSettings {
    /// The settings as uploaded (sanitize them first).
    fn from(fxaa: FastApproximateAntiAliasing) -> Self {
        Self {
            contrast_threshold: fxaa.contrast_threshold,
            relative_threshold: fxaa.relative_threshold,
            subpixel_blending: fxaa.subpixel_blending,
            _padding: 0.0,
        }
    }
}

/// The binding of [`FxaaSettings`] (0 to 2 are the image read, its sampler and the output).
const SETTINGS_BINDING: u32 = 3;

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

/// The FXAA pipeline and the bind groups of the images it last read and wrote. Made on the
/// first frame that asks for it.
#[derive(Debug)]
pub(crate) struct FxaaPass {
    pipeline: FullScreenPipeline,
    layout: wgpu::BindGroupLayout,
    /// The bilinear sampler of an 8-bit display's image (a float one is read with loads).
    sampler: Option<wgpu::Sampler>,
    format: TargetFormat,
    /// The settings buffer, and what it holds.
    settings: wgpu::Buffer,
    uploaded: Option<FxaaSettings>,
    /// Bind groups by the ids of the target, the image read and the image written.
    bind_groups: BindGroupCache<(u64, u64, u64)>,
}

/// Whether FXAA reads images of `format` through a filtering sampler: all but float ones.
fn filters(format: TargetFormat) -> bool {
    format != TargetFormat::Float32
}

/// The pass's bindings for display targets of `format`, drawn as a full-screen triangle
/// (`fragment`) or in compute.
fn bind_group_layout(
    device: &wgpu::Device,
    format: TargetFormat,
    fragment: bool,
) -> wgpu::BindGroupLayout {
    // A float display is read with loads, an 8-bit one through the sampler at binding 1.
    let mut entries = if filters(format) {
        vec![layout::texture_2d(0), layout::filtering_sampler(1)]
    } else {
        vec![layout::unfilterable_texture_2d(0)]
    };
    if !fragment {
        // Binding 2: the output post-processing's prelude declares.
        entries.push(layout::compute_storage_texture(2, format.texture_format()));
    }
    // Read-only storage, not a uniform (fxaa.wgsl says why).
    entries.push(layout::read_only_storage_buffer(
        SETTINGS_BINDING,
        std::mem::size_of::<FxaaSettings>() as u64,
    ));
    device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("fxaa layout"),
        entries: &entries,
    })
}

impl FxaaPass {
    /// The pass for display targets of `format`, run in `stage` (post-processing's own, so
    /// both run the same way).
    pub(crate) fn new(gpu: &GpuContext, format: TargetFormat, stage: FullScreenStage) -> Self {
        let fragment = stage == FullScreenStage::Fragment;
        let device = &gpu.device;
        let display = format.texture_format();
        let filtered = filters(format);
        let bind_layout = bind_group_layout(device, format, fragment);
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
            FullScreenPipeline::Fragment(layout::fullscreen_pipeline(
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
            FullScreenPipeline::Compute(device.create_compute_pipeline(
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
        let settings = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("fxaa settings"),
            size: std::mem::size_of::<FxaaSettings>() as u64,
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        Self {
            pipeline,
            layout: bind_layout,
            sampler,
            format,
            settings,
            uploaded: None,
            bind_groups: BindGroupCache::default(),
        }
    }

    /// Writes `settings` if they changed; returns the bytes written.
    pub(crate) fn upload(&mut self, gpu: &GpuContext, settings: FxaaSettings) -> u64 {
        gpu.write_changed(&self.settings, &mut self.uploaded, settings)
    }

    /// Whether the pass was made for targets of `format`.
    pub(crate) fn is_for(&self, format: TargetFormat) -> bool {
        self.format == format
    }

    /// The bind group reading `input` and, in compute, writing `output`, made unless the pass
    /// has one.
    fn bind_group(
        &mut self,
        (gpu, target): (&GpuContext, &RenderTarget),
        input: &PostImage,
        output: &PostImage,
    ) -> wgpu::BindGroup {
        // Groups of another target's images would keep them alive.
        self.bind_groups.retain(|(id, _, _)| *id == target.id());
        let (pipeline, layout) = (&self.pipeline, &self.layout);
        let (sampler, settings) = (self.sampler.as_ref(), &self.settings);
        self.bind_groups
            .get_or_make((target.id(), input.id, output.id), || {
                let mut entries = vec![
                    wgpu::BindGroupEntry {
                        binding: 0,
                        resource: wgpu::BindingResource::TextureView(&input.view),
                    },
                    wgpu::BindGroupEntry {
                        binding: SETTINGS_BINDING,
                        resource: settings.as_entire_binding(),
                    },
                ];
                if let Some(sampler) = sampler {
                    entries.push(wgpu::BindGroupEntry {
                        binding: 1,
                        resource: wgpu::BindingResource::Sampler(sampler),
                    });
                }
                pipeline.bind_group(
                    &gpu.device,
                    ("fxaa bind group", layout),
                    entries,
                    &output.view,
                )
            })
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
        let bind_group = self.bind_group((gpu, target), input, output);
        self.pipeline.record(
            "fxaa pass",
            encoder,
            (&bind_group, &output.view),
            target.size(),
            timestamps,
        );
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_settings_match_their_wgsl() {
        for shader in FXAA_SHADERS {
            let layout =
                crate::shader::check_wgsl_layout::<FxaaSettings>(&shader.source(), "FxaaSettings");
            assert_eq!(layout, Ok(()), "{}", shader.name);
        }
    }

    #[test]
    fn the_defaults_are_the_shaders_former_constants() {
        let defaults = FxaaSettings::from(FastApproximateAntiAliasing::default());
        assert_eq!(
            (
                defaults.contrast_threshold,
                defaults.relative_threshold,
                defaults.subpixel_blending
            ),
            (0.0312, 0.125, 0.75)
        );
    }

    #[test]
    fn out_of_range_settings_are_named_and_clamped() {
        let wild = FastApproximateAntiAliasing {
            contrast_threshold: -1.0,
            relative_threshold: f32::INFINITY,
            subpixel_blending: 2.0,
        };
        let problems: Vec<String> = wild.problems().iter().map(ToString::to_string).collect();
        assert_eq!(
            problems,
            [
                "contrast_threshold is -1 but must be at least 0",
                "relative_threshold is inf, which is not a finite number",
                "subpixel_blending is 2 but must be at most 1",
            ]
        );
        let clean = wild.sanitized();
        assert_eq!(clean.contrast_threshold, 0.0);
        assert_eq!(clean.relative_threshold, 0.125);
        assert_eq!(clean.subpixel_blending, 1.0);
        assert!(clean.problems().is_empty());
    }
}
