//! Errors no error scope catches are kept for `GpuContext::take_uncaptured_errors`, up to a
//! bound: an app that never asks for them and repeats an error every frame does not grow.

use pom::gpu::MAX_KEPT_ERRORS;
use pom::{App, RenderPlugin};

#[test]
fn uncaptured_errors_are_kept_up_to_a_bound_and_the_rest_counted() {
    let mut app = App::new();
    app.add_plugin(RenderPlugin::new(8, 8));
    app.finish().unwrap();
    let gpu = app.resources.get::<pom::GpuContext>().unwrap();
    let empty_texture = |label| wgpu::TextureDescriptor {
        label: Some(label),
        size: wgpu::Extent3d {
            width: 0,
            height: 1,
            depth_or_array_layers: 1,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format: wgpu::TextureFormat::Rgba8Unorm,
        usage: wgpu::TextureUsages::TEXTURE_BINDING,
        view_formats: &[],
    };
    let made = MAX_KEPT_ERRORS + 36;
    for _ in 0..made {
        drop(
            gpu.device
                .create_texture(&empty_texture("an empty texture")),
        );
    }
    let errors = gpu.take_uncaptured_errors();
    assert_eq!(errors.len(), MAX_KEPT_ERRORS + 1, "{errors:?}");
    assert!(errors[0].contains("an empty texture"), "{}", errors[0]);
    assert_eq!(
        errors[MAX_KEPT_ERRORS],
        format!("36 more errors past the first {MAX_KEPT_ERRORS} (logged, not kept)")
    );
    assert!(gpu.take_uncaptured_errors().is_empty(), "taken and cleared");
    drop(gpu.device.create_texture(&empty_texture("one more")));
    assert_eq!(gpu.take_uncaptured_errors().len(), 1);
}
