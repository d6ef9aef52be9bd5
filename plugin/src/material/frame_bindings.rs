//! Group 0 of a material's pipelines: its layout (frame, transforms, uniforms, prepass depth,
//! shadow maps, visibility keys, the test counter) and the two bind groups made from it, one
//! for the passes that write depth (prepass, shadow maps) and one for those that shade.

use crate::gpu::GpuContext;
use crate::gpu::ObjectBuffer;
use crate::render::{
    BoundResources, EnvironmentMaps, FrameUniformBuffer, LightBuffers, MeshTransform,
    PhaseBindings, frame_group,
};

/// The buffers and textures group 0 binds.
struct FrameBindings<'a> {
    frame: &'a FrameUniformBuffer,
    transforms: &'a wgpu::Buffer,
    uniforms: &'a wgpu::Buffer,
    counter: Option<&'a wgpu::Buffer>,
    /// Whether the layout has the visibility keys (only a deferred shader's does: a writable
    /// fragment-stage buffer is an optional capability the forward path must not need).
    visibility_keys: bool,
}

/// Which depth textures a group 0 binds: the real ones where they are read, or the dummies
/// where they are being written.
#[derive(Clone, Copy, PartialEq)]
enum DepthUse {
    Shading,
    Writing,
}

fn frame_bind_group(
    gpu: &GpuContext,
    label: &str,
    layout: &wgpu::BindGroupLayout,
    bindings: &FrameBindings<'_>,
    depth: &PhaseBindings<'_>,
    depth_use: DepthUse,
) -> wgpu::BindGroup {
    let entry = |binding, resource| wgpu::BindGroupEntry { binding, resource };
    let (prepass_depth, shadow_maps, visibility) = match depth_use {
        DepthUse::Shading => (depth.opaque, depth.shadow_maps, depth.dummy_visibility),
        DepthUse::Writing => (depth.dummy, depth.dummy_shadow_maps, depth.visibility),
    };
    let mut entries = vec![
        entry(frame_group::FRAME, bindings.frame.binding()),
        entry(
            frame_group::TRANSFORMS,
            bindings.transforms.as_entire_binding(),
        ),
        entry(
            frame_group::MATERIAL_UNIFORMS,
            bindings.uniforms.as_entire_binding(),
        ),
        entry(
            frame_group::PREPASS_DEPTH,
            wgpu::BindingResource::TextureView(prepass_depth),
        ),
        entry(
            frame_group::SHADOW_VIEWS,
            depth.shadow_views.as_entire_binding(),
        ),
        entry(
            frame_group::SHADOW_MAPS,
            wgpu::BindingResource::TextureView(shadow_maps),
        ),
        entry(
            frame_group::SHADOW_SAMPLER,
            wgpu::BindingResource::Sampler(depth.shadow_sampler),
        ),
    ];
    entries.extend(depth.environment.entries());
    entries.extend(depth.lights.entries());
    if bindings.visibility_keys {
        for binding in [frame_group::VISIBILITY_KEYS, frame_group::VISIBILITY_WORDS] {
            entries.push(entry(binding, visibility.as_entire_binding()));
        }
    }
    if let Some(counter) = bindings.counter {
        entries.push(entry(
            frame_group::FRAGMENT_COUNTER,
            counter.as_entire_binding(),
        ));
    }
    gpu.device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some(label),
        layout,
        entries: &entries,
    })
}

/// Binding 3 of group 0: the prepass depth, read by materials that test their own depth.
fn prepass_depth_entry() -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding: frame_group::PREPASS_DEPTH,
        visibility: wgpu::ShaderStages::FRAGMENT,
        ty: wgpu::BindingType::Texture {
            sample_type: wgpu::TextureSampleType::Depth,
            view_dimension: wgpu::TextureViewDimension::D2,
            multisampled: false,
        },
        count: None,
    }
}

/// Bindings 5 to 7 of group 0: what receivers read of each shadow map, the maps, their
/// comparison sampler.
fn shadow_entries() -> [wgpu::BindGroupLayoutEntry; 3] {
    let visibility = wgpu::ShaderStages::FRAGMENT.union(wgpu::ShaderStages::COMPUTE);
    [
        wgpu::BindGroupLayoutEntry {
            binding: frame_group::SHADOW_VIEWS,
            visibility,
            ty: wgpu::BindingType::Buffer {
                ty: wgpu::BufferBindingType::Storage { read_only: true },
                has_dynamic_offset: false,
                min_binding_size: None,
            },
            count: None,
        },
        wgpu::BindGroupLayoutEntry {
            binding: frame_group::SHADOW_MAPS,
            visibility,
            ty: wgpu::BindingType::Texture {
                sample_type: wgpu::TextureSampleType::Depth,
                view_dimension: wgpu::TextureViewDimension::D2Array,
                multisampled: false,
            },
            count: None,
        },
        wgpu::BindGroupLayoutEntry {
            binding: frame_group::SHADOW_SAMPLER,
            visibility,
            ty: wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Comparison),
            count: None,
        },
    ]
}

/// Bindings 8 and 9 of group 0: the visibility keys the deferred path's prepass merges into,
/// and the same buffer as words, read for the depth each pixel has kept.
fn visibility_entries() -> [wgpu::BindGroupLayoutEntry; 2] {
    [frame_group::VISIBILITY_KEYS, frame_group::VISIBILITY_WORDS].map(|binding| {
        wgpu::BindGroupLayoutEntry {
            binding,
            visibility: wgpu::ShaderStages::FRAGMENT,
            ty: wgpu::BindingType::Buffer {
                ty: wgpu::BufferBindingType::Storage { read_only: false },
                has_dynamic_offset: false,
                min_binding_size: wgpu::BufferSize::new(crate::render::VISIBILITY_BYTES_PER_PIXEL),
            },
            count: None,
        }
    })
}

/// Binding 4 of group 0: the fragment invocation counter.
fn counter_entry() -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding: frame_group::FRAGMENT_COUNTER,
        visibility: wgpu::ShaderStages::FRAGMENT,
        ty: wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Storage { read_only: false },
            has_dynamic_offset: false,
            min_binding_size: wgpu::BufferSize::new(4),
        },
        count: None,
    }
}

/// A material's group-0 layout and its two bind groups, remade when a buffer they hold grows or
/// the target, shadow maps or visibility buffer change.
pub(crate) struct FrameBindGroups {
    label: &'static str,
    layout: wgpu::BindGroupLayout,
    /// For the prepass and the shadow maps (the depth textures being written are dummies).
    writing: wgpu::BindGroup,
    /// For the shading passes and the deferred resolve.
    shading: wgpu::BindGroup,
    bound: BoundResources,
    /// The fragment invocation counter (tests), bound at binding 4 when present.
    counter: Option<wgpu::Buffer>,
    visibility_keys: bool,
}

/// The per-draw buffers group 0 binds besides the frame's.
pub(crate) struct DrawBuffers<'a> {
    pub(crate) frame: &'a FrameUniformBuffer,
    pub(crate) transforms: &'a wgpu::Buffer,
    pub(crate) uniforms: &'a wgpu::Buffer,
}

/// The two groups of `layout` over `bindings`: for the passes that write depth, and for those
/// that shade.
fn writing_and_shading(
    gpu: &GpuContext,
    label: &str,
    layout: &wgpu::BindGroupLayout,
    bindings: &FrameBindings<'_>,
    depth: &PhaseBindings<'_>,
) -> (wgpu::BindGroup, wgpu::BindGroup) {
    let group = |depth_use| frame_bind_group(gpu, label, layout, bindings, depth, depth_use);
    (group(DepthUse::Writing), group(DepthUse::Shading))
}

impl FrameBindGroups {
    /// The layout for a material whose per-draw uniforms are laid out by `uniforms_entry`
    /// (binding 2), with the visibility keys where its shader is the `deferred` one, and the
    /// bind groups for `buffers` and `depth`.
    pub(crate) fn new(
        gpu: &GpuContext,
        label: &'static str,
        uniforms_entry: wgpu::BindGroupLayoutEntry,
        (deferred, counter): (bool, Option<wgpu::Buffer>),
        buffers: &DrawBuffers<'_>,
        depth: &PhaseBindings<'_>,
    ) -> Self {
        let mut entries = vec![
            FrameUniformBuffer::layout_entry(),
            ObjectBuffer::<MeshTransform>::layout_entry(frame_group::TRANSFORMS),
            uniforms_entry,
            prepass_depth_entry(),
        ];
        entries.extend(shadow_entries());
        entries.extend(EnvironmentMaps::layout_entries());
        entries.extend(LightBuffers::layout_entries());
        if deferred {
            entries.extend(visibility_entries());
        }
        if counter.is_some() {
            entries.push(counter_entry());
        }
        let layout = gpu
            .device
            .create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
                label: Some(&format!("{label} frame layout")),
                entries: &entries,
            });
        let bindings = FrameBindings {
            frame: buffers.frame,
            transforms: buffers.transforms,
            uniforms: buffers.uniforms,
            counter: counter.as_ref(),
            visibility_keys: deferred,
        };
        let (writing, shading) = writing_and_shading(gpu, label, &layout, &bindings, depth);
        Self {
            label,
            layout,
            writing,
            shading,
            bound: depth.bound,
            counter,
            visibility_keys: deferred,
        }
    }

    /// Remakes both bind groups when `grew` (a buffer was replaced) or `depth` belongs to
    /// another target, shadow-map texture or visibility buffer.
    pub(crate) fn refresh(
        &mut self,
        gpu: &GpuContext,
        buffers: &DrawBuffers<'_>,
        depth: &PhaseBindings<'_>,
        grew: bool,
    ) {
        if !grew && self.bound == depth.bound {
            return;
        }
        let bindings = FrameBindings {
            frame: buffers.frame,
            transforms: buffers.transforms,
            uniforms: buffers.uniforms,
            counter: self.counter.as_ref(),
            visibility_keys: self.visibility_keys,
        };
        (self.writing, self.shading) =
            writing_and_shading(gpu, self.label, &self.layout, &bindings, depth);
        self.bound = depth.bound;
    }

    /// The layout, for pipeline layouts.
    pub(crate) fn layout(&self) -> &wgpu::BindGroupLayout {
        &self.layout
    }

    /// The group of the passes that write depth: the prepass and the shadow maps.
    pub(crate) fn writing(&self) -> &wgpu::BindGroup {
        &self.writing
    }

    /// The group of the passes that shade, and of the deferred resolve.
    pub(crate) fn shading(&self) -> &wgpu::BindGroup {
        &self.shading
    }
}
