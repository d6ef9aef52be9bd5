//! `sandbox generate-assets`: writes the shipped material set and the street-corner scene, by
//! day and at night.
//!
//! Everything is computed from fixed seeds, so running it again reproduces the committed files
//! byte for byte (a test checks this).

mod glb;
mod street_corner;
mod textures;

use std::path::{Path, PathBuf};

use anyhow::{Context, Result};

use street_corner::TimeOfDay;
pub use street_corner::{STREET_CORNER_FILE, STREET_CORNER_NIGHT_FILE};

/// Where the generator writes by default: the assets/ folder of the repository the working
/// directory lies in (found by its assets/README.md, in the working directory or above it).
pub fn default_output() -> Result<PathBuf> {
    let here = std::env::current_dir().context("reading the working directory")?;
    here.ancestors()
        .map(|folder| folder.join("assets"))
        .find(|assets| assets.join("README.md").is_file())
        .with_context(|| {
            format!(
                "no assets/README.md in {} or above it: run inside the repository or pass --out",
                here.display()
            )
        })
}

/// PNG bytes of an 8-bit image.
fn png<P: image::PixelWithColorType<Subpixel = u8>>(
    image: &image::ImageBuffer<P, Vec<u8>>,
) -> Result<Vec<u8>> {
    let mut bytes = std::io::Cursor::new(Vec::new());
    image
        .write_to(&mut bytes, image::ImageFormat::Png)
        .context("encoding a PNG")?;
    Ok(bytes.into_inner())
}

/// The files of one material: albedo.png, normal.png, height.png.
pub struct EncodedMaterial {
    /// Folder name.
    pub name: &'static str,
    /// sRGB colour.
    pub albedo: Vec<u8>,
    /// Tangent-space normal map (OpenGL convention).
    pub normal: Vec<u8>,
    /// 8-bit height, white = top.
    pub height: Vec<u8>,
    /// Height range the normal map is made for, in texture units.
    pub height_scale: f32,
}

fn encode(maps: &textures::MaterialMaps) -> Result<EncodedMaterial> {
    let height = maps.height.to_image();
    let pom::Pixels::Gray8(grey) = height.pixels() else {
        anyhow::bail!("the height image of {} is not 8-bit grey", maps.name);
    };
    Ok(EncodedMaterial {
        name: maps.name,
        albedo: png(&maps.albedo)?,
        normal: png(&maps.height.normal_map(maps.height_scale).to_rgba8())?,
        height: png(grey)?,
        height_scale: maps.height_scale,
    })
}

/// Writes every asset under `out` and returns the files written.
pub fn generate(out: &Path) -> Result<Vec<PathBuf>> {
    let materials: Vec<EncodedMaterial> =
        textures::all().iter().map(encode).collect::<Result<_>>()?;
    let mut written = Vec::new();
    for material in &materials {
        let folder = out.join(material.name);
        std::fs::create_dir_all(&folder)
            .with_context(|| format!("creating {}", folder.display()))?;
        for (file, bytes) in [
            ("albedo.png", &material.albedo),
            ("normal.png", &material.normal),
            ("height.png", &material.height),
        ] {
            let path = folder.join(file);
            pom::files::write_file(&path, bytes)?;
            written.push(path);
        }
    }
    for (file, time) in [
        (STREET_CORNER_FILE, TimeOfDay::Day),
        (STREET_CORNER_NIGHT_FILE, TimeOfDay::Night),
    ] {
        let scene = out.join(file);
        pom::files::write_file(&scene, &street_corner::build(&materials, time))?;
        written.push(scene);
    }
    Ok(written)
}
