//! What terrain layers and triplanar mapping cost, at the bench material's samples: on the bench
//! plane, the material against its own height map as the only layer of a layered material, as
//! four layers tiled alike (one fetch a march step reads them all) and as four tiled apart (a
//! fetch each), every layer showing everywhere; on the preview sphere, triplanar mapping against
//! its texture coordinates.

use anyhow::Result;
use pom::preview::{PreviewShape, PreviewView};
use pom::{
    Channel, HeightConvention, HeightField, Image, LayerWeights, ParallaxLayer, ParallaxLayers,
    ParallaxOcclusionMaterial, TextureKind, TextureMapping,
};

use super::Runner;

/// The four layers' tilings when they tile apart (each over the plane's own repeats).
const APART: [f32; 4] = [1.0, 1.25, 1.5, 2.0];

/// A weight map in which every one of four layers has a share everywhere, waves of each
/// crossing the plane a different way.
fn mixed_weights() -> Result<Image> {
    let side = 256;
    let pixels = image::RgbaImage::from_fn(side, side, |x, y| {
        let (u, v) = (x as f32 / side as f32, y as f32 / side as f32);
        let wave =
            |a: f32, b: f32| (96.0 + 80.0 * (std::f32::consts::TAU * (a * u + b * v)).sin()) as u8;
        image::Rgba([
            wave(2.0, 0.0),
            wave(0.0, 3.0),
            wave(1.0, 1.0),
            wave(3.0, -2.0),
        ])
    });
    Ok(Image::new(pixels, TextureKind::Data)?)
}

impl Runner<'_> {
    /// The bench material against its height map as one, and four, layers of a layered material.
    pub(super) fn layers(&mut self, size: (u32, u32)) -> Result<()> {
        let place = (size, self.view.tiling);
        let mut scene = self.scene(size, &self.view.clone())?;
        let plain = self.case_variant(
            &mut scene,
            "layers",
            place,
            self.base.clone(),
            "the material (not layered)".into(),
        )?;
        let field = HeightField::from_image(
            &self.textures.height,
            Channel::Red,
            HeightConvention::Height,
        );
        let images = scene.images()?;
        let layer = ParallaxLayer {
            base_color_texture: Some(images.add(self.textures.albedo.clone())),
            normal_map: Some(images.add(self.textures.normal.clone())),
            ..ParallaxLayer::default()
        };
        let weights = LayerWeights::Texture(images.add(mixed_weights()?));
        let layers = |images: &mut pom::Assets<Image>, tilings: &[f32]| {
            let list = tilings
                .iter()
                .map(|&tiling| {
                    let tiled = ParallaxLayer {
                        tiling,
                        ..layer.clone()
                    };
                    (tiled, Some(&field))
                })
                .collect();
            ParallaxLayers::new(images, list, weights.clone())
        };
        let cases = [
            ("one layer", layers(images, &[1.0])?),
            ("four layers tiled alike", layers(images, &[1.0; 4])?),
            ("four layers tiled apart", layers(images, &APART)?),
        ];
        let mut medians = Vec::new();
        for (variant, layers) in cases {
            let material = ParallaxOcclusionMaterial {
                layers: Some(layers),
                ..self.base.clone()
            };
            medians.push(self.case_variant(
                &mut scene,
                "layers",
                place,
                material,
                variant.into(),
            )?);
        }
        if let [one, alike, apart] = medians[..] {
            self.ratio("one layer / the material".into(), size, one, plain);
            self.ratio(
                "four layers tiled alike / one layer".into(),
                size,
                alike,
                one,
            );
            self.ratio(
                "four layers tiled apart / one layer".into(),
                size,
                apart,
                one,
            );
        }
        Ok(())
    }

    /// Triplanar mapping against texture coordinates on the preview sphere, at a scale that
    /// repeats the texture about as often: the sphere's coordinates repeat it `tiling` times
    /// around its equator (π units) and pole to pole (half that), a mean of √2 · tiling / π
    /// repeats per unit.
    pub(super) fn triplanar(&mut self, size: (u32, u32)) -> Result<()> {
        let view = PreviewView {
            shape: PreviewShape::Sphere,
            ..self.view
        };
        let place = (size, view.tiling);
        let mut scene = self.scene(size, &view)?;
        let uv = self.case_variant(
            &mut scene,
            "triplanar",
            place,
            self.base.clone(),
            "sphere, uv".into(),
        )?;
        let triplanar = ParallaxOcclusionMaterial {
            mapping: TextureMapping::Triplanar,
            triplanar_scale: std::f32::consts::PI / (std::f32::consts::SQRT_2 * view.tiling),
            ..self.base.clone()
        };
        let projected = self.case_variant(
            &mut scene,
            "triplanar",
            place,
            triplanar,
            "sphere, triplanar".into(),
        )?;
        self.ratio("triplanar / uv, sphere".into(), size, projected, uv);
        Ok(())
    }
}
