//! The MaxMip method: the maximum pyramid the GPU derives against the CPU reference's.

use pom::reference::MaxPyramid;
use pom::{GpuContext, HeightField, patterns};

#[test]
fn the_gpu_pyramid_equals_the_cpu_reference_for_every_channel_and_convention() {
    let gpu = GpuContext::headless().unwrap();
    let field = patterns::cobblestones(64, 4).quantized();
    let reference = MaxPyramid::new(&field);
    let levels = pom::render::read_max_pyramid(&gpu, field.to_image(), 0, false).unwrap();
    assert_eq!(levels.len(), reference.level_count());
    for (level, (width, height, maxima)) in levels.iter().enumerate() {
        for y in 0..*height {
            for x in 0..*width {
                let gpu = maxima[(y * width + x) as usize];
                let cpu = reference.max_at(level, i64::from(x), i64::from(y));
                assert!(
                    (gpu - cpu).abs() < 1e-6,
                    "level {level} ({x}, {y}): GPU {gpu}, CPU {cpu}"
                );
            }
        }
    }
}
