//! The tonemapping operators: [`Tonemapping`], a component of the camera entity (the default
//! where it is missing), and the function that sets it with the exposure on every active camera.

use crate::Exposure;

crate::choice_enum! {
    /// The curve that maps exposed scene values (0..∞) to display values (0..1).
    pub enum Tonemapping: "TONEMAP" {
        /// Clamp to 1: values above white clip, and bright colours shift towards their brightest channels.
        None = "none",
        /// ACES filmic, Hill's fit of the RRT + ODT: contrasty, shifts bright hues towards yellow.
        Aces = "aces",
        /// AgX (Sobotka), the minimal fit: bright colours desaturate along the path to white.
        Agx = "agx",
        /// Khronos PBR Neutral: base colours up to 0.76 unchanged in hue and value, highlights rolled off.
        Neutral = "neutral",
    }
}

impl Default for Tonemapping {
    /// Khronos PBR Neutral: this is a tool for tuning materials, and Neutral shows a base
    /// colour as authored (same hue, same value up to 0.76; only its 0.04 Fresnel floor is
    /// taken off) while rolling off highlights instead of clipping them. ACES and AgX change
    /// mid-tone contrast and hue, which would hide what the material itself does.
    fn default() -> Self {
        Tonemapping::Neutral
    }
}

/// Puts `exposure` and `tonemapping` on every active camera of `world` (replacing what they
/// had); returns how many cameras that was.
pub fn set_camera_display_mapping(
    world: &mut hecs::World,
    exposure: Exposure,
    tonemapping: Tonemapping,
) -> usize {
    let cameras = crate::camera::active_cameras(world);
    for camera in &cameras {
        // The entity was just found, so inserting cannot fail.
        let _ = world.insert(*camera, (exposure, tonemapping));
    }
    cameras.len()
}
