//! The three textures of the previewed material: the files the user named, or stand-ins for the
//! ones left out, so any subset of `--height`, `--normal` and `--albedo` makes a sensible picture.

use std::path::Path;

use anyhow::{Context, Result};
use pom::{
    Assets, HeightField, HeightSource, Image, ParallaxOcclusionMaterial, TextureKind, patterns,
};

/// The stand-in height map: running-bond bricks, texels per side.
pub const BRICKS_TEXELS: u32 = 256;
/// Bricks per tile, across (u) and down (v).
pub const BRICKS_PER_TILE: (f32, f32) = (4.0, 8.0);
/// The stand-in albedo: a neutral grey, so the relief and the lighting are all one sees.
pub const NEUTRAL_GREY: [u8; 4] = [180, 180, 180, 255];

/// The texture files the user named; `None` means "use the stand-in".
#[derive(Clone, Copy, Debug, Default)]
pub struct TextureFiles<'a> {
    /// Height (or, with `depth_map`, depth) map; its red channel is read.
    pub height: Option<&'a Path>,
    /// Whether white is the deepest point of `height`.
    pub depth_map: bool,
    /// Tangent-space normal map (OpenGL convention).
    pub normal: Option<&'a Path>,
    /// sRGB colour texture.
    pub albedo: Option<&'a Path>,
}

/// The decoded textures, ready to add to the app.
#[derive(Clone, Debug)]
pub struct PreviewTextures {
    /// Read as [`HeightSource::Texture`] (red channel), linear.
    pub height: Image,
    /// Linear.
    pub normal: Image,
    /// sRGB.
    pub albedo: Image,
}

fn load(path: &Path, kind: TextureKind, option: &str) -> Result<Image> {
    Image::load(path, kind).with_context(|| format!("reading {option}"))
}

impl PreviewTextures {
    /// Decodes the named files and makes the missing textures. A normal map made here comes from
    /// the height map by the plugin's Sobel filter with `height_scale`, so its slopes match the
    /// parallax.
    pub fn load(files: &TextureFiles, height_scale: f32) -> Result<Self> {
        let height = match files.height {
            Some(path) => load(path, TextureKind::Height, "--height")?,
            None => {
                let (columns, rows) = BRICKS_PER_TILE;
                patterns::bricks(BRICKS_TEXELS, columns, rows).to_image()
            }
        };
        let normal = match files.normal {
            Some(path) => load(path, TextureKind::Normal, "--normal")?,
            // `from_image` flips a depth map into heights, so the Sobel slopes point the way
            // the shader's depth convention will displace the surface.
            None => HeightField::from_image(&height, 0, files.depth_map).normal_map(height_scale),
        };
        let albedo = match files.albedo {
            Some(path) => load(path, TextureKind::Color, "--albedo")?,
            None => Image::solid(NEUTRAL_GREY, TextureKind::Color),
        };
        Ok(Self {
            height,
            normal,
            albedo,
        })
    }

    /// Adds the textures to `images` and returns `settings` wearing them.
    pub fn attach(
        self,
        images: &mut Assets<Image>,
        settings: ParallaxOcclusionMaterial,
    ) -> ParallaxOcclusionMaterial {
        ParallaxOcclusionMaterial {
            base_color_texture: Some(images.add(self.albedo)),
            normal_map: Some(images.add(self.normal)),
            height_map: Some(HeightSource::Texture(images.add(self.height))),
            ..settings
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn without_files_the_stand_ins_are_bricks_their_normals_and_grey() {
        let textures = PreviewTextures::load(&TextureFiles::default(), 0.05).unwrap();
        let bricks = patterns::bricks(BRICKS_TEXELS, 4.0, 8.0);
        assert_eq!(textures.height, bricks.to_image());
        assert_eq!(
            textures.normal,
            bricks.quantized().normal_map(0.05),
            "normals of the height map as the GPU sees it"
        );
        assert_eq!(
            textures.albedo,
            Image::solid([180, 180, 180, 255], TextureKind::Color)
        );
        assert_eq!(textures.height.kind(), TextureKind::Height);
        assert_eq!(textures.normal.kind(), TextureKind::Normal);
    }

    #[test]
    fn a_missing_file_names_the_option_and_the_path() {
        let files = TextureFiles {
            albedo: Some(Path::new("/nonexistent/albedo.png")),
            ..TextureFiles::default()
        };
        let error = PreviewTextures::load(&files, 0.05).unwrap_err();
        let message = format!("{error:#}");
        assert!(message.contains("--albedo"), "{message}");
        assert!(message.contains("/nonexistent/albedo.png"), "{message}");
    }
}
