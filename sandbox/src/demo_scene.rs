//! The scene the sandbox opens with: the shipped street corner, embedded in the binary so it
//! runs from anywhere.

use anyhow::{Context, Result};
use pom::{App, GltfScene};

/// The street-corner scene of assets/, as built by `sandbox generate-assets`.
pub const STREET_CORNER: &[u8] = include_bytes!("../../assets/street_corner.glb");

/// Loads the embedded street corner into `app` (its camera, sun and POM materials included),
/// logging the loader's warnings.
pub fn spawn(app: &mut App) -> Result<GltfScene> {
    let scene = pom::load_gltf_bytes(app, STREET_CORNER, "street_corner.glb (embedded)")
        .context("loading the embedded street corner")?;
    for warning in &scene.warnings {
        log::warn!("{warning}");
    }
    Ok(scene)
}
