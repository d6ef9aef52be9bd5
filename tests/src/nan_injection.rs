//! A NaN written into one pixel of the HDR scene every frame, for tests that check it does
//! not spread (through TAA's history, say).

use pom::render::{RenderPhase, RenderPhases, RenderTarget};
use pom::{App, GpuContext};

/// A pipeline that writes NaN into one pixel of the scene target (scissored).
struct NanInjector {
    pipeline: pom::wgpu::RenderPipeline,
    pixel: (u32, u32),
}

fn inject_nan(resources: &pom::Resources, encoder: &mut pom::wgpu::CommandEncoder) {
    let (Some(injector), Some(target)) = (
        resources.get::<NanInjector>(),
        resources.get::<RenderTarget>(),
    ) else {
        return;
    };
    let mut pass = encoder.begin_render_pass(&pom::wgpu::RenderPassDescriptor {
        label: Some("nan injection"),
        color_attachments: &[Some(pom::wgpu::RenderPassColorAttachment {
            view: &target.scene_view,
            depth_slice: None,
            resolve_target: None,
            ops: pom::wgpu::Operations {
                load: pom::wgpu::LoadOp::Load,
                store: pom::wgpu::StoreOp::Store,
            },
        })],
        depth_stencil_attachment: None,
        timestamp_writes: None,
        occlusion_query_set: None,
        multiview_mask: None,
    });
    pass.set_pipeline(&injector.pipeline);
    pass.set_scissor_rect(injector.pixel.0, injector.pixel.1, 1, 1);
    pass.draw(0..3, 0..1);
}

/// Makes every frame of `app` write NaN into `pixel` of its HDR scene, after every draw (as
/// work of the transparent phase): what a broken shader or a bad texture could leave there.
pub fn inject_nan_at(app: &mut App, pixel: (u32, u32)) {
    let (device, format) = {
        let gpu = app.resources.get::<GpuContext>().unwrap();
        (
            gpu.device.clone(),
            app.resources.get::<RenderTarget>().unwrap().scene_format(),
        )
    };
    let module = device.create_shader_module(pom::wgpu::ShaderModuleDescriptor {
        label: Some("nan"),
        source: pom::wgpu::ShaderSource::Wgsl(
            "@vertex fn vs(@builtin(vertex_index) i: u32) -> @builtin(position) vec4<f32> {
                 let c = vec2<f32>(f32((i << 1u) & 2u), f32(i & 2u));
                 return vec4<f32>(c * 2.0 - 1.0, 0.0, 1.0);
             }
             @fragment fn fs() -> @location(0) vec4<f32> {
                 let nan = bitcast<f32>(0x7fc00000u);
                 return vec4<f32>(nan, nan, nan, 1.0);
             }"
            .into(),
        ),
    });
    let pipeline = device.create_render_pipeline(&pom::wgpu::RenderPipelineDescriptor {
        label: Some("nan"),
        layout: None,
        vertex: pom::wgpu::VertexState {
            module: &module,
            entry_point: Some("vs"),
            compilation_options: Default::default(),
            buffers: &[],
        },
        primitive: Default::default(),
        depth_stencil: None,
        multisample: Default::default(),
        fragment: Some(pom::wgpu::FragmentState {
            module: &module,
            entry_point: Some("fs"),
            compilation_options: Default::default(),
            targets: &[Some(format.into())],
        }),
        multiview_mask: None,
        cache: None,
    });
    app.resources.insert(NanInjector { pipeline, pixel });
    app.resources
        .get_mut::<RenderPhases>()
        .unwrap()
        .add_work::<NanInjector>(RenderPhase::Transparent, inject_nan);
}
