//! Environment images that are broken or odd: a truncated `.hdr` is an error naming it; a 1×1
//! image lights like a constant; a 100000×2 one is averaged down to the GPU's texture limit
//! with a warning naming it, and lights the scene.

use std::sync::Arc;

use pom::{EnvironmentLight, EnvironmentSource, EquirectImage, ParallaxOcclusionMaterial};

use super::{install_logger, material_app, renders_cleanly, warnings_containing};

/// The material plane lit by `image` as the environment: the frame renders clean.
fn render_under(image: EquirectImage) {
    let mut app = material_app(|_| ParallaxOcclusionMaterial::default());
    app.insert_resource(EnvironmentLight {
        source: EnvironmentSource::Equirect(Arc::new(image)),
        ..EnvironmentLight::default()
    });
    renders_cleanly(&mut app);
}

#[test]
fn truncated_hdr_environment() {
    let dir = pom_tests::gltf_fixture::scratch_dir("truncated-hdr");
    let whole = dir.join("whole.hdr");
    let image = image::Rgb32FImage::from_pixel(64, 32, image::Rgb([100.0, 200.0, 300.0]));
    image::DynamicImage::ImageRgb32F(image)
        .save(&whole)
        .unwrap();
    let bytes = std::fs::read(&whole).unwrap();
    let cut = dir.join("cut.hdr");
    std::fs::write(&cut, &bytes[..bytes.len() / 2]).unwrap();
    let message = EnvironmentLight::from_file(&cut).unwrap_err().to_string();
    assert!(message.contains("cut.hdr"), "{message}");
}

#[test]
fn one_by_one_environment() {
    render_under(EquirectImage::new("one.hdr", 1, 1, vec![[2000.0; 3]]).unwrap());
}

#[test]
fn hundred_thousand_by_two_environment() {
    install_logger();
    let texels = vec![[500.0, 600.0, 700.0]; 200_000];
    render_under(EquirectImage::new("wide.hdr", 100_000, 2, texels).unwrap());
    let warnings = warnings_containing("environment wide.hdr: 100000 × 2 is larger than");
    assert_eq!(warnings.len(), 1, "{warnings:?}");
}
