//! Command-line spellings of the preview's choices, and parsers for values clap cannot check by
//! type alone. The material's own choices need none: their spellings are declared with the
//! material (`material_args.rs`).

use std::path::PathBuf;

use clap::ValueEnum;
use pom::hecs::{Entity, World};
use pom::preview::{MAX_VIEW_ANGLE, PreviewProjection, PreviewShape};
use pom::{DirectionalLight, LightShadows, PointLight, RenderPath, RenderPlugin, SpotLight};

use crate::settings_args::SettingsArgs;

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

/// `--shape`: what the material preview shows the material on (`pom::preview::PreviewShape`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum ShapeArg {
    /// A square facing up, u along +X and v along +Z (0..tiling); it fills the image
    Plane,
    /// A cube with the whole texture on each face (u and v along the face's edges, v down the
    /// side faces), framed whole
    Cube,
    /// A sphere, u once around the equator and v from the top pole (0) to the bottom (1)
    Sphere,
    /// A closed cylinder about the vertical: its side u once around and v from the top rim to
    /// the bottom, each cap the unit square over its disc
    Cylinder,
}

impl From<ShapeArg> for PreviewShape {
    fn from(shape: ShapeArg) -> Self {
        match shape {
            ShapeArg::Plane => PreviewShape::Plane,
            ShapeArg::Cube => PreviewShape::Cube,
            ShapeArg::Sphere => PreviewShape::Sphere,
            ShapeArg::Cylinder => PreviewShape::Cylinder,
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

/// An exposure in EV100 within [`pom::Exposure::RANGE`].
pub fn parse_exposure(text: &str) -> Result<f32, String> {
    let value = parse_finite(text)?;
    let range = pom::Exposure::RANGE;
    if range.contains(&value) {
        Ok(value)
    } else {
        Err(format!(
            "{value} EV100 is outside {}..={}",
            range.start(),
            range.end()
        ))
    }
}

/// How the camera maps scene light to the display: `--exposure`, `--tonemap`, `--aa` and the
/// anti-aliasing parameters.
#[derive(Clone, Debug, clap::Args)]
#[command(next_help_heading = "Display")]
pub struct DisplayArgs {
    /// Camera exposure in EV100, -16..=24; +1 halves the light [default: the scene camera's
    /// own, else 14.7, daylight: white in a 100,000 lux sun shows as 1].
    #[arg(long, value_name = "EV", allow_negative_numbers = true, value_parser = parse_exposure)]
    pub exposure: Option<f32>,
    /// Tonemapping operator: none (clamp), aces, agx or neutral (Khronos PBR Neutral).
    #[arg(long, value_name = "NAME", value_parser = crate::material_args::choice_parser::<pom::Tonemapping>(), default_value = "neutral")]
    pub tonemap: pom::Tonemapping,
    /// Anti-aliasing: off, fxaa (the post filter) or taa (a still image renders the jitter's
    /// whole cycle, --taa-jitter-samples frames, for the history to settle).
    #[arg(long, value_name = "NAME", value_parser = crate::material_args::choice_parser::<pom::AntiAliasing>(), default_value = "off")]
    pub aa: pom::AntiAliasing,
    /// TAA's parameters: `--taa-current-weight` and the rest of its table.
    #[command(flatten)]
    pub taa: SettingsArgs<pom::TemporalAntiAliasing>,
    /// FXAA's parameters: `--fxaa-contrast-threshold` and the rest of its table.
    #[command(flatten)]
    pub fxaa: SettingsArgs<pom::FastApproximateAntiAliasing>,
}

impl DisplayArgs {
    /// Puts the exposure and operator on the app's active cameras.
    pub fn apply(&self, app: &mut pom::App) {
        // Without the flag a camera keeps the exposure its scene gave it (a night scene's).
        let own = pom::active_cameras(&app.world)
            .first()
            .and_then(|&camera| app.world.get::<&pom::Exposure>(camera).ok().map(|e| *e));
        let exposure = self
            .exposure
            .map_or_else(|| own.unwrap_or_default(), |ev100| pom::Exposure { ev100 });
        pom::set_camera_display_mapping(&mut app.world, exposure, self.tonemap);
        pom::set_camera_anti_aliasing(&mut app.world, self.aa, self.temporal());
        pom::set_camera_fxaa(&mut app.world, self.fxaa.settings());
    }

    /// The TAA parameters the flags give (the defaults for those not given).
    pub fn temporal(&self) -> pom::TemporalAntiAliasing {
        self.taa.settings()
    }

    /// Frames a still image is rendered for: TAA's settling frames, else one.
    pub fn frames(&self) -> u32 {
        match self.aa {
            pom::AntiAliasing::Taa => self.temporal().settling_frames(),
            _ => 1,
        }
    }
}

/// `--scene-shadows`: a switch spelled `on` or `off`. The values have no doc comments, so
/// `--help` lists them on one line instead of explaining each.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum Switch {
    On,
    Off,
}

/// A shadow-map side in texels, within [`LightShadows::MIN_MAP_SIZE`]`..=`
/// [`LightShadows::MAX_MAP_SIZE`]; the renderer would clamp anything else without a word.
pub fn parse_shadow_map_size(text: &str) -> Result<u32, String> {
    let (min, max) = (LightShadows::MIN_MAP_SIZE, LightShadows::MAX_MAP_SIZE);
    let value: u32 = text
        .trim()
        .parse()
        .map_err(|_| format!("{text:?} is not a whole number of texels ({min}..={max})"))?;
    if (min..=max).contains(&value) {
        Ok(value)
    } else {
        Err(format!("{value} texels is outside {min}..={max}"))
    }
}

/// Scene shadows of every light: `--scene-shadows` and `--shadow-map-size`.
#[derive(Clone, Copy, Debug, clap::Args)]
#[command(next_help_heading = "Shadows")]
pub struct ShadowArgs {
    /// Whether the lights cast scene shadows (shadow maps); the parallax materials'
    /// self-shadows do not depend on it.
    #[arg(
        long,
        long_help,
        value_name = "on|off",
        value_enum,
        default_value = "on"
    )]
    pub scene_shadows: Switch,
    /// Texels along each side of every light's shadow map (per cascade or cube face),
    /// 16..=8192 [default: 2048].
    #[arg(long, value_name = "TEXELS", value_parser = parse_shadow_map_size)]
    pub shadow_map_size: Option<u32>,
}

impl ShadowArgs {
    /// Puts the switch and the map size on every light of `world` (directional, point and
    /// spot), keeping the rest of a `LightShadows` the light already has.
    pub fn apply(&self, world: &mut World) {
        for light in light_entities(world) {
            let mut shadows = world
                .get::<&LightShadows>(light)
                .map_or_else(|_| LightShadows::default(), |shadows| *shadows);
            shadows.enabled = self.scene_shadows == Switch::On;
            if let Some(map_size) = self.shadow_map_size {
                shadows.map_size = map_size;
            }
            // The entity was just listed, so it exists.
            let _ = world.insert_one(light, shadows);
        }
    }
}

/// `--path`: where opaque surfaces are shaded, spelled as [`RenderPath`]'s `FromStr` reads it
/// (its error names the choices; clap adds the flag).
#[derive(Clone, Copy, Debug, clap::Args)]
#[command(next_help_heading = "Renderer")]
pub struct PathArgs {
    /// Render path: forward (fragment shaders), deferred (compute, from a visibility buffer) or
    /// auto (deferred on a GPU, forward on a software driver).
    #[arg(
        long,
        value_name = "forward|deferred|auto",
        value_parser = str::parse::<RenderPath>,
        default_value = "auto"
    )]
    pub path: RenderPath,
}

impl PathArgs {
    /// `plugin`, shading on the path asked for.
    pub fn apply(&self, plugin: RenderPlugin) -> RenderPlugin {
        plugin.with_path(self.path)
    }
}

/// `--path` of `sandbox bench`: like [`PathArgs`], but repeatable, so that one run times
/// several paths side by side (`--path forward --path deferred`).
#[derive(Clone, Debug, clap::Args)]
#[command(next_help_heading = "Renderer")]
pub struct BenchPathArgs {
    /// Render path: forward (fragment shaders), deferred (compute, from a visibility buffer) or
    /// auto (deferred on a GPU, forward on a software driver); repeatable: every measurement
    /// runs once per path, in the order given.
    #[arg(
        long = "path",
        value_name = "forward|deferred|auto",
        value_parser = str::parse::<RenderPath>,
        default_value = "auto"
    )]
    pub paths: Vec<RenderPath>,
}

impl BenchPathArgs {
    /// The paths asked for, in order, each once (at least one: clap's default is auto).
    pub fn paths(&self) -> Vec<RenderPath> {
        let mut paths: Vec<RenderPath> = Vec::with_capacity(self.paths.len());
        for path in &self.paths {
            if !paths.contains(path) {
                paths.push(*path);
            }
        }
        if paths.is_empty() {
            paths.push(RenderPath::Auto);
        }
        paths
    }
}

/// Every entity holding a directional, point or spot light, in entity order.
pub fn light_entities(world: &World) -> Vec<Entity> {
    let mut lights: Vec<Entity> = world
        .query::<(Entity, &DirectionalLight)>()
        .iter()
        .map(|(entity, _)| entity)
        .chain(
            world
                .query::<(Entity, &PointLight)>()
                .iter()
                .map(|(e, _)| e),
        )
        .chain(world.query::<(Entity, &SpotLight)>().iter().map(|(e, _)| e))
        .collect();
    lights.sort();
    lights.dedup();
    lights
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
        for projection in ProjectionArg::value_variants() {
            let round_trip = ProjectionArg::from(PreviewProjection::from(*projection));
            assert_eq!(round_trip, *projection);
        }
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
    fn shadow_map_sizes_outside_the_limits_are_rejected_naming_them() {
        assert_eq!(parse_shadow_map_size("16"), Ok(16));
        assert_eq!(parse_shadow_map_size(" 1024 "), Ok(1024));
        assert_eq!(parse_shadow_map_size("8192"), Ok(8192));
        for bad in ["0", "15", "8193", "-1", "1e3", "2048.0", "big", ""] {
            let error = parse_shadow_map_size(bad).expect_err(bad);
            assert!(error.contains("16..=8192"), "{bad:?}: {error}");
        }
    }

    #[test]
    fn shadow_flags_reach_every_light() {
        let mut world = World::new();
        let sun = world.spawn((DirectionalLight::default(),));
        let lamp = world.spawn((PointLight::default(),));
        let tuned = LightShadows {
            softness: 3.0,
            ..LightShadows::default()
        };
        let spot = world.spawn((SpotLight::default(), tuned));
        let not_a_light = world.spawn((pom::Transform::IDENTITY,));
        assert_eq!(light_entities(&world), [sun, lamp, spot]);
        let args = ShadowArgs {
            scene_shadows: Switch::Off,
            shadow_map_size: Some(512),
        };
        args.apply(&mut world);
        for light in [sun, lamp, spot] {
            let shadows = *world.get::<&LightShadows>(light).unwrap();
            assert!(!shadows.enabled, "{shadows:?}");
            assert_eq!(shadows.map_size, 512);
        }
        assert_eq!(world.get::<&LightShadows>(spot).unwrap().softness, 3.0);
        assert!(world.get::<&LightShadows>(not_a_light).is_err());
        // Without a size, the switch alone changes and the size stays.
        ShadowArgs {
            scene_shadows: Switch::On,
            shadow_map_size: None,
        }
        .apply(&mut world);
        let shadows = *world.get::<&LightShadows>(sun).unwrap();
        assert!(shadows.enabled);
        assert_eq!(shadows.map_size, 512);
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
    fn bench_paths_keep_their_order_once_each() {
        use RenderPath::{Auto, Deferred, Forward};
        let paths = |paths: Vec<RenderPath>| BenchPathArgs { paths }.paths();
        assert_eq!(paths(vec![]), [Auto]);
        assert_eq!(paths(vec![Deferred, Forward]), [Deferred, Forward]);
        assert_eq!(paths(vec![Forward, Deferred, Forward]), [Forward, Deferred]);
    }

    #[test]
    fn output_paths_must_be_png() {
        assert_eq!(parse_png_path("a/b.PNG"), Ok(PathBuf::from("a/b.PNG")));
        for bad in ["preview.jpg", "preview", "png"] {
            assert!(parse_png_path(bad).is_err(), "{bad:?} was accepted");
        }
    }
}

/// The light from all around the scene: `--environment` and its parameters.
#[derive(Clone, Debug, clap::Args)]
#[command(next_help_heading = "Environment")]
pub struct EnvironmentArgs {
    /// The light from all around the scene, drawn behind it: off, sky (a daylight sky whose
    /// sun is the scene's first directional light), uniform:R,G,B (a constant radiance in
    /// cd/m²) or the path of an equirectangular .hdr or .exr image [default: off].
    #[arg(long, value_name = "PATH|sky|off|uniform:R,G,B", value_parser = parse_environment)]
    pub environment: Option<pom::EnvironmentChoice>,
    /// The environment's parameters: `--environment-intensity`, `--environment-rotation` (in
    /// degrees) and the rest of its table.
    #[command(flatten)]
    pub environment_settings: SettingsArgs<pom::EnvironmentSettings>,
}

/// `--environment`'s value, as [`pom::EnvironmentChoice`] reads it.
fn parse_environment(text: &str) -> Result<pom::EnvironmentChoice, String> {
    text.parse()
        .map_err(|error: pom::EnvironmentError| error.to_string())
}

impl EnvironmentArgs {
    /// The environment the flags name, its file read (before the GPU starts, so a bad file
    /// is reported alone); `None` without `--environment`.
    pub fn light(&self) -> anyhow::Result<Option<pom::EnvironmentLight>> {
        let Some(choice) = &self.environment else {
            return Ok(None);
        };
        Ok(Some(pom::EnvironmentLight {
            source: choice.load()?,
            settings: self.environment_settings.settings(),
        }))
    }
}

/// An illuminance in lux: finite and ≥ 0.
pub fn parse_lux(text: &str) -> Result<f32, String> {
    let value = parse_finite(text)?;
    if value >= 0.0 {
        Ok(value)
    } else {
        Err(format!("{value} lux is negative"))
    }
}

/// Sets every directional light of `world` to `lux` (0: no direct sunlight).
pub fn set_sun_illuminance(world: &mut World, lux: f32) {
    for light in world.query_mut::<&mut DirectionalLight>() {
        light.intensity = lux;
    }
}
