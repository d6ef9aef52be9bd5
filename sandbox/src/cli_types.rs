//! Command-line spellings of the plugin's choices, and parsers for values clap cannot check by
//! type alone. Each value enum maps one-to-one onto a `pom` type, so a new variant in the plugin
//! is a compile error here rather than an option the command silently lacks.

use std::path::PathBuf;

use clap::ValueEnum;
use pom::preview::{MAX_VIEW_ANGLE, PreviewProjection};
use pom::{DebugView, ParallaxMethod, ShadowMode};

/// Bisection steps `--method relief` takes after its linear search.
pub const RELIEF_BINARY_STEPS: u32 = 6;

/// `--method`: how the ray meets the height field.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum MethodArg {
    /// Normal mapping only, no parallax
    Normal,
    /// Parallax offset with offset limiting (Welsh 2004): one height sample
    Offset,
    /// Steep parallax (McGuire 2005): linear search, shades the first sample below the surface
    Steep,
    /// Parallax occlusion mapping (Tatarchuk 2006): linear search, then a line intersection
    Pom,
    /// Relief mapping (Policarpo 2005): linear search, then 6 bisection steps
    Relief,
}

impl From<MethodArg> for ParallaxMethod {
    fn from(method: MethodArg) -> Self {
        match method {
            MethodArg::Normal => ParallaxMethod::NormalMapping,
            MethodArg::Offset => ParallaxMethod::ParallaxOffset,
            MethodArg::Steep => ParallaxMethod::Steep,
            MethodArg::Pom => ParallaxMethod::Occlusion,
            MethodArg::Relief => ParallaxMethod::Relief {
                binary_steps: RELIEF_BINARY_STEPS,
            },
        }
    }
}

impl From<ParallaxMethod> for MethodArg {
    fn from(method: ParallaxMethod) -> Self {
        match method {
            ParallaxMethod::NormalMapping => MethodArg::Normal,
            ParallaxMethod::ParallaxOffset => MethodArg::Offset,
            ParallaxMethod::Steep => MethodArg::Steep,
            ParallaxMethod::Occlusion => MethodArg::Pom,
            ParallaxMethod::Relief { .. } => MethodArg::Relief,
        }
    }
}

/// `--shadows`: self-shadowing of the height field.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum ShadowsArg {
    /// No self-shadowing
    Off,
    /// Any blocker towards the light makes the point fully dark
    Hard,
    /// Tatarchuk's penumbra estimate (see --shadow-softening)
    Soft,
}

impl From<ShadowsArg> for ShadowMode {
    fn from(shadows: ShadowsArg) -> Self {
        match shadows {
            ShadowsArg::Off => ShadowMode::Off,
            ShadowsArg::Hard => ShadowMode::Hard,
            ShadowsArg::Soft => ShadowMode::Soft,
        }
    }
}

impl From<ShadowMode> for ShadowsArg {
    fn from(shadows: ShadowMode) -> Self {
        match shadows {
            ShadowMode::Off => ShadowsArg::Off,
            ShadowMode::Hard => ShadowsArg::Hard,
            ShadowMode::Soft => ShadowsArg::Soft,
        }
    }
}

/// `--projection`: how the preview camera projects.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum ProjectionArg {
    /// Parallel rays: every pixel sees the plane at the same angle
    Ortho,
    /// A 45° vertical field of view
    Perspective,
}

impl From<ProjectionArg> for PreviewProjection {
    fn from(projection: ProjectionArg) -> Self {
        match projection {
            ProjectionArg::Ortho => PreviewProjection::Orthographic,
            ProjectionArg::Perspective => PreviewProjection::Perspective,
        }
    }
}

impl From<PreviewProjection> for ProjectionArg {
    fn from(projection: PreviewProjection) -> Self {
        match projection {
            PreviewProjection::Orthographic => ProjectionArg::Ortho,
            PreviewProjection::Perspective => ProjectionArg::Perspective,
        }
    }
}

/// `--debug-view`: what the material outputs instead of the lit colour.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum DebugViewArg {
    /// The lit surface
    None,
    /// Tatarchuk's LOD tint: bluer through the LOD band, deepest blue where only normal
    /// mapping runs
    Lod,
    /// The mip level as grey, black = level 0
    Mip,
    /// March samples as a heat map, black (none) to white (--max-samples)
    Samples,
    /// Raw 16-bit PNG: R = fract(u), G = fract(v), B = 1 full march / 0.5 LOD band / 0 normal
    /// mapping only
    Uv,
    /// Raw 16-bit PNG: the self-shadowing visibility (1 = lit) in R, G and B
    Shadow,
    /// The tangent-space shading normal as n × 0.5 + 0.5
    Normal,
}

impl DebugViewArg {
    /// Whether the view holds measurements rather than colours: those are rendered into a float
    /// target and written as 16-bit values without the sRGB curve, so the numbers survive.
    pub fn writes_raw_values(self) -> bool {
        matches!(self, DebugViewArg::Uv | DebugViewArg::Shadow)
    }
}

impl From<DebugViewArg> for DebugView {
    fn from(view: DebugViewArg) -> Self {
        match view {
            DebugViewArg::None => DebugView::None,
            DebugViewArg::Lod => DebugView::Lod,
            DebugViewArg::Mip => DebugView::Mip,
            DebugViewArg::Samples => DebugView::Samples,
            DebugViewArg::Uv => DebugView::Uv,
            DebugViewArg::Shadow => DebugView::Shadow,
            DebugViewArg::Normal => DebugView::Normal,
        }
    }
}

impl From<DebugView> for DebugViewArg {
    fn from(view: DebugView) -> Self {
        match view {
            DebugView::None => DebugViewArg::None,
            DebugView::Lod => DebugViewArg::Lod,
            DebugView::Mip => DebugViewArg::Mip,
            DebugView::Samples => DebugViewArg::Samples,
            DebugView::Uv => DebugViewArg::Uv,
            DebugView::Shadow => DebugViewArg::Shadow,
            DebugView::Normal => DebugViewArg::Normal,
        }
    }
}

/// `--camera`: which camera a scene is rendered from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CameraArg {
    /// A three-quarter view framing the whole scene (`pom::preview::three_quarter_view`).
    Auto,
    /// The file's camera with this index, counting from 0 in the order of its nodes.
    Index(usize),
}

/// Parses `--camera`: a camera index (0, 1, …) or `auto`.
pub fn parse_camera(text: &str) -> Result<CameraArg, String> {
    let text = text.trim();
    if text.eq_ignore_ascii_case("auto") {
        return Ok(CameraArg::Auto);
    }
    text.parse()
        .map(CameraArg::Index)
        .map_err(|_| format!("expected a camera index (0, 1, …) or auto, got {text:?}"))
}

/// Parses `WIDTHxHEIGHT`, each side 1..=8192.
pub fn parse_size(text: &str) -> Result<(u32, u32), String> {
    let (width, height) = text
        .split_once(['x', 'X'])
        .ok_or_else(|| format!("expected WIDTHxHEIGHT, got {text:?}"))?;
    let side = |value: &str| -> Result<u32, String> {
        let parsed: u32 = value
            .trim()
            .parse()
            .map_err(|_| format!("{value:?} is not a whole number of pixels"))?;
        if (1..=8192).contains(&parsed) {
            Ok(parsed)
        } else {
            Err(format!("{parsed} is outside 1..=8192"))
        }
    };
    Ok((side(width)?, side(height)?))
}

/// A number that is not NaN or infinite. The preview view has no validation of its own and
/// would quietly fall back to a default, so the command rejects such values up front.
pub fn parse_finite(text: &str) -> Result<f32, String> {
    let value: f32 = text
        .trim()
        .parse()
        .map_err(|_| format!("{text:?} is not a number"))?;
    if value.is_finite() {
        Ok(value)
    } else {
        Err(format!("{value} is not a finite number"))
    }
}

/// A finite number above zero (distances and tiling).
pub fn parse_positive(text: &str) -> Result<f32, String> {
    let value = parse_finite(text)?;
    if value > 0.0 {
        Ok(value)
    } else {
        Err(format!("{value} must be greater than 0"))
    }
}

/// A view angle in degrees, 0 (straight down) up to the preview's steepest angle; the preview
/// would clamp anything else, and an angle the user did not ask for is worse than an error.
pub fn parse_view_angle(text: &str) -> Result<f32, String> {
    let value = parse_finite(text)?;
    if (0.0..=MAX_VIEW_ANGLE).contains(&value) {
        Ok(value)
    } else {
        Err(format!("{value} is outside 0..={MAX_VIEW_ANGLE} degrees"))
    }
}

/// A path ending in `.png`: the preview is always a PNG (16-bit for the raw debug views), and a
/// PNG written under another extension would mislead whoever opens it.
pub fn parse_png_path(text: &str) -> Result<PathBuf, String> {
    let path = PathBuf::from(text);
    let is_png = path
        .extension()
        .is_some_and(|extension| extension.eq_ignore_ascii_case("png"));
    if is_png {
        Ok(path)
    } else {
        Err(format!("{text:?} does not end in .png"))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_parse_and_bad_sizes_are_rejected_with_a_reason() {
        assert_eq!(parse_size("640x480"), Ok((640, 480)));
        assert_eq!(parse_size("1X1"), Ok((1, 1)));
        for bad in ["640", "0x10", "10x0", "axb", "9000x10", "-1x5", ""] {
            assert!(parse_size(bad).is_err(), "{bad:?} was accepted");
        }
    }

    #[test]
    fn every_value_enum_round_trips_through_its_pom_type() {
        for method in MethodArg::value_variants() {
            assert_eq!(MethodArg::from(ParallaxMethod::from(*method)), *method);
        }
        for shadows in ShadowsArg::value_variants() {
            assert_eq!(ShadowsArg::from(ShadowMode::from(*shadows)), *shadows);
        }
        for projection in ProjectionArg::value_variants() {
            let round_trip = ProjectionArg::from(PreviewProjection::from(*projection));
            assert_eq!(round_trip, *projection);
        }
        for view in DebugViewArg::value_variants() {
            assert_eq!(DebugViewArg::from(DebugView::from(*view)), *view);
        }
        assert_eq!(
            ParallaxMethod::from(MethodArg::Relief),
            ParallaxMethod::Relief { binary_steps: 6 }
        );
    }

    #[test]
    fn only_uv_and_shadow_views_are_written_raw() {
        let raw: Vec<_> = DebugViewArg::value_variants()
            .iter()
            .filter(|view| view.writes_raw_values())
            .collect();
        assert_eq!(raw, [&DebugViewArg::Uv, &DebugViewArg::Shadow]);
    }

    #[test]
    fn numbers_that_would_be_silently_replaced_are_rejected() {
        assert_eq!(parse_finite("-12.5"), Ok(-12.5));
        for bad in ["NaN", "inf", "-inf", "ten", ""] {
            assert!(parse_finite(bad).is_err(), "{bad:?} was accepted");
        }
        assert_eq!(parse_positive("0.5"), Ok(0.5));
        for bad in ["0", "-1", "NaN"] {
            assert!(parse_positive(bad).is_err(), "{bad:?} was accepted");
        }
        assert_eq!(parse_view_angle("0"), Ok(0.0));
        assert_eq!(parse_view_angle("89.99"), Ok(89.99));
        for bad in ["-1", "90", "120", "NaN"] {
            assert!(parse_view_angle(bad).is_err(), "{bad:?} was accepted");
        }
    }

    #[test]
    fn cameras_are_an_index_or_auto() {
        assert_eq!(parse_camera("auto"), Ok(CameraArg::Auto));
        assert_eq!(parse_camera("AUTO"), Ok(CameraArg::Auto));
        assert_eq!(parse_camera("0"), Ok(CameraArg::Index(0)));
        assert_eq!(parse_camera("12"), Ok(CameraArg::Index(12)));
        for bad in ["-1", "first", "1.5", ""] {
            assert!(parse_camera(bad).is_err(), "{bad:?} was accepted");
        }
    }

    #[test]
    fn output_paths_must_be_png() {
        assert_eq!(parse_png_path("a/b.PNG"), Ok(PathBuf::from("a/b.PNG")));
        for bad in ["preview.jpg", "preview", "png"] {
            assert!(parse_png_path(bad).is_err(), "{bad:?} was accepted");
        }
    }
}
