//! [`FullScreenPass`]: a post effect's pass from one WGSL function, `effect(pixel)`, run as a
//! compute pass or a full-screen triangle wherever the renderer runs full-screen work, with
//! its input image, its parameters and its output bound for it. A toolkit on the core's post
//! chain (post_chain.rs) for writing an effect in one file: the core does not use it; a game's
//! effect (`plugin/examples/post_effect.rs`) does.

use crate::gpu::{BindGroupCache, FullScreenPipeline};
use crate::gpu::{PassTimestamps, layout};
use crate::render::shaders::{self, WgslFile};
use crate::render::{
    FrameView, FullScreenStage, PostChainError, PostImage, PostIo, PostStage, RenderError,
};

/// A full-screen pass from an effect's WGSL, which defines
/// `fn effect(pixel: vec2<u32>) -> vec4<f32>`: the value of output pixel `pixel`. It may read
/// `input` (a `texture_2d<f32>`, the image the effect reads, with `textureLoad`), call
/// `to_linear(rgb)` / `from_linear(rgb)` (what the stage's images hold to linear colour and
/// back: the sRGB curve on 8-bit display images, nothing elsewhere) and, when made
/// [`FullScreenPass::with_params`], read `params`, a read-only storage buffer of the WGSL struct
/// `EffectParams` (check its layout against the Rust struct with
/// [`crate::shader::check_wgsl_layout`]).
#[derive(Debug)]
pub struct FullScreenPass {
    /// The pipeline, or why the effect's WGSL does not compile.
    pipeline: Result<FullScreenPipeline, PostChainError>,
    layout: wgpu::BindGroupLayout,
    params: Option<wgpu::Buffer>,
    uploaded: Vec<u8>,
    /// Bind groups by the ids of the target and the images read and written.
    bind_groups: BindGroupCache<(u64, u64, u64)>,
    /// What the pass was made from, to make it again for a target of another format.
    source: EffectSource,
}

/// What a pass is made from.
#[derive(Debug)]
struct EffectSource {
    stage: PostStage,
    label: String,
    wgsl: String,
    params_size: u64,
    /// The format of the images it writes.
    format: wgpu::TextureFormat,
}

impl FullScreenPass {
    /// The pass of an effect of `stage` for `frame`'s target, from `effect_wgsl`.
    pub fn new(frame: FrameView<'_>, stage: PostStage, label: &str, effect_wgsl: &str) -> Self {
        Self::build(frame, stage, (label, effect_wgsl), 0)
    }

    /// [`FullScreenPass::new`] for an effect that reads `params` of type `P` (upload them
    /// with [`FullScreenPass::write_params`]).
    pub fn with_params<P: bytemuck::Pod>(
        frame: FrameView<'_>,
        stage: PostStage,
        label: &str,
        effect_wgsl: &str,
    ) -> Self {
        Self::build(frame, stage, (label, effect_wgsl), size_of::<P>() as u64)
    }

    fn build(
        frame: FrameView<'_>,
        stage: PostStage,
        (label, effect_wgsl): (&str, &str),
        params_size: u64,
    ) -> Self {
        let device = &frame.gpu.device;
        let format = image_format(frame, stage);
        let compute = compute_storage(frame, format);
        let mut entries = vec![layout::unfilterable_texture_2d(0)];
        if params_size > 0 {
            entries.push(layout::read_only_storage_buffer(1, params_size));
        }
        if compute.is_some() {
            entries.push(layout::compute_storage_texture(2, format));
        }
        let bind_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some(label),
            entries: &entries,
        });
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some(label),
            bind_group_layouts: &[Some(&bind_layout)],
            immediate_size: 0,
        });
        let source = effect_source(effect_wgsl, (format, compute), params_size > 0);
        let pipeline = check_effect(label, &source, effect_wgsl).map(|()| {
            let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
                label: Some(label),
                source: wgpu::ShaderSource::Wgsl(source.into()),
            });
            match compute {
                Some(_) => FullScreenPipeline::Compute(device.create_compute_pipeline(
                    &wgpu::ComputePipelineDescriptor {
                        label: Some(label),
                        layout: Some(&pipeline_layout),
                        module: &module,
                        entry_point: Some("effect_compute"),
                        compilation_options: Default::default(),
                        cache: None,
                    },
                )),
                None => FullScreenPipeline::Fragment(layout::fullscreen_pipeline(
                    device,
                    label,
                    Some(&pipeline_layout),
                    &module,
                    "effect_fragment",
                    format,
                )),
            }
        });
        let params = (params_size > 0).then(|| {
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: params_size,
                usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            })
        });
        Self {
            pipeline,
            layout: bind_layout,
            params,
            uploaded: Vec::new(),
            bind_groups: BindGroupCache::default(),
            source: EffectSource {
                stage,
                label: label.to_owned(),
                wgsl: effect_wgsl.to_owned(),
                params_size,
                format,
            },
        }
    }

    /// Makes the pass again when `frame`'s target stores another format than it was made for
    /// (its parameters are then uploaded again).
    fn follow(&mut self, frame: FrameView<'_>) {
        let source = &self.source;
        if image_format(frame, source.stage) != source.format {
            *self = Self::build(
                frame,
                source.stage,
                (&source.label.clone(), &source.wgsl.clone()),
                source.params_size,
            );
        }
    }

    /// Every shader a pass of `effect_wgsl` reading parameters `P` (`()`: none) may compile
    /// (each format of the chain's images, in compute and as a full-screen triangle), named,
    /// to validate an effect without a GPU.
    pub fn compositions<P: bytemuck::Pod>(effect_wgsl: &str) -> Vec<(String, String)> {
        let params = size_of::<P>() > 0;
        let formats = [
            wgpu::TextureFormat::Rgba8Unorm,
            wgpu::TextureFormat::Rgba16Float,
            wgpu::TextureFormat::Rgba32Float,
        ];
        formats
            .into_iter()
            .flat_map(|format| {
                [storage_format_name(format), None].map(|compute| {
                    let name = format!("post effect ({format:?}, {compute:?})");
                    (name, effect_source(effect_wgsl, (format, compute), params))
                })
            })
            .collect()
    }

    /// Whether the pass runs in compute (else as a full-screen triangle).
    pub fn is_compute(&self) -> bool {
        self.pipeline
            .as_ref()
            .is_ok_and(FullScreenPipeline::is_compute)
    }

    /// Uploads `params` if they changed (a pass made without parameters ignores them);
    /// returns the bytes written.
    pub fn write_params<P: bytemuck::Pod>(&mut self, frame: FrameView<'_>, params: &P) -> u64 {
        self.follow(frame);
        let bytes = bytemuck::bytes_of(params);
        match &self.params {
            Some(buffer) if self.uploaded != bytes && bytes.len() as u64 == buffer.size() => {
                frame.gpu.write_buffer(buffer, 0, bytes);
                self.uploaded = bytes.to_vec();
                bytes.len() as u64
            }
            _ => 0,
        }
    }

    /// Records the pass from `io.input` into `io.output` (nothing without an output); an
    /// effect whose WGSL does not compile records nothing and returns the error, each frame.
    pub fn record(
        &mut self,
        frame: FrameView<'_>,
        io: PostIo<'_>,
        encoder: &mut wgpu::CommandEncoder,
        time: Option<&PassTimestamps>,
    ) -> Result<(), RenderError> {
        let Some(output) = io.output else {
            return Ok(());
        };
        self.follow(frame);
        let pipeline = self.pipeline.as_ref().map_err(Clone::clone)?;
        let bind_group = Self::bind_group(
            (pipeline, &self.layout, self.params.as_ref()),
            &mut self.bind_groups,
            frame,
            (io.input, output),
        );
        pipeline.record(
            "post effect",
            encoder,
            (&bind_group, &output.view),
            frame.target.size(),
            time,
        );
        Ok(())
    }

    /// The bind group reading `input` and writing `output`, made unless `cache` has one.
    fn bind_group(
        (pipeline, layout, params): (
            &FullScreenPipeline,
            &wgpu::BindGroupLayout,
            Option<&wgpu::Buffer>,
        ),
        cache: &mut BindGroupCache<(u64, u64, u64)>,
        frame: FrameView<'_>,
        (input, output): (&PostImage, &PostImage),
    ) -> wgpu::BindGroup {
        // Groups of another target's images would keep them alive.
        let target = frame.target.id();
        cache.retain(|(id, _, _)| *id == target);
        cache.get_or_make((target, input.id, output.id), || {
            let mut entries = vec![wgpu::BindGroupEntry {
                binding: 0,
                resource: wgpu::BindingResource::TextureView(&input.view),
            }];
            if let Some(params) = params {
                entries.push(wgpu::BindGroupEntry {
                    binding: 1,
                    resource: params.as_entire_binding(),
                });
            }
            pipeline.bind_group(
                &frame.gpu.device,
                ("post effect", layout),
                entries,
                &output.view,
            )
        })
    }
}

/// Whether `source`, the whole shader composed around `effect`, compiles: its error names the
/// effect by `label` and the line in `effect` (the effect comes last in `source`).
fn check_effect(label: &str, source: &str, effect: &str) -> Result<(), PostChainError> {
    let effect_starts = source
        .lines()
        .count()
        .saturating_sub(effect.lines().count());
    let error = |line: Option<u32>, message: String| PostChainError::EffectShader {
        effect: label.to_owned(),
        line: line.map_or(0, |line| line.saturating_sub(effect_starts as u32)),
        message,
    };
    let module = naga::front::wgsl::parse_str(source).map_err(|parse| {
        error(
            parse.location(source).map(|at| at.line_number),
            parse.message().to_owned(),
        )
    })?;
    naga::valid::Validator::new(
        naga::valid::ValidationFlags::all(),
        naga::valid::Capabilities::all(),
    )
    .validate(&module)
    .map_err(|invalid| {
        error(
            invalid.location(source).map(|at| at.line_number),
            invalid.as_inner().to_string(),
        )
    })?;
    Ok(())
}

/// The format of the images an effect of `stage` writes on `frame`'s target.
fn image_format(frame: FrameView<'_>, stage: PostStage) -> wgpu::TextureFormat {
    match stage {
        PostStage::Hdr => frame.target.scene_format(),
        _ => frame.target.format(),
    }
}

/// The WGSL storage format a pass writing `format` on `frame` declares, where it runs in
/// compute (where the renderer runs full-screen work in compute and can store the format).
fn compute_storage(frame: FrameView<'_>, format: wgpu::TextureFormat) -> Option<&'static str> {
    let run_in = frame.resources.get::<crate::render::Renderer>().map_or(
        FullScreenStage::Fragment,
        crate::render::Renderer::full_screen_stage,
    );
    match (run_in, storage_format_name(format)) {
        (FullScreenStage::Compute, Some(name)) if frame.gpu.can_store(format) => Some(name),
        _ => None,
    }
}

/// The WGSL name of `format` as a storage texture's, for the formats the post chain's images
/// have.
fn storage_format_name(format: wgpu::TextureFormat) -> Option<&'static str> {
    match format {
        wgpu::TextureFormat::Rgba8Unorm => Some("rgba8unorm"),
        wgpu::TextureFormat::Rgba16Float => Some("rgba16float"),
        wgpu::TextureFormat::Rgba32Float => Some("rgba32float"),
        _ => None,
    }
}

/// The library's WGSL files an effect is composed with, besides [`shaders::SRGB`] and
/// [`shaders::FULLSCREEN_TRIANGLE`].
pub const EFFECT_FILES: [WgslFile; 3] = [EFFECT_HELPERS, EFFECT_COMPUTE, EFFECT_FRAGMENT];

/// `to_linear` and `from_linear`.
const EFFECT_HELPERS: WgslFile =
    crate::wgsl_file!(nested "render/full_screen_pass/effect_helpers.wgsl");
/// The compute entry point.
const EFFECT_COMPUTE: WgslFile =
    crate::wgsl_file!(nested "render/full_screen_pass/effect_compute.wgsl");
/// The full-screen triangle's entry point.
const EFFECT_FRAGMENT: WgslFile =
    crate::wgsl_file!(nested "render/full_screen_pass/effect_fragment.wgsl");

/// The whole shader of an effect writing `format`, in compute where `compute` names its
/// storage format: generated declarations, the helpers, the entry point, the effect.
fn effect_source(
    effect: &str,
    (format, compute): (wgpu::TextureFormat, Option<&str>),
    params: bool,
) -> String {
    let encoded = format == wgpu::TextureFormat::Rgba8Unorm;
    let mut source = format!(
        "@group(0) @binding(0) var input: texture_2d<f32>;\nconst ENCODED_SRGB: bool = {encoded};\n{}",
        crate::render::display_referred_wgsl()
    );
    if params {
        source.push_str("@group(0) @binding(1) var<storage, read> params: EffectParams;\n");
    }
    let files = match compute {
        Some(name) => {
            source.push_str(&format!(
                "@group(0) @binding(2) var output: texture_storage_2d<{name}, write>;\n"
            ));
            vec![shaders::SRGB, EFFECT_HELPERS, EFFECT_COMPUTE]
        }
        None => vec![
            shaders::SRGB,
            EFFECT_HELPERS,
            shaders::FULLSCREEN_TRIANGLE,
            EFFECT_FRAGMENT,
        ],
    };
    for file in files {
        source.push_str(file.source);
        source.push('\n');
    }
    source.push_str(effect);
    source
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::gpu::FULL_SCREEN_GROUP;

    #[test]
    fn the_dispatch_covers_the_shaders_workgroup() {
        assert!(EFFECT_COMPUTE.source.contains(&format!(
            "@workgroup_size({FULL_SCREEN_GROUP}, {FULL_SCREEN_GROUP}, 1)"
        )));
    }
}
