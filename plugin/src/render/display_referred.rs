//! How the scene marks a display-referred pixel (the clear colour, a debug view's data), whose
//! colour post-processing writes as it is, without exposure or tonemapping: its alpha `a` is
//! stored as `DISPLAY_REFERRED_BASE − a`, below zero, where no lit pixel's alpha is. The rule is
//! declared here once: Rust clears the scene with [`display_referred_alpha`], and the shaders
//! that write or read such pixels compose [`display_referred_wgsl`].

/// What the scene stores for a display-referred pixel of alpha 0.
const DISPLAY_REFERRED_BASE: f32 = -1.0;

/// What the scene stores for a display-referred pixel of alpha `alpha` (clamped to 0..=1).
pub(crate) fn display_referred_alpha(alpha: f32) -> f32 {
    DISPLAY_REFERRED_BASE - alpha.clamp(0.0, 1.0)
}

/// The rule in WGSL: `DEBUG_VIEW_ALPHA` (an opaque debug view's stored alpha),
/// `is_display_referred(stored)` and `displayed_alpha(stored)`, the alpha it is shown with.
pub fn display_referred_wgsl() -> String {
    format!(
        "const DISPLAY_REFERRED_BASE: f32 = {DISPLAY_REFERRED_BASE:?};\n\
         const DEBUG_VIEW_ALPHA: f32 = {:?};\n\
         fn is_display_referred(stored: f32) -> bool {{ return stored < 0.0; }}\n\
         fn displayed_alpha(stored: f32) -> f32 {{ return clamp(DISPLAY_REFERRED_BASE - stored, 0.0, 1.0); }}\n",
        display_referred_alpha(1.0)
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_display_referred_alpha_is_negative_and_comes_back() {
        for alpha in [0.0, 0.25, 1.0, 2.0, -1.0] {
            let stored = display_referred_alpha(alpha);
            assert!(stored < 0.0, "{alpha}");
            assert_eq!(DISPLAY_REFERRED_BASE - stored, alpha.clamp(0.0, 1.0));
        }
        assert!(display_referred_wgsl().contains("const DEBUG_VIEW_ALPHA: f32 = -2.0;"));
    }
}
