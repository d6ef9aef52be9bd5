//! The render pipelines of mesh materials: one per pass a material draws in ([`MeshPass`]).

use crate::gpu::ShaderEntry;

/// Which pass a mesh pipeline draws in, which sets its depth state and colour target.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub(crate) enum MeshPass {
    /// The depth prepass: depth tested `Less` and written, no colour.
    Prepass,
    /// The deferred path's prepass: as the prepass, its fragments also merging each pixel's id
    /// into the visibility buffer (a storage buffer: no colour target).
    Visibility,
    /// The deferred path's candidate pass, after the opaque phase: depth tested `Less` against
    /// the visibility pass and written, the polygon's depth merged into the candidate keys
    /// (`fs_visibility_candidate`) for the resolve to settle.
    Candidate,
    /// After the deferred resolve, the candidates' polygons again: depth compared `Always`
    /// and written, each pixel's settled depth (`fs_settled_depth`).
    SettledDepth,
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

impl MeshPass {
    /// Whether the pass writes depth, and how it compares.
    fn depth_test(self) -> (bool, wgpu::CompareFunction) {
        match self {
            MeshPass::Prepass
            | MeshPass::Visibility
            | MeshPass::Candidate
            | MeshPass::Shadow
            | MeshPass::Opaque => (true, wgpu::CompareFunction::Less),
            MeshPass::SettledDepth => (true, wgpu::CompareFunction::Always),
            MeshPass::OpaqueAfterPrepass | MeshPass::Transparent | MeshPass::Motion => {
                (false, wgpu::CompareFunction::LessEqual)
            }
        }
    }
}

/// The candidate pass's fragment entry (candidates.wgsl).
pub(crate) const CANDIDATE_ENTRY: &str = "fs_visibility_candidate";
/// The settled depth's fragment entry (candidates.wgsl, composed only by materials whose
/// surface leaves their polygon).
pub(crate) const SETTLED_DEPTH_ENTRY: &str = "fs_settled_depth";

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

/// The render pipeline every mesh material uses: interleaved [`crate::gpu::Vertex`] input
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
    let (depth_write, depth_compare) = pass.depth_test();
    let color_targets = [Some(wgpu::ColorTargetState {
        format: match pass {
            MeshPass::Motion => crate::render::MOTION_ID_FORMAT,
            _ => color_format,
        },
        blend: (pass == MeshPass::Transparent)
            .then(|| over_blend(device, color_format))
            .flatten(),
        write_mask: wgpu::ColorWrites::ALL,
    })];

    let targets: &[Option<wgpu::ColorTargetState>] = match pass {
        MeshPass::Prepass
        | MeshPass::Visibility
        | MeshPass::Candidate
        | MeshPass::SettledDepth
        | MeshPass::Shadow => &[],
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
            buffers: &[Some(crate::gpu::Vertex::LAYOUT)],
        },
        primitive: wgpu::PrimitiveState {
            cull_mode,
            ..Default::default()
        },
        depth_stencil: Some(wgpu::DepthStencilState {
            format: if pass == MeshPass::Shadow {
                crate::render::SHADOW_MAP_FORMAT
            } else {
                crate::render::DEPTH_FORMAT
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
