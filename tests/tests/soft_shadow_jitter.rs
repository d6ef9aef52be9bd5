//! The soft self-shadow under TAA: its seven samples move a per-pixel, per-frame part of their
//! spacing along the light ray, so the settled penumbra of the bricks under a grazing light
//! nears the shadow of many samples (the CPU reference) instead of keeping seven steps. Without
//! TAA the samples stay Tatarchuk's. Both paths; each test prints what it measured.

use image::{Rgba32FImage, RgbaImage};
use pom::glam::{Vec2, Vec3};
use pom::preview::PreviewView;
use pom::reference::{ray_offset, soft_shadow, soft_shadow_many_taps};
use pom::{
    AntiAliasing, App, DebugView, ParallaxMethod, ParallaxOcclusionMaterial, RenderPath,
    TargetFormat, patterns,
};
use pom_tests::anti_aliasing::{save_for_looking, set_anti_aliasing};
use pom_tests::pom_scene::{HeightMaterial, preview_app, uv_view};
use pom_tests::{render_on_path_f32, run_frames, set_path};

/// Side of the images: the view shows a fifth of the brick tile around a joint.
const SIZE: u32 = 128;
/// TAA frames the shadow settles over: two cycles of the sub-pixel jitter, within the plain
/// mean the history keeps while still.
const FRAMES: usize = 32;
/// Shifts per sample spacing of the many-sample reference (7 × 16 samples along the ray).
const REFERENCE_SHIFTS: u32 = 16;
/// Sub-pixel positions per axis the CPU images average over a pixel, as TAA's jitter does.
const PIXEL_SUBSAMPLES: u32 = 4;

fn bricks() -> HeightMaterial {
    HeightMaterial {
        field: patterns::bricks(256, 4.0, 8.0),
        height_scale: 0.05,
    }
}

/// Straight down at the bricks (the view ray meets the polygon where it enters), lit as the
/// README's sun lights them (55° from the normal, diagonally across the rows), a texel about
/// 2.5 pixels wide as there: the shadows' edges run askew to the texels and the pixels.
fn view() -> PreviewView {
    PreviewView {
        light_angle: 55.0,
        light_azimuth: 45.0,
        distance: 0.2,
        ..PreviewView::default()
    }
}

/// The parallax soft shadow's visibility (the shadow debug view) of the first light.
fn shadow_app() -> App {
    preview_app(
        SIZE,
        TargetFormat::Float32,
        &bricks(),
        &view(),
        |material| ParallaxOcclusionMaterial {
            debug_view: DebugView::Shadow,
            lod_threshold: 16.0,
            ..material
        },
    )
    .unwrap()
}

/// The shadow on `path` with `mode`: TAA after [`FRAMES`] frames, the others after one.
fn rendered_shadow(path: RenderPath, mode: AntiAliasing) -> Vec<f32> {
    let mut app = shadow_app();
    set_path(&mut app, path);
    set_anti_aliasing(&mut app, mode);
    if mode == AntiAliasing::Taa {
        run_frames(&mut app, FRAMES - 1).unwrap();
    }
    let image = render_on_path_f32(&mut app, path).unwrap();
    image.pixels().map(|pixel| pixel.0[0]).collect()
}

/// Where each pixel's centre meets the plane, and how the texture coordinate moves one pixel
/// right and one down (the view is orthographic and straight: the same everywhere).
struct PixelGrid {
    uv: Rgba32FImage,
    across: Vec2,
    down: Vec2,
}

impl PixelGrid {
    fn new() -> Self {
        let uv = uv_view(SIZE, &bricks(), &view(), ParallaxMethod::Occlusion).unwrap();
        let at = |x, y| {
            let pixel: &image::Rgba<f32> = uv.get_pixel(x, y);
            Vec2::new(pixel.0[0], pixel.0[1])
        };
        let last = SIZE - 1;
        let across = (at(last, 0) - at(0, 0)) / last as f32;
        let down = (at(0, last) - at(0, 0)) / last as f32;
        Self { uv, across, down }
    }

    fn centre(&self, x: u32, y: u32) -> Vec2 {
        let pixel = self.uv.get_pixel(x, y).0;
        Vec2::new(pixel[0], pixel[1])
    }

    /// `visibility` at each pixel, averaged over [`PIXEL_SUBSAMPLES`]² places in it.
    fn averaged(&self, visibility: impl Fn(Vec2) -> f32) -> Vec<f32> {
        let n = PIXEL_SUBSAMPLES;
        let places: Vec<Vec2> = (0..n * n)
            .map(|i| {
                let (sx, sy) = ((i % n) as f32, (i / n) as f32);
                self.across * ((sx + 0.5) / n as f32 - 0.5)
                    + self.down * ((sy + 0.5) / n as f32 - 0.5)
            })
            .collect();
        (0..SIZE * SIZE)
            .map(|i| {
                let centre = self.centre(i % SIZE, i / SIZE);
                places
                    .iter()
                    .map(|&place| visibility(centre + place))
                    .sum::<f32>()
                    / places.len() as f32
            })
            .collect()
    }
}

/// The light's offset in texture space (`ray_offset` of its tangent-space direction): the plane
/// runs u along world +X, v along +Z, its normal +Y.
fn light_offset() -> Vec2 {
    let to_light = view().light_transform().translation.normalize();
    ray_offset(
        Vec3::new(to_light.x, to_light.z, to_light.y),
        bricks().height_scale,
    )
}

/// The penumbra: pixels with a pixel of the reference strictly between lit and shadowed in
/// their 3 × 3 neighbourhood.
fn penumbra(reference: &[f32]) -> Vec<usize> {
    let partial = |x: i64, y: i64| {
        let inside = (0..i64::from(SIZE)).contains(&x) && (0..i64::from(SIZE)).contains(&y);
        inside && {
            let value = reference[(y * i64::from(SIZE) + x) as usize];
            value > 0.02 && value < 0.98
        }
    };
    (0..SIZE * SIZE)
        .filter(|&i| {
            let (x, y) = (i64::from(i % SIZE), i64::from(i / SIZE));
            (-1..=1).any(|dy| (-1..=1).any(|dx| partial(x + dx, y + dy)))
        })
        .map(|i| i as usize)
        .collect()
}

/// The part of `image`'s error against `reference` that changes from pixel to pixel along the
/// edge (the steps): the error less its mean over the 5 × 5 neighbourhood, averaged over `pixels`.
fn step_error(image: &[f32], reference: &[f32], pixels: &[usize]) -> f32 {
    let error = |x: i64, y: i64| {
        let (x, y) = (
            x.clamp(0, i64::from(SIZE) - 1),
            y.clamp(0, i64::from(SIZE) - 1),
        );
        let i = (y * i64::from(SIZE) + x) as usize;
        image[i] - reference[i]
    };
    pixels
        .iter()
        .map(|&i| {
            let (x, y) = ((i as u32 % SIZE) as i64, (i as u32 / SIZE) as i64);
            let local: f32 = (-2..=2)
                .flat_map(|dy| (-2..=2).map(move |dx| (dx, dy)))
                .map(|(dx, dy)| error(x + dx, y + dy))
                .sum::<f32>()
                / 25.0;
            (error(x, y) - local).abs()
        })
        .sum::<f32>()
        / pixels.len() as f32
}

/// The mean absolute error of `image` against `reference` over `pixels`.
fn mean_error(image: &[f32], reference: &[f32], pixels: &[usize]) -> f32 {
    pixels
        .iter()
        .map(|&i| (image[i] - reference[i]).abs())
        .sum::<f32>()
        / pixels.len() as f32
}

/// Writes a visibility image, grey, under target/anti-aliasing/ for a person to look at.
fn save_shadow(name: &str, visibility: &[f32]) {
    let image = RgbaImage::from_fn(SIZE, SIZE, |x, y| {
        let value = (visibility[(y * SIZE + x) as usize].clamp(0.0, 1.0) * 255.0).round() as u8;
        image::Rgba([value, value, value, 255])
    });
    save_for_looking(&format!("soft-shadow-{name}"), &image);
}

#[test]
fn under_taa_the_soft_shadow_settles_nearer_many_samples_than_seven_steps() {
    let grid = PixelGrid::new();
    let field = bricks().field.quantized();
    let offset = light_offset();
    let softening = ParallaxOcclusionMaterial::default().shadow_softening;
    let reference =
        grid.averaged(|uv| soft_shadow_many_taps(&field, uv, offset, softening, REFERENCE_SHIFTS));
    // What TAA settles to with the samples where Tatarchuk puts them: the seven steps, averaged
    // over the pixel only.
    let seven_steps = grid.averaged(|uv| soft_shadow(&field, uv, offset, softening, 0.0));
    let pixels = penumbra(&reference);
    assert!(pixels.len() > 500, "only {} penumbra pixels", pixels.len());
    let steps_error = mean_error(&seven_steps, &reference, &pixels);
    let steps_step_error = step_error(&seven_steps, &reference, &pixels);
    save_shadow("reference", &reference);
    save_shadow("seven-steps", &seven_steps);
    for path in [RenderPath::Forward, RenderPath::Deferred] {
        let settled = rendered_shadow(path, AntiAliasing::Taa);
        assert!(settled.iter().all(|v| v.is_finite()), "{path:?}: a NaN");
        let error = mean_error(&settled, &reference, &pixels);
        let settled_step_error = step_error(&settled, &reference, &pixels);
        save_shadow(&format!("taa-{path:?}"), &settled);
        eprintln!(
            "{path:?}: {} penumbra pixels against {} samples: TAA settled: mean error \
             {error:.4}, steps {settled_step_error:.4}; the seven samples: mean error \
             {steps_error:.4}, steps {steps_step_error:.4}",
            pixels.len(),
            7 * REFERENCE_SHIFTS,
        );
        // Every finite set of samples along the ray finds a blocker's edge a little past where
        // it is (the strongest sample is the first beyond the edge), so the settled penumbra is
        // lighter than the reference's as the seven samples' is on average: the steps are what
        // the moving samples take away, the mean error only must not grow.
        assert!(
            settled_step_error <= 0.75 * steps_step_error,
            "{path:?}: steps: TAA settled {settled_step_error}, the seven samples {steps_step_error}"
        );
        assert!(
            error <= steps_error,
            "{path:?}: mean error: TAA settled {error}, the seven samples {steps_error}"
        );
    }
}

#[test]
fn without_taa_the_samples_stay_where_tatarchuk_puts_them() {
    let grid = PixelGrid::new();
    let field = bricks().field.quantized();
    let offset = light_offset();
    let softening = ParallaxOcclusionMaterial::default().shadow_softening;
    let expected: Vec<f32> = (0..SIZE * SIZE)
        .map(|i| {
            soft_shadow(
                &field,
                grid.centre(i % SIZE, i / SIZE),
                offset,
                softening,
                0.0,
            )
        })
        .collect();
    let all: Vec<usize> = (0..expected.len()).collect();
    for path in [RenderPath::Forward, RenderPath::Deferred] {
        let rendered = rendered_shadow(path, AntiAliasing::Off);
        let error = mean_error(&rendered, &expected, &all);
        eprintln!(
            "{path:?}, no anti-aliasing: mean visibility error against the CPU's seven samples {error:.5}"
        );
        // Bilinear weights of a few bits on the GPU: a few ten-thousandths apart.
        assert!(error < 0.002, "{path:?}: {error}");
    }
}
