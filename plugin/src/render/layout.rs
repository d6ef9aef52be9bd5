//! Bind group layout entries the material passes share, and the entry point of a pipeline
//! variant ([`ShaderEntry`]).

/// The entry point (fragment, or compute for a deferred resolve) and pipeline-overridable
/// constants of one pipeline variant.
#[derive(Clone, Debug, PartialEq)]
pub struct ShaderEntry {
    /// The `@fragment` or `@compute` function.
    pub entry_point: &'static str,
    /// Values of the shader's `override` constants.
    pub constants: Vec<(&'static str, f64)>,
}

impl ShaderEntry {
    /// `entry_point` with no constants.
    pub fn entry(entry_point: &'static str) -> Self {
        Self {
            entry_point,
            constants: Vec::new(),
        }
    }
}

/// A filterable float 2D texture visible to the fragment stage and the deferred resolve.
pub(crate) fn texture_2d(binding: u32) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::FRAGMENT.union(wgpu::ShaderStages::COMPUTE),
        ty: wgpu::BindingType::Texture {
            sample_type: wgpu::TextureSampleType::Float { filterable: true },
            view_dimension: wgpu::TextureViewDimension::D2,
            multisampled: false,
        },
        count: None,
    }
}

/// A float 2D texture read with `textureLoad` (no sampler), visible to the fragment stage and
/// compute: `R32Float` and other unfilterable formats bind here.
pub(crate) fn unfilterable_texture_2d(binding: u32) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        ty: wgpu::BindingType::Texture {
            sample_type: wgpu::TextureSampleType::Float { filterable: false },
            view_dimension: wgpu::TextureViewDimension::D2,
            multisampled: false,
        },
        ..texture_2d(binding)
    }
}

/// A write-only 2D storage texture of `format` for a compute pass.
pub(crate) fn compute_storage_texture(
    binding: u32,
    format: wgpu::TextureFormat,
) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::COMPUTE,
        ty: wgpu::BindingType::StorageTexture {
            access: wgpu::StorageTextureAccess::WriteOnly,
            format,
            view_dimension: wgpu::TextureViewDimension::D2,
        },
        count: None,
    }
}

/// A read-only storage buffer of at least `size` bytes for a full-screen pass (compute or
/// fragment): settings that steer branches (post_process.wgsl says why not a uniform).
pub(crate) fn read_only_storage_buffer(binding: u32, size: u64) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::COMPUTE | wgpu::ShaderStages::FRAGMENT,
        ty: wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Storage { read_only: true },
            has_dynamic_offset: false,
            min_binding_size: wgpu::BufferSize::new(size),
        },
        count: None,
    }
}

/// A filtering sampler visible to the fragment stage and the deferred resolve.
pub(crate) fn filtering_sampler(binding: u32) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::FRAGMENT.union(wgpu::ShaderStages::COMPUTE),
        ty: wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Filtering),
        count: None,
    }
}

/// A uniform buffer of the deferred path's compute passes, at a dynamic offset or not.
pub(crate) fn compute_uniform_buffer(
    binding: u32,
    dynamic_offset: bool,
) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::COMPUTE,
        ty: wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Uniform,
            has_dynamic_offset: dynamic_offset,
            min_binding_size: None,
        },
        count: None,
    }
}

/// A storage buffer of the deferred path's compute passes, read-only or not.
pub(crate) fn compute_storage_buffer(binding: u32, read_only: bool) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::COMPUTE,
        ty: wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Storage { read_only },
            has_dynamic_offset: false,
            min_binding_size: None,
        },
        count: None,
    }
}

/// A full-screen pass's pipeline: `fullscreen_vertex` (fullscreen_triangle.wgsl, composed into
/// `shader`) and the fragment entry `fragment_entry` writing one `format` target, no depth.
/// `layout: None` derives the layout from the shader.
pub(crate) fn fullscreen_pipeline(
    device: &wgpu::Device,
    label: &str,
    layout: Option<&wgpu::PipelineLayout>,
    shader: &wgpu::ShaderModule,
    fragment_entry: &str,
    format: wgpu::TextureFormat,
) -> wgpu::RenderPipeline {
    device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some(label),
        layout,
        vertex: wgpu::VertexState {
            module: shader,
            entry_point: Some("fullscreen_vertex"),
            compilation_options: Default::default(),
            buffers: &[],
        },
        primitive: Default::default(),
        depth_stencil: None,
        multisample: Default::default(),
        fragment: Some(wgpu::FragmentState {
            module: shader,
            entry_point: Some(fragment_entry),
            compilation_options: Default::default(),
            targets: &[Some(format.into())],
        }),
        multiview_mask: None,
        cache: None,
    })
}

/// Which pass a mesh pipeline draws in, which sets its depth state and colour target.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub(crate) enum MeshPass {
    /// The depth prepass: depth tested `Less` and written, no colour.
    Prepass,
    /// The deferred path's prepass: as the prepass, its fragments also merging each pixel's id
    /// into the visibility buffer (a storage buffer: no colour target).
    Visibility,
    /// A shadow map: as the prepass, from a light's view, into the shadow-map format.
    Shadow,
    /// The opaque phase after a prepass: depth tested `LessEqual` against it, never written.
    OpaqueAfterPrepass,
    /// The opaque phase of a frame without prepass: depth tested `Less` and written.
    Opaque,
    /// The transparent phase: depth tested `LessEqual`, never written, colour blended.
    Transparent,
    /// TAA's object motion pass (`vs_motion`, `fs_motion`): depth tested `LessEqual`, never
    /// written, into the motion numbers.
    Motion,
}

/// "Over" blending of a straight-alpha colour; the destination keeps its alpha (which marks
/// display-referred pixels for post-processing). `None`, with a warning, where the target's
/// format cannot blend (`Rgba32Float` without `FLOAT32_BLENDABLE`): the surface is then drawn
/// opaque.
fn over_blend(device: &wgpu::Device, format: wgpu::TextureFormat) -> Option<wgpu::BlendState> {
    let blendable = format != wgpu::TextureFormat::Rgba32Float
        || device
            .features()
            .contains(wgpu::Features::FLOAT32_BLENDABLE);
    if !blendable {
        log::warn!(
            "the {format:?} scene target cannot blend on this adapter: transparent surfaces are drawn opaque"
        );
        return None;
    }
    Some(wgpu::BlendState {
        color: wgpu::BlendComponent {
            src_factor: wgpu::BlendFactor::SrcAlpha,
            dst_factor: wgpu::BlendFactor::OneMinusSrcAlpha,
            operation: wgpu::BlendOperation::Add,
        },
        alpha: wgpu::BlendComponent {
            src_factor: wgpu::BlendFactor::Zero,
            dst_factor: wgpu::BlendFactor::One,
            operation: wgpu::BlendOperation::Add,
        },
    })
}

/// What varies between the render pipelines of mesh materials.
#[derive(Clone, Copy)]
pub(crate) struct MeshPipelineDescriptor<'a> {
    /// The pipeline's label.
    pub(crate) label: &'a str,
    /// The material's pipeline layout.
    pub(crate) layout: &'a wgpu::PipelineLayout,
    /// The material's shader.
    pub(crate) shader: &'a wgpu::ShaderModule,
    /// Which pass it draws in: sets the depth state and whether there is a colour target.
    pub(crate) pass: MeshPass,
    /// The entry point and its constants; `None`: no fragment stage (prepass only).
    pub(crate) fragment: Option<&'a ShaderEntry>,
    /// The scene target's format.
    pub(crate) color_format: wgpu::TextureFormat,
    /// The material's: back faces, or none when double-sided.
    pub(crate) cull_mode: Option<wgpu::Face>,
}

/// The render pipeline every mesh material uses: interleaved [`super::Vertex`] input
/// (`vs_main`) and what `descriptor` says.
pub(crate) fn mesh_pipeline(
    device: &wgpu::Device,
    descriptor: &MeshPipelineDescriptor<'_>,
) -> wgpu::RenderPipeline {
    let MeshPipelineDescriptor {
        label,
        layout,
        shader,
        pass,
        fragment,
        color_format,
        cull_mode,
    } = *descriptor;
    let (depth_write, depth_compare) = match pass {
        MeshPass::Prepass | MeshPass::Visibility | MeshPass::Shadow | MeshPass::Opaque => {
            (true, wgpu::CompareFunction::Less)
        }
        MeshPass::OpaqueAfterPrepass | MeshPass::Transparent | MeshPass::Motion => {
            (false, wgpu::CompareFunction::LessEqual)
        }
    };
    let color_targets = [Some(wgpu::ColorTargetState {
        format: match pass {
            MeshPass::Motion => super::MOTION_ID_FORMAT,
            _ => color_format,
        },
        blend: (pass == MeshPass::Transparent)
            .then(|| over_blend(device, color_format))
            .flatten(),
        write_mask: wgpu::ColorWrites::ALL,
    })];

    let targets: &[Option<wgpu::ColorTargetState>] = match pass {
        MeshPass::Prepass | MeshPass::Visibility | MeshPass::Shadow => &[],
        _ => &color_targets,
    };
    device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some(label),
        layout: Some(layout),
        vertex: wgpu::VertexState {
            module: shader,
            entry_point: Some(if pass == MeshPass::Motion {
                "vs_motion"
            } else {
                "vs_main"
            }),
            compilation_options: Default::default(),
            buffers: &[Some(super::gpu_types::Vertex::LAYOUT)],
        },
        primitive: wgpu::PrimitiveState {
            cull_mode,
            ..Default::default()
        },
        depth_stencil: Some(wgpu::DepthStencilState {
            format: if pass == MeshPass::Shadow {
                super::SHADOW_MAP_FORMAT
            } else {
                super::target::DEPTH_FORMAT
            },
            depth_write_enabled: Some(depth_write),
            depth_compare: Some(depth_compare),
            stencil: Default::default(),
            bias: Default::default(),
        }),
        multisample: Default::default(),
        fragment: fragment.map(|fragment| wgpu::FragmentState {
            module: shader,
            entry_point: Some(fragment.entry_point),
            compilation_options: wgpu::PipelineCompilationOptions {
                constants: &fragment.constants,
                ..Default::default()
            },
            targets,
        }),
        multiview_mask: None,
        cache: None,
    })
}
