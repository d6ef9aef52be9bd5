//! A measurement of the bilinear texel rate the fragment stage reaches on the adapter: the
//! limit of the path the parallax material runs on, which on some GPUs is far below the whole
//! chip's (only a few of their SMs run pixel shaders: sandbox/BENCHMARKS.md, "What the numbers
//! mean").

use wgpu::util::DeviceExt;

use crate::gpu::{GpuContext, clearing_attachment};
use crate::gpu::{PassTimestamps, time_pass};
use crate::render::RenderTarget;
use crate::render::shaders::{ComposedShader, FULLSCREEN_TRIANGLE, WgslFile};
use crate::{AppError, Resources};

/// The pass name the probe is timed under in [`crate::gpu::GpuTimings`].
pub const PROBE_PASS: &str = "texel-rate probe";
/// Side of the probe's texture: large enough that it does not all stay in the nearest cache.
const PROBE_TEXTURE_SIDE: u32 = 1024;
/// Half a texel per tap, the step of a dense march.
const STEP_TEXELS: f32 = 0.5;

/// The probe's full-screen pass.
pub const TEXEL_RATE_PROBE_ENTRY: WgslFile =
    crate::wgsl_file!("texel_rate_probe/texel_rate_probe.wgsl");

/// The bench's fragment-stage texel-rate probe.
pub const TEXEL_RATE_PROBE: ComposedShader = ComposedShader {
    name: "texel_rate_probe.wgsl",
    constants: &[],
    files: &[FULLSCREEN_TRIANGLE, TEXEL_RATE_PROBE_ENTRY],
};

/// A full-screen pass in which every pixel takes a fixed number of bilinear samples.
#[derive(Debug)]
pub struct TexelRateProbe {
    pipeline: wgpu::RenderPipeline,
    bind_group: wgpu::BindGroup,
    taps: u32,
}

impl TexelRateProbe {
    /// A probe taking `taps` samples per pixel (at least 1), drawing into targets of `format`.
    pub fn new(gpu: &GpuContext, format: wgpu::TextureFormat, taps: u32) -> Self {
        let device = &gpu.device;
        let taps = taps.max(1);
        let shader = TEXEL_RATE_PROBE.create_module(device);
        let texture = device.create_texture_with_data(
            &gpu.queue,
            &wgpu::TextureDescriptor {
                label: Some("texel-rate probe texture"),
                size: wgpu::Extent3d {
                    width: PROBE_TEXTURE_SIDE,
                    height: PROBE_TEXTURE_SIDE,
                    depth_or_array_layers: 1,
                },
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format: wgpu::TextureFormat::Rgba8Unorm,
                usage: wgpu::TextureUsages::TEXTURE_BINDING,
                view_formats: &[],
            },
            wgpu::util::TextureDataOrder::LayerMajor,
            &noise_texels(PROBE_TEXTURE_SIDE),
        );
        let sampler = device.create_sampler(&wgpu::SamplerDescriptor {
            label: Some("texel-rate probe sampler"),
            address_mode_u: wgpu::AddressMode::Repeat,
            address_mode_v: wgpu::AddressMode::Repeat,
            mag_filter: wgpu::FilterMode::Linear,
            min_filter: wgpu::FilterMode::Linear,
            ..Default::default()
        });
        let step = STEP_TEXELS / PROBE_TEXTURE_SIDE as f32;
        let params = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("texel-rate probe parameters"),
            contents: bytemuck::cast_slice(&[taps as f32, step, step * 0.5, 0.0]),
            usage: wgpu::BufferUsages::UNIFORM,
        });
        let pipeline = crate::gpu::layout::fullscreen_pipeline(
            device,
            "texel-rate probe",
            None,
            &shader,
            "fs_main",
            format,
        );
        let view = texture.create_view(&Default::default());
        let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("texel-rate probe bindings"),
            layout: &pipeline.get_bind_group_layout(0),
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: wgpu::BindingResource::TextureView(&view),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: wgpu::BindingResource::Sampler(&sampler),
                },
                wgpu::BindGroupEntry {
                    binding: 2,
                    resource: params.as_entire_binding(),
                },
            ],
        });
        Self {
            pipeline,
            bind_group,
            taps,
        }
    }

    /// Samples each pixel takes.
    pub fn taps(&self) -> u32 {
        self.taps
    }

    /// Draws the probe over the app's [`RenderTarget`], timed as [`PROBE_PASS`] when GPU timing
    /// is on, and submits. Call [`crate::gpu::resolve_gpu_timings`] afterwards to read the time.
    pub fn render(&self, resources: &mut Resources) -> Result<(), AppError> {
        let timestamps = time_pass(resources, PROBE_PASS);
        let gpu = resources.require::<GpuContext>()?;
        let target = resources.require::<RenderTarget>()?;
        let mut encoder = gpu
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("texel-rate probe encoder"),
            });
        {
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some(PROBE_PASS),
                color_attachments: &[Some(clearing_attachment(
                    &target.color_view,
                    wgpu::Color::BLACK,
                ))],
                depth_stencil_attachment: None,
                timestamp_writes: timestamps.as_ref().map(PassTimestamps::render),
                occlusion_query_set: None,
                multiview_mask: None,
            });
            pass.set_pipeline(&self.pipeline);
            pass.set_bind_group(0, &self.bind_group, &[]);
            pass.draw(0..3, 0..1);
        }
        gpu.queue.submit([encoder.finish()]);
        Ok(())
    }
}

/// Hashed RGBA8 texels: no two neighbours alike, so nothing compresses or repeats.
fn noise_texels(side: u32) -> Vec<u8> {
    (0..side * side * 4)
        .map(|i| (i.wrapping_mul(2_654_435_761) >> 24) as u8)
        .collect()
}
