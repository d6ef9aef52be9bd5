//! The MaxMip method: the maximum pyramid the GPU derives against the CPU reference's, for
//! every channel, convention and size, and rebuilt when a dynamic height field changes.

use pom::reference::MaxPyramid;
use pom::{Channel, GpuContext, HeightConvention, HeightField, Image, TextureKind, patterns};

/// The GPU's pyramid of `image` (height in `channel`, `depth` convention) equals the CPU
/// reference's of the field the image holds, level by level.
fn assert_pyramid_matches(
    gpu: &GpuContext,
    image: Image,
    channel: Channel,
    convention: HeightConvention,
) {
    let field = HeightField::from_image(&image, channel, convention);
    let reference = MaxPyramid::new(&field);
    let levels = pom::parallax::read_max_pyramid(gpu, image, channel, convention).unwrap();
    assert_eq!(levels.len(), reference.level_count());
    for (level, (width, height, maxima)) in levels.iter().enumerate() {
        for y in 0..*height {
            for x in 0..*width {
                let gpu = maxima[(y * width + x) as usize];
                let cpu = reference.max_at(level, i64::from(x), i64::from(y));
                // 16-bit unorm decodes within an ulp of the CPU's division.
                assert!(
                    (gpu - cpu).abs() < 1e-6,
                    "{channel:?} {convention:?}, level {level} ({x}, {y}): GPU {gpu}, CPU {cpu}"
                );
            }
        }
    }
}

#[test]
fn the_gpu_pyramid_equals_the_cpu_reference_for_every_channel_and_convention() {
    let gpu = GpuContext::headless().unwrap();
    let cobbles = patterns::cobblestones(64, 4).quantized();
    assert_pyramid_matches(
        &gpu,
        cobbles.to_image(),
        Channel::Red,
        HeightConvention::Height,
    );
    assert_pyramid_matches(
        &gpu,
        cobbles.to_image(),
        Channel::Red,
        HeightConvention::Depth,
    );
    // A 16-bit map whose sides are not powers of two: 48 × 40 halves three times.
    let cones = patterns::cones(48, 3.0);
    let npot = HeightField::new(
        48,
        40,
        (0..48 * 40).map(|i| cones.texel(i % 48, i / 48)).collect(),
    )
    .unwrap();
    assert_pyramid_matches(
        &gpu,
        npot.to_image_16(),
        Channel::Red,
        HeightConvention::Height,
    );
    // Height in the alpha of a normal map, as a depth map; red, green and blue hold other
    // values that must not leak in.
    let rgba: Vec<u8> = (0..64 * 64)
        .flat_map(|i: i64| {
            let height = (cobbles.texel(i % 64, i / 64) * 255.0).round() as u8;
            [(i % 251) as u8, 255 - height, 17, height]
        })
        .collect();
    let packed = Image::from_rgba8(64, 64, rgba, TextureKind::Normal).unwrap();
    assert_pyramid_matches(
        &gpu,
        packed.clone(),
        Channel::Alpha,
        HeightConvention::Height,
    );
    assert_pyramid_matches(&gpu, packed, Channel::Alpha, HeightConvention::Depth);
}

/// The `uv` debug view of max-mip on a 32² plane seen at 50°, after `change` rewrote the
/// heights (a dynamic height field's every frame).
#[test]
fn the_pyramid_follows_rewritten_heights() {
    use pom::preview::PreviewView;
    use pom::{Assets, HeightSource, ParallaxMethod, ParallaxOcclusionMaterial};
    use pom_tests::pom_scene::{HeightMaterial, uv_app};

    let floor = HeightField::new(16, 16, vec![0.0; 256]).unwrap();
    let textures = HeightMaterial {
        field: floor,
        height_scale: 0.05,
    };
    let view = PreviewView {
        view_angle: 50.0,
        ..PreviewView::default()
    };
    let mut app = uv_app(32, &textures, &view, ParallaxMethod::MaxMip).unwrap();
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
    pom_tests::pom_scene::set_material(app, |material| material.method = method);
}

/// For each pixel of the `uv` views `entry` (normal mapping: where the ray enters) and
/// `marched` (max-mip), the GPU's hit, the CPU reference's from the same entry seen along
/// +u at `angle` degrees, and the distance between them in texels (wrapping).
fn gpu_and_cpu_hits(
    field: &HeightField,
    height_scale: f32,
    angle: f32,
    entry: &image::Rgba32FImage,
    marched: &image::Rgba32FImage,
) -> Vec<(pom::glam::Vec2, pom::glam::Vec2, f32)> {
    use pom::glam::{Vec2, Vec3};
    let pyramid = MaxPyramid::new(field);
    let radians = angle.to_radians();
    let to_eye = Vec3::new(-radians.sin(), 0.0, radians.cos());
    let (width, height) = field.size();
    let size = Vec2::new(width as f32, height as f32);
    let wrapped = pom_tests::pom_scene::wrapped;
    entry
        .pixels()
        .zip(marched.pixels())
        .map(|(entry, gpu)| {
            let uv = Vec2::new(entry.0[0], entry.0[1]);
            let gpu = Vec2::new(gpu.0[0], gpu.0[1]);
            let cpu = pom::reference::march_max_mip(&pyramid, uv, to_eye, height_scale).uv;
            let difference = Vec2::new(wrapped(gpu.x - cpu.x), wrapped(gpu.y - cpu.y));
            (uv, cpu, (difference * size).length())
        })
        .collect()
}

/// Max-mip's hard shadows on the GPU against the CPU reference: thin spikes (one texel at the
/// top every 16 over a floor at 0.2), seen from straight above, lit from 75° along −u.
#[test]
fn gpu_hard_shadows_match_the_cpu_reference_on_thin_spikes() {
    use pom::glam::{Vec2, Vec3};
    use pom::preview::{PreviewProjection, PreviewView};
    use pom::{DebugView, ParallaxMethod, ParallaxOcclusionMaterial, ShadowMode, TargetFormat};
    use pom_tests::pom_scene::{HeightMaterial, preview_app};

    const SIZE: u32 = 64;
    const HEIGHT_SCALE: f32 = 0.05;
    let field = patterns::spikes(64, 16, 0.2);
    let textures = HeightMaterial {
        field: field.clone(),
        height_scale: HEIGHT_SCALE,
    };
    let view = PreviewView {
        view_angle: 0.0,
        light_angle: 75.0,
        light_azimuth: 0.0,
        projection: PreviewProjection::Orthographic,
        ..PreviewView::default()
    };
    let render = |method, debug_view| {
        let mut app = preview_app(SIZE, TargetFormat::Float32, &textures, &view, |material| {
            ParallaxOcclusionMaterial {
                method,
                shadows: ShadowMode::Hard,
                debug_view,
                lod_threshold: 16.0,
                ..material
            }
        })
        .unwrap();
        pom_tests::render_and_capture_f32(&mut app).unwrap()
    };
    let shadow = render(ParallaxMethod::MaxMip, DebugView::Shadow);
    let uv = render(ParallaxMethod::MaxMip, DebugView::Uv);
    let pyramid = MaxPyramid::new(&field);
    let radians = 75.0_f32.to_radians();
    let to_light = Vec3::new(-radians.sin(), 0.0, radians.cos());
    let light_offset = pom::reference::ray_offset(to_light, HEIGHT_SCALE);
    let (mut agree, mut shadowed) = (0, 0);
    for (gpu_shadow, gpu_uv) in shadow.pixels().zip(uv.pixels()) {
        let at = Vec2::new(gpu_uv.0[0], gpu_uv.0[1]);
        let cpu = pom::reference::max_mip_hard_shadow(&pyramid, at, light_offset);
        agree += usize::from(gpu_shadow.0[0] == cpu);
        shadowed += usize::from(cpu == 0.0);
    }
    let pixels = (SIZE * SIZE) as usize;
    eprintln!("max-mip hard shadows: GPU = CPU at {agree} of {pixels} pixels, {shadowed} shadowed");
    assert!(shadowed > 64, "{shadowed} shadowed pixels");
    assert!(
        agree * 100 >= pixels * 99,
        "GPU = CPU at {agree} of {pixels}"
    );
}

/// A pyramid lives while draws use it: built when max-mip is chosen, freed once the last draw
/// that used it switched to another method, built again when one switches back.
#[test]
fn an_unused_pyramid_is_freed() {
    use pom::preview::PreviewView;
    use pom::render::Renderer;
    use pom::{ParallaxMethod, ParallaxOcclusionMaterial, TargetFormat};
    use pom_tests::pom_scene::{HeightMaterial, preview_app};

    let textures = HeightMaterial {
        field: patterns::cones(32, 2.0),
        height_scale: 0.05,
    };
    let mut app = preview_app(
        16,
        TargetFormat::Srgb8,
        &textures,
        &PreviewView::default(),
        |m| ParallaxOcclusionMaterial {
            method: ParallaxMethod::MaxMip,
            ..m
        },
    )
    .unwrap();
    let held = |app: &pom::App| {
        app.resources
            .get::<Renderer>()
            .unwrap()
            .derived_texture_count()
    };
    pom_tests::run_frames(&mut app, 3).unwrap();
    assert_eq!(held(&app), 1);
    set_method(&mut app, ParallaxMethod::Occlusion);
    pom_tests::run_frames(&mut app, 2).unwrap();
    assert_eq!(held(&app), 0);
    set_method(&mut app, ParallaxMethod::MaxMip);
    pom_tests::run_frames(&mut app, 1).unwrap();
    assert_eq!(held(&app), 1);
}

/// Rays that cross the map several times (85°, height scale 0.25: about 3 repetitions): the
/// GPU's wrapping of far cells agrees with the CPU reference.
#[test]
fn long_rays_across_several_repetitions_match_the_cpu_reference() {
    use pom::ParallaxMethod;
    use pom::preview::{PreviewProjection, PreviewView};
    use pom_tests::pom_scene::{HeightMaterial, uv_view};

    const HEIGHT_SCALE: f32 = 0.25;
    // A wall across u at height 0.6 on a floor: the rays (91 texels long) pass over its first
    // copies and meet it one to three repetitions on, where only wrapping finds it.
    let field = HeightField::from_fn(32, 32, |u, _| {
        if (20.0..22.0).contains(&(u * 32.0)) {
            0.6
        } else {
            0.0
        }
    });
    let textures = HeightMaterial {
        field: field.clone(),
        height_scale: HEIGHT_SCALE,
    };
    let view = PreviewView {
        view_angle: 85.0,
        projection: PreviewProjection::Orthographic,
        ..PreviewView::default()
    };
    let entry = uv_view(48, &textures, &view, ParallaxMethod::NormalMapping).unwrap();
    let marched = uv_view(48, &textures, &view, ParallaxMethod::MaxMip).unwrap();
    let hits = gpu_and_cpu_hits(&field, HEIGHT_SCALE, 85.0, &entry, &marched);
    let mean = hits.iter().map(|(_, _, apart)| apart).sum::<f32>() / hits.len() as f32;
    let travelled = hits
        .iter()
        .map(|(uv, cpu, _)| ((*cpu - *uv) * 32.0).length())
        .fold(0.0_f32, f32::max);
    eprintln!("long rays: mean |GPU − CPU| {mean:.4} texel, longest {travelled:.0} texels");
    assert!(
        travelled > 64.0,
        "some rays cross the map twice ({travelled})"
    );
    assert!(mean <= 0.25, "{mean} texels");
}

/// A material whose textures' sampler clamps (as a glTF sampler may): max-mip still marches the
/// repeating field across the map's seam, as the CPU reference and the pyramid do. The field
/// rises along u, so the patch across the seam drops from 0.7 to 0.2, and a clamp would hold
/// 0.7: seen at 80°, rays from the map's last texels hit that patch.
#[test]
fn a_clamping_height_sampler_still_wraps_across_the_seam() {
    use pom::preview::{PreviewProjection, PreviewView};
    use pom::{Assets, ImageSampler, ParallaxMethod, WrapMode};
    use pom_tests::pom_scene::{HeightMaterial, uv_app};

    const HEIGHT_SCALE: f32 = 0.1;
    let field = HeightField::from_fn(64, 64, |u, v| 0.2 + 0.5 * u + 0.2 * v).quantized();
    let textures = HeightMaterial {
        field: field.clone(),
        height_scale: HEIGHT_SCALE,
    };
    let view = PreviewView {
        view_angle: 80.0,
        projection: PreviewProjection::Orthographic,
        ..PreviewView::default()
    };
    let clamp = ImageSampler {
        wrap_u: WrapMode::ClampToEdge,
        wrap_v: WrapMode::ClampToEdge,
        ..ImageSampler::default()
    };
    let [entry, marched] = [ParallaxMethod::NormalMapping, ParallaxMethod::MaxMip].map(|method| {
        let mut app = uv_app(64, &textures, &view, method).unwrap();
        // The material samples with its first texture's sampler: clamp them all.
        for (_, image) in app.resources.get_mut::<Assets<Image>>().unwrap().iter_mut() {
            *image = image.clone().with_sampler(clamp);
        }
        pom_tests::render_and_capture_f32(&mut app).unwrap()
    });
    let hits = gpu_and_cpu_hits(&field, HEIGHT_SCALE, 80.0, &entry, &marched);
    let largest = hits.iter().map(|(_, _, apart)| *apart).fold(0.0, f32::max);
    eprintln!("clamping sampler: largest |GPU − CPU| {largest:.5} texel");
    assert!(largest <= 0.05, "{largest} texels");
}

/// For each pixel of the bricks' `uv` views (`entry`: normal mapping, where the ray enters;
/// `marched`: max-mip) seen at `angle` degrees along +u, how far the GPU's and the CPU
/// reference's hits are from the exact one: (largest in texels, its pixel, pixels off by more
/// than a texel), the GPU's first.
fn errors_against_the_exact_hit(
    field: &HeightField,
    height_scale: f32,
    angle: f32,
    entry: &image::Rgba32FImage,
    marched: &image::Rgba32FImage,
) -> [(f32, (u32, u32), usize); 2] {
    use pom::glam::{Vec2, Vec3};
    use pom_tests::pom_scene::wrapped;
    let radians = angle.to_radians();
    let to_eye = Vec3::new(-radians.sin(), 0.0, radians.cos());
    let pyramid = MaxPyramid::new(field);
    let size = Vec2::splat(field.size().0 as f32);
    let texels_apart =
        |a: Vec2, b: Vec2| (Vec2::new(wrapped(a.x - b.x), wrapped(a.y - b.y)) * size).length();
    let mut worst = [(0.0_f32, (0, 0), 0); 2];
    for (x, y, entry_pixel) in entry.enumerate_pixels() {
        let uv = Vec2::new(entry_pixel.0[0], entry_pixel.0[1]);
        let exact = pom::reference::exact_intersection(field, uv, to_eye, height_scale);
        let gpu = Vec2::from_slice(&marched.get_pixel(x, y).0[..2]);
        let cpu = pom::reference::march_max_mip(&pyramid, uv, to_eye, height_scale).uv;
        for (worst, hit) in worst.iter_mut().zip([gpu, cpu]) {
            let apart = texels_apart(hit, exact);
            worst.2 += usize::from(apart > 1.0);
            if apart > worst.0 {
                (worst.0, worst.1) = (apart, (x, y));
            }
        }
    }
    worst
}

/// The shipped bricks (256², white = top, a plateau at exactly 1 on every brick) in the `uv`
/// debug view of a 256² orthographic image at 60° and 80° along +u: image rows fall on
/// texel-centre columns, so whole rows of rays enter on the top plane at a brick's rim, touch
/// the field there and pass above the drop after it. On every pixel the GPU's and the CPU
/// reference's hits are the exact intersection: the largest error, not the mean, shows a ray
/// stopped at a touch. (Not at 88°: there a 256-texel ray passes 5·10⁻⁷ above a texel-centre
/// kink, which the fragment's own view vector, a rounding away from the one given here, meets.)
#[test]
fn max_mip_is_exact_on_every_pixel_of_the_bricks_at_grazing_angles() {
    use pom::preview::{PreviewProjection, PreviewView};
    use pom::{Channel, ParallaxMethod};
    use pom_tests::pom_scene::{HeightMaterial, uv_view};

    const HEIGHT_SCALE: f32 = 0.05;
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets/bricks/height.png");
    let field = HeightField::from_image(
        &Image::load_height(path, Channel::Red).unwrap(),
        Channel::Red,
        HeightConvention::Height,
    );
    let textures = HeightMaterial {
        field: field.clone(),
        height_scale: HEIGHT_SCALE,
    };
    for angle in [60.0, 80.0] {
        let view = PreviewView {
            view_angle: angle,
            projection: PreviewProjection::Orthographic,
            ..PreviewView::default()
        };
        let entry = uv_view(256, &textures, &view, ParallaxMethod::NormalMapping).unwrap();
        let marched = uv_view(256, &textures, &view, ParallaxMethod::MaxMip).unwrap();
        let worst = errors_against_the_exact_hit(&field, HEIGHT_SCALE, angle, &entry, &marched);
        for (name, (largest, at, off)) in ["GPU", "CPU"].into_iter().zip(worst) {
            eprintln!(
                "bricks at {angle}°: largest |{name} − exact| {largest:.4} texel at pixel {at:?}, {off} pixels off by more than a texel"
            );
        }
        for (name, (largest, at, _)) in ["GPU", "CPU"].into_iter().zip(worst) {
            assert!(
                largest <= 0.05,
                "{angle}°, {name}: {largest} texels at pixel {at:?}"
            );
        }
    }
}
