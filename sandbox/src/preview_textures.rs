//! The three textures of the previewed material: the files the user named, or stand-ins for the
//! ones left out, so any subset of `--height`, `--normal` and `--albedo` makes a sensible picture.

use std::path::Path;

use anyhow::{Context, Result};
use pom::{
    Assets, Channel, HeightConvention, HeightField, HeightSource, Image, ParallaxOcclusionMaterial,
    TextureKind,
};

/// The stand-in height map: the shipped bricks (assets/bricks), embedded in the binary.
pub const BRICKS_HEIGHT: &[u8] = include_bytes!("../../assets/bricks/height.png");
/// The shipped bricks' colour, used when no height map is given either.
pub const BRICKS_ALBEDO: &[u8] = include_bytes!("../../assets/bricks/albedo.png");
/// The stand-in albedo for a height map of the user's: a neutral grey, so the relief and the
/// lighting are all one sees.
pub const NEUTRAL_GREY: [u8; 4] = [180, 180, 180, 255];

fn embedded(bytes: &[u8], name: &str, kind: TextureKind) -> Result<Image> {
    Image::decode(bytes, name, kind, Channel::Red)
        .with_context(|| format!("decoding the embedded {name}"))
}

/// The texture files the user named; `None` means "use the stand-in".
#[derive(Clone, Copy, Debug, Default)]
pub struct TextureFiles<'a> {
    /// Height (or depth) map; its red channel is read.
    pub height: Option<&'a Path>,
    /// What the values of `height` mean.
    pub convention: HeightConvention,
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
            None => embedded(
                BRICKS_HEIGHT,
                "assets/bricks/height.png",
                TextureKind::Height,
            )?,
        };
        let normal = match files.normal {
            Some(path) => load(path, TextureKind::Normal, "--normal")?,
            // `from_image` flips a depth map into heights, so the Sobel slopes point the way
            // the shader's depth convention will displace the surface.
            None => HeightField::from_image(&height, Channel::Red, files.convention)
                .normal_map(height_scale),
        };
        let albedo = match (files.albedo, files.height) {
            (Some(path), _) => load(path, TextureKind::Color, "--albedo")?,
            (None, None) => embedded(
                BRICKS_ALBEDO,
                "assets/bricks/albedo.png",
                TextureKind::Color,
            )?,
            (None, Some(_)) => Image::solid(NEUTRAL_GREY, TextureKind::Color),
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
    fn without_files_the_stand_ins_are_the_shipped_bricks_with_sobel_normals() {
        let textures = PreviewTextures::load(&TextureFiles::default(), 0.05).unwrap();
        let shipped = |file: &str, kind| {
            let path = Path::new(env!("CARGO_MANIFEST_DIR"))
                .join("../assets/bricks")
                .join(file);
            Image::load(path, kind).unwrap()
        };
        let height = shipped("height.png", TextureKind::Height);
        assert_eq!(textures.height, height);
        assert_eq!(
            textures.normal,
            HeightField::from_image(&height, Channel::Red, HeightConvention::Height)
                .normal_map(0.05),
            "normals of the height map as the GPU sees it, at the asked height scale"
        );
        assert_eq!(textures.albedo, shipped("albedo.png", TextureKind::Color));
        assert_eq!(textures.height.kind(), TextureKind::Height);
        assert_eq!(textures.normal.kind(), TextureKind::Normal);
    }

    #[test]
    fn a_height_map_of_ones_own_gets_a_grey_albedo() {
        let dir = std::env::temp_dir().join(format!("pom-preview-textures-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("h.png");
        image::GrayImage::new(4, 4).save(&path).unwrap();
        let files = TextureFiles {
            height: Some(&path),
            ..TextureFiles::default()
        };
        let textures = PreviewTextures::load(&files, 0.05).unwrap();
        assert_eq!(
            textures.albedo,
            Image::solid(NEUTRAL_GREY, TextureKind::Color)
        );
        std::fs::remove_dir_all(&dir).unwrap();
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
