//! MaxMip's maximum pyramid rebuilt every frame, as under a dynamic height field whose heights
//! change each frame: the GPU time of the build (the frame's `derived textures` pass) for the
//! bench's height map and for a large one. The build depends on neither the image size nor the
//! path: it is timed once per path, at the run's first size.

use anyhow::Result;
use pom::gpu::DERIVED_TEXTURES_PASS;
use pom::{
    Channel, HeightConvention, HeightField, Image, ParallaxMethod, ParallaxOcclusionMaterial,
};

use super::Runner;
use super::scene::{BenchScene, SceneOptions};
use crate::preview_textures::PreviewTextures;

/// The side of the large map timed beside the bench's own: the largest height map in common use.
const LARGE_MAP: u32 = 4096;
/// Its side under `--quick`, which only checks the harness.
const QUICK_LARGE_MAP: u32 = 2048;

impl Runner<'_> {
    /// The build's milliseconds per frame for the bench's height map and, where that is
    /// smaller, a large one, each recorded as a case of the group `pyramid_build`.
    pub(super) fn pyramid_builds(&mut self, size: (u32, u32), quick: bool) -> Result<()> {
        let material = ParallaxOcclusionMaterial {
            method: ParallaxMethod::MaxMip,
            ..self.base.clone()
        };
        let large_side = if quick { QUICK_LARGE_MAP } else { LARGE_MAP };
        let (own_width, own_height) = self.textures.height.size();
        // A map already that large is timed on its own. The large one is made once per run.
        if own_width.max(own_height) < large_side && self.large_height_map.is_none() {
            self.large_height_map = Some(tiled(&self.textures.height, large_side));
        }
        let large = self.large_height_map.clone().map(|height| PreviewTextures {
            height,
            ..self.textures.clone()
        });
        for textures in std::iter::once(self.textures.clone()).chain(large) {
            let (width, height) = textures.height.size();
            let options = SceneOptions::timed_plane(size, self.path);
            let mut scene = BenchScene::new(options, &textures, material.clone(), &self.view)?;
            let times = scene.time_rewritten_heights(self.warmup, self.frames)?;
            let variant = format!("{width}x{height} map");
            let row = (scene.path_ran(), DERIVED_TEXTURES_PASS, variant);
            let place = (size, self.view.tiling);
            self.record("pyramid_build", place, &material, row, &times)?;
        }
        Ok(())
    }
}

/// `height`'s red channel repeated over `side` × `side` texels, at 16 bits (as a dynamic
/// height field stores it).
fn tiled(height: &Image, side: u32) -> Image {
    let field = HeightField::from_image(height, Channel::Red, HeightConvention::Height);
    let texel = |coordinate: f32| (coordinate * side as f32) as i64;
    HeightField::from_fn(side, side, |u, v| field.texel(texel(u), texel(v))).to_image_16()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_tiled_map_repeats_the_source_texel_for_texel() {
        let source = HeightField::from_fn(4, 2, |u, v| u * 0.5 + v * 0.25);
        let big = HeightField::from_image(
            &tiled(&source.to_image_16(), 8),
            Channel::Red,
            HeightConvention::Height,
        );
        assert_eq!(big.size(), (8, 8));
        for (x, y) in [(0, 0), (5, 1), (7, 6), (2, 3)] {
            let expected = source.texel(x, y);
            assert!((big.texel(x, y) - expected).abs() < 1e-4, "({x}, {y})");
        }
    }
}
