//! The temporal anti-aliasing pass (taa.wgsl): in compute, before tonemapping, the jittered
//! HDR scene and last frame's history into this frame's history, which tonemapping then reads.
//! Two histories per target take turns, each a colour texture (with the frames each pixel holds)
//! and a depth texture; what the pass does and when it resets is in temporal.rs.

use bytemuck::{Pod, Zeroable};

use super::object_motion::ObjectMotions;
use super::temporal::TemporalFrame;
use crate::gpu::{GpuContext, PassTimestamps, layout};
use crate::render::shaders::{ComposedShader, WgslFile};
use crate::render::{PostImage, RenderTarget};
use crate::shader::Choice;

/// The pass's WGSL file.
pub const TAA_ENTRY: WgslFile = crate::wgsl_file!(nested "render/anti_aliasing/taa.wgsl");

/// The side of TAA's square workgroup in pixels (taa.wgsl's `GROUP`).
const GROUP: u32 = 16;

/// The pass's shader.
pub const TAA_SHADER: ComposedShader = ComposedShader {
    name: "taa.wgsl",
    constants: &[
        crate::render::Tonemapping::wgsl_constants,
        crate::render::display_referred_wgsl,
    ],
    files: &[crate::render::tonemapping::TONEMAPPING, TAA_ENTRY],
};

/// The history's format: filterable, storable, and wide enough for the pre-exposed scene (rgb)
/// and the count of frames a pixel holds (a: whole numbers, exact in a half float).
pub const HISTORY_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba16Float;

/// The format of the view depth the history keeps for the next frame's disocclusion test.
const HISTORY_DEPTH_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::R32Float;

/// How TAA's uniform is used: bound twice, as a uniform and as storage where it alone chooses a
/// branch (taa.wgsl says why).
const UNIFORM_USAGE: wgpu::BufferUsages = wgpu::BufferUsages::UNIFORM
    .union(wgpu::BufferUsages::STORAGE)
    .union(wgpu::BufferUsages::COPY_DST);

/// One TAA frame as the shader reads it; mirrors `TaaUniform` in taa.wgsl.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct TaaUniform {
    /// Clip space of the jittered frame to world space.
    pub inverse_view_projection: [[f32; 4]; 4],
    /// World to clip space now, unjittered.
    pub view_projection: [[f32; 4]; 4],
    /// World to clip space a frame ago, unjittered.
    pub previous_view_projection: [[f32; 4]; 4],
    /// Eye position now.
    pub camera_position: [f32; 4],
    /// View direction now.
    pub view_direction: [f32; 4],
    /// Eye position a frame ago.
    pub previous_camera_position: [f32; 4],
    /// View direction a frame ago.
    pub previous_view_direction: [f32; 4],
    /// Frames in the history before this one (0: dropped).
    pub accumulated: u32,
    /// Least share of the new frame in a still pixel.
    pub still_weight: f32,
    /// Least share of the new frame in a pixel moving half a pixel or more.
    pub current_weight: f32,
    /// Half-width of the clip box in standard deviations.
    pub clip_gamma: f32,
    /// Relative depth difference past which the history is disoccluded.
    pub depth_tolerance: f32,
    /// `TONEMAP_*` code of the camera's operator (the history holds display values).
    pub tonemapping: u32,
    /// 1 where a draw moved since the last frame (the motion numbers are then written).
    pub object_motion: u32,
    /// Keeps the size a multiple of 16 bytes.
    pub _padding: u32,
}

crate::wgsl_layout!(TaaUniform {
    inverse_view_projection,
    view_projection,
    previous_view_projection,
    camera_position,
    view_direction,
    previous_camera_position,
    previous_view_direction,
    accumulated,
    still_weight,
    current_weight,
    clip_gamma,
    depth_tolerance,
    tonemapping,
    object_motion,
    _padding
});

impl TaaUniform {
    /// The uniform of `frame`, whose jittered projection is `jittered_view_projection`, with
    /// the motion numbers read where `object_motion` (a draw moved).
    pub fn new(
        frame: &TemporalFrame,
        jittered_view_projection: glam::Mat4,
        tonemapping: crate::render::Tonemapping,
        object_motion: bool,
    ) -> Self {
        let settings = frame.settings;
        Self {
            inverse_view_projection: jittered_view_projection.inverse().to_cols_array_2d(),
            view_projection: frame.current.view_projection.to_cols_array_2d(),
            previous_view_projection: frame.previous.view_projection.to_cols_array_2d(),
            camera_position: frame.current.position.extend(1.0).into(),
            view_direction: frame.current.direction.extend(0.0).into(),
            previous_camera_position: frame.previous.position.extend(1.0).into(),
            previous_view_direction: frame.previous.direction.extend(0.0).into(),
            accumulated: frame.accumulated,
            still_weight: settings.still_weight,
            current_weight: settings.current_weight,
            clip_gamma: settings.clip_gamma,
            depth_tolerance: settings.depth_tolerance,
            tonemapping: tonemapping.code(),
            object_motion: u32::from(object_motion),
            _padding: 0,
        }
    }
}

/// What one TAA frame reads besides the scene: its uniform, the frame's object motions and the
/// scene's depth ([`crate::render::FrameView::scene_depth`]).
pub(crate) struct TaaInputs<'a> {
    pub(crate) uniform: TaaUniform,
    pub(crate) motions: &'a ObjectMotions,
    pub(crate) scene_depth: &'a wgpu::TextureView,
}

/// The two histories of one target (colour and depth each), and the bind group that writes
/// each.
#[derive(Debug)]
struct HistoryTextures {
    target: u64,
    /// Each history's id as an image of the post chain.
    ids: [u64; 2],
    views: [wgpu::TextureView; 2],
    depth_views: [wgpu::TextureView; 2],
    /// The scene depth they bind, and `bind_groups[i]`, which reads history `1 - i` and writes
    /// history `i`.
    bind_groups: Option<(wgpu::TextureView, [wgpu::BindGroup; 2])>,
    /// The history the last frame wrote.
    written: usize,
}

/// The TAA pipeline, its uniform, and the history of the current target. Made on the first
/// TAA frame; the TAA effect's (mod.rs).
#[derive(Debug)]
pub(crate) struct TaaPass {
    pipeline: wgpu::ComputePipeline,
    layout: wgpu::BindGroupLayout,
    uniform: wgpu::Buffer,
    sampler: wgpu::Sampler,
    history: Option<HistoryTextures>,
    motion_layout: wgpu::BindGroupLayout,
    /// Group 1, the object motions, and the key of what it binds.
    motion_group: Option<((u64, u64, bool), wgpu::BindGroup)>,
}

impl TaaPass {
    pub(crate) fn new(gpu: &GpuContext) -> Self {
        let device = &gpu.device;
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("taa layout"),
            entries: &[
                layout::unfilterable_texture_2d(0),
                layout::unfilterable_texture_2d(1),
                layout::texture_2d(2),
                layout::filtering_sampler(3),
                layout::compute_storage_texture(4, HISTORY_FORMAT),
                layout::compute_uniform_buffer(5, false),
                layout::unfilterable_texture_2d(6),
                layout::compute_storage_texture(7, HISTORY_DEPTH_FORMAT),
                layout::compute_storage_buffer(8, true),
            ],
        });
        let motion_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("taa object motion layout"),
            entries: &[
                wgpu::BindGroupLayoutEntry {
                    binding: 0,
                    visibility: wgpu::ShaderStages::COMPUTE,
                    ty: wgpu::BindingType::Texture {
                        sample_type: wgpu::TextureSampleType::Uint,
                        view_dimension: wgpu::TextureViewDimension::D2,
                        multisampled: false,
                    },
                    count: None,
                },
                layout::compute_storage_buffer(1, true),
            ],
        });
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("taa pipeline layout"),
            bind_group_layouts: &[Some(&layout), Some(&motion_layout)],
            immediate_size: 0,
        });
        let module = TAA_SHADER.create_module(device);
        let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some("taa pipeline"),
            layout: Some(&pipeline_layout),
            module: &module,
            entry_point: Some("taa_main"),
            compilation_options: Default::default(),
            cache: None,
        });
        let uniform = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("taa uniform"),
            size: std::mem::size_of::<TaaUniform>() as u64,
            usage: UNIFORM_USAGE,
            mapped_at_creation: false,
        });
        let sampler = device.create_sampler(&wgpu::SamplerDescriptor {
            label: Some("taa history sampler"),
            mag_filter: wgpu::FilterMode::Linear,
            min_filter: wgpu::FilterMode::Linear,
            ..Default::default()
        });
        Self {
            pipeline,
            layout,
            uniform,
            sampler,
            history: None,
            motion_layout,
            motion_group: None,
        }
    }

    /// Group 1 for `motions`, made again only when what it binds changed.
    fn motion_group(&mut self, gpu: &GpuContext, motions: &ObjectMotions) -> &wgpu::BindGroup {
        let (ids, buffer, key) = motions.bindings();
        if self
            .motion_group
            .as_ref()
            .is_some_and(|(bound, _)| *bound != key)
        {
            self.motion_group = None;
        }
        let layout = &self.motion_layout;
        let (_, group) = self.motion_group.get_or_insert_with(|| {
            let group = gpu.device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("taa object motion bind group"),
                layout,
                entries: &[
                    wgpu::BindGroupEntry {
                        binding: 0,
                        resource: wgpu::BindingResource::TextureView(ids),
                    },
                    wgpu::BindGroupEntry {
                        binding: 1,
                        resource: buffer.as_entire_binding(),
                    },
                ],
            });
            (key, group)
        });
        group
    }

    /// Makes the history textures for `target` unless the current ones are for it; returns
    /// whether they are new (they then hold nothing to accumulate).
    fn follow(&mut self, gpu: &GpuContext, target: &RenderTarget) -> bool {
        if self
            .history
            .as_ref()
            .is_some_and(|history| history.target == target.id())
        {
            return false;
        }
        let view = |label, format| {
            crate::render::plain_texture(
                gpu,
                label,
                target.size(),
                format,
                wgpu::TextureUsages::TEXTURE_BINDING
                    | wgpu::TextureUsages::STORAGE_BINDING
                    | wgpu::TextureUsages::COPY_SRC,
            )
            .create_view(&wgpu::TextureViewDescriptor::default())
        };
        let views = ["taa history 0", "taa history 1"].map(|label| view(label, HISTORY_FORMAT));
        let depth_views = ["taa history depth 0", "taa history depth 1"]
            .map(|label| view(label, HISTORY_DEPTH_FORMAT));
        self.history = Some(HistoryTextures {
            target: target.id(),
            ids: [PostImage::new_id(), PostImage::new_id()],
            views,
            depth_views,
            bind_groups: None,
            written: 1,
        });
        true
    }

    /// The bind group that writes history `written` of `target`, reading `scene_depth`; made
    /// again where the scene depth changed.
    fn bind_group(
        &mut self,
        gpu: &GpuContext,
        target: &RenderTarget,
        scene_depth: &wgpu::TextureView,
        written: usize,
    ) -> Option<wgpu::BindGroup> {
        let history = self.history.as_mut()?;
        if let Some((bound, groups)) = &history.bind_groups
            && bound == scene_depth
        {
            return Some(groups[written].clone());
        }
        let (views, depth_views) = (&history.views, &history.depth_views);
        let bind_group = |written: usize| {
            let texture = |binding, view| wgpu::BindGroupEntry {
                binding,
                resource: wgpu::BindingResource::TextureView(view),
            };
            gpu.device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("taa bind group"),
                layout: &self.layout,
                entries: &[
                    texture(0, &target.scene_view),
                    texture(1, scene_depth),
                    texture(2, &views[1 - written]),
                    wgpu::BindGroupEntry {
                        binding: 3,
                        resource: wgpu::BindingResource::Sampler(&self.sampler),
                    },
                    texture(4, &views[written]),
                    wgpu::BindGroupEntry {
                        binding: 5,
                        resource: self.uniform.as_entire_binding(),
                    },
                    texture(6, &depth_views[1 - written]),
                    texture(7, &depth_views[written]),
                    wgpu::BindGroupEntry {
                        binding: 8,
                        resource: self.uniform.as_entire_binding(),
                    },
                ],
            })
        };
        let groups = [bind_group(0), bind_group(1)];
        let group = groups[written].clone();
        history.bind_groups = Some((scene_depth.clone(), groups));
        Some(group)
    }

    /// Records the pass for `target`; returns the history it writes, what the post chain reads
    /// next.
    pub(crate) fn record(
        &mut self,
        gpu: &GpuContext,
        target: &RenderTarget,
        TaaInputs {
            mut uniform,
            motions,
            scene_depth,
        }: TaaInputs<'_>,
        encoder: &mut wgpu::CommandEncoder,
        timestamps: Option<&PassTimestamps>,
    ) -> Option<PostImage> {
        if self.follow(gpu, target) {
            uniform.accumulated = 0;
        }
        gpu.write_buffer(&self.uniform, 0, bytemuck::bytes_of(&uniform));
        let motion_group = self.motion_group(gpu, motions).clone();
        let written = 1 - self.history.as_ref()?.written;
        let bind_group = self.bind_group(gpu, target, scene_depth, written)?;
        let history = self.history.as_mut()?;
        history.written = written;
        let (width, height) = target.size();
        {
            let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some("taa pass"),
                timestamp_writes: timestamps.map(PassTimestamps::compute),
            });
            pass.set_pipeline(&self.pipeline);
            pass.set_bind_group(0, &bind_group, &[]);
            pass.set_bind_group(1, &motion_group, &[]);
            pass.dispatch_workgroups(width.div_ceil(GROUP), height.div_ceil(GROUP), 1);
        }
        Some(PostImage {
            id: history.ids[written],
            view: history.views[written].clone(),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_uniform_matches_its_wgsl() {
        let layout =
            crate::shader::check_wgsl_layout::<TaaUniform>(&TAA_SHADER.source(), "TaaUniform");
        assert_eq!(layout, Ok(()));
    }

    #[test]
    fn the_dispatch_covers_the_shaders_workgroup() {
        let declaration = format!("const GROUP: i32 = {GROUP};");
        assert!(TAA_SHADER.source().contains(&declaration), "{declaration}");
    }
}
