//! The MaxMip method: the maximum pyramid the GPU derives against the CPU reference's, for
//! every channel, convention and size, and rebuilt when a dynamic height field changes.

use pom::reference::MaxPyramid;
use pom::{GpuContext, HeightField, Image, TextureKind, patterns};

/// The GPU's pyramid of `image` (height in `channel`, `depth` convention) equals the CPU
/// reference's of the field the image holds, level by level.
fn assert_pyramid_matches(gpu: &GpuContext, image: Image, channel: u8, depth: bool) {
    let field = HeightField::from_image(&image, usize::from(channel), depth);
    let reference = MaxPyramid::new(&field);
    let levels = pom::render::read_max_pyramid(gpu, image, channel, depth).unwrap();
    assert_eq!(levels.len(), reference.level_count());
    for (level, (width, height, maxima)) in levels.iter().enumerate() {
        for y in 0..*height {
            for x in 0..*width {
                let gpu = maxima[(y * width + x) as usize];
                let cpu = reference.max_at(level, i64::from(x), i64::from(y));
                // 16-bit unorm decodes within an ulp of the CPU's division.
                assert!(
                    (gpu - cpu).abs() < 1e-6,
                    "channel {channel}, depth {depth}, level {level} ({x}, {y}): GPU {gpu}, CPU {cpu}"
                );
            }
        }
    }
}

#[test]
fn the_gpu_pyramid_equals_the_cpu_reference_for_every_channel_and_convention() {
    let gpu = GpuContext::headless().unwrap();
    let cobbles = patterns::cobblestones(64, 4).quantized();
    assert_pyramid_matches(&gpu, cobbles.to_image(), 0, false);
    assert_pyramid_matches(&gpu, cobbles.to_image(), 0, true);
    // A 16-bit map whose sides are not powers of two: 48 × 40 halves three times.
    let cones = patterns::cones(48, 3.0);
    let npot = HeightField::new(
        48,
        40,
        (0..48 * 40).map(|i| cones.texel(i % 48, i / 48)).collect(),
    )
    .unwrap();
    assert_pyramid_matches(&gpu, npot.to_image_16(), 0, false);
    // Height in the alpha of a normal map, as a depth map; red, green and blue hold other
    // values that must not leak in.
    let rgba: Vec<u8> = (0..64 * 64)
        .flat_map(|i: i64| {
            let height = (cobbles.texel(i % 64, i / 64) * 255.0).round() as u8;
            [(i % 251) as u8, 255 - height, 17, height]
        })
        .collect();
    let packed = Image::from_rgba8(64, 64, rgba, TextureKind::Normal).unwrap();
    assert_pyramid_matches(&gpu, packed.clone(), 3, false);
    assert_pyramid_matches(&gpu, packed, 3, true);
}

/// The `uv` debug view of max-mip on a 32² plane seen at 50°, after `change` rewrote the
/// heights (a dynamic height field's every frame).
#[test]
fn the_pyramid_follows_rewritten_heights() {
    use pom::preview::PreviewView;
    use pom::{Assets, DebugView, HeightSource, ParallaxMethod, ParallaxOcclusionMaterial};
    use pom::{ShadowMode, TargetFormat};
    use pom_tests::pom_scene::{HeightMaterial, preview_app};

    let floor = HeightField::new(16, 16, vec![0.0; 256]).unwrap();
    let textures = HeightMaterial {
        field: floor,
        height_scale: 0.05,
    };
    let view = PreviewView {
        view_angle: 50.0,
        ..PreviewView::default()
    };
    let mut app = preview_app(32, TargetFormat::Float32, &textures, &view, |material| {
        ParallaxOcclusionMaterial {
            method: ParallaxMethod::MaxMip,
            debug_view: DebugView::Uv,
            shadows: ShadowMode::Off,
            lod_threshold: 16.0,
            ..material
        }
    })
    .unwrap();
    let on_the_floor = pom_tests::render_and_capture_f32(&mut app).unwrap();
    // Raise the whole field to the top: a pyramid left at the floor's maxima would let every
    // ray fall through to the floor again.
    let height = {
        let mut query = app.world.query::<&ParallaxOcclusionMaterial>();
        let material = query.iter().next().unwrap();
        let Some(HeightSource::Texture(height)) = &material.height_map else {
            panic!("the preview's height has its own texture");
        };
        height.clone()
    };
    *app.resources
        .get_mut::<Assets<Image>>()
        .unwrap()
        .get_mut(&height)
        .unwrap() = HeightField::new(16, 16, vec![1.0; 256]).unwrap().to_image();
    let at_the_top = pom_tests::render_and_capture_f32(&mut app).unwrap();
    set_method(&mut app, ParallaxMethod::NormalMapping);
    let entry = pom_tests::render_and_capture_f32(&mut app).unwrap();
    let mut moved = 0;
    for ((top, floor), entry) in at_the_top
        .pixels()
        .zip(on_the_floor.pixels())
        .zip(entry.pixels())
    {
        assert_eq!(
            top.0[..2],
            entry.0[..2],
            "at the top the ray stops where it enters"
        );
        moved += usize::from(floor.0[..2] != entry.0[..2]);
    }
    assert!(
        moved > 32 * 32 / 2,
        "on the floor the rays travel ({moved} pixels moved)"
    );
}

fn set_method(app: &mut pom::App, method: pom::ParallaxMethod) {
    for material in app
        .world
        .query_mut::<&mut pom::ParallaxOcclusionMaterial>()
        .into_iter()
    {
        material.method = method;
    }
}
