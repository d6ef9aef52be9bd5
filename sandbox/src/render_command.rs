//! `sandbox render`: one parallax material on the plugin's preview plane, or a glTF scene
//! (`--scene`, see `scene_preview`), rendered headless to a PNG. The plugin does all the
//! rendering and owns the geometry conventions (`pom::preview::PreviewView`); this module defines
//! the options, checks them and hands them to the material preview or the scene preview.

use std::path::{Path, PathBuf};

use anyhow::{Context, Result};
use clap::Args;
use image::DynamicImage;
use pom::preview::{FramingView, PreviewView, spawn_preview};
use pom::{
    App, Assets, DebugView, HeightConvention, Image, ParallaxOcclusionMaterial, PomPlugin,
    RenderPlugin, TargetFormat,
};

use crate::cli_types::set_sun_illuminance;
use crate::cli_types::{
    CameraArg, DisplayArgs, EnvironmentArgs, PathArgs, ProjectionArg, ShadowArgs, ShapeArg,
    parse_camera, parse_finite, parse_lux, parse_png_path, parse_positive, parse_size,
    parse_view_angle,
};
use crate::frame_output;
use crate::material_args::{self, MaterialArgs, choice_parser};
use crate::preview_textures::{PreviewTextures, TextureFiles};
use crate::scene_preview::{self, ScenePreview};

/// Shown after the options by `render --help`. The geometry paragraph follows
/// `PreviewView`'s documentation, which is the authority on it.
const LONG_HELP_NOTES: &str = "\
Geometry conventions:
  Angles are in degrees. The view angle is between the view direction and the plane's
  normal (0 = looking straight down). With --projection ortho and --distance at its
  default, the plane fills the image. Azimuth 0 puts the camera on the −u side with its
  view ray's in-plane component along +u, so +u runs up the image and +v to the right;
  the azimuth turns that towards +v. The light uses the same frame: light angle 0 is
  straight above, 90 is the horizon, more is below it. Every --shape is one unit across
  and centred where the plane is, its top facing up as the plane does; a solid (cube,
  sphere, cylinder) is framed whole, so its outline shows (--silhouette).

Missing textures:
  Without --height, the shipped bricks (assets/bricks, embedded in the binary) are used,
  their colour too, so the command shows something useful. Without --normal, the normal
  map is derived from the height map by the plugin's Sobel filter, using --height-scale.
  Without --albedo, a height map of your own gets a neutral grey surface.

Output formats:
  --debug-view uv and --debug-view shadow write a 16-bit RGB PNG of raw values
  (value × 65535, clamped, no sRGB curve). Every other view writes an 8-bit sRGB PNG.

Scenes:
  --scene renders a glTF 2.0 file (.gltf with its files, or .glb) instead of the
  material preview; the texture and material options do not apply to it.
  --camera N looks through the file's N-th camera node (counting from 0, in a walk of
  the scene's nodes depth first, parents before children, siblings in file order);
  --camera auto frames the scene's meshes from a three-quarter view (a flat mesh more
  than four times wider than the rest, such as a ground plane, does not decide the
  framing). Without --camera, the file's first camera is used, or auto when it has
  none. --view-angle, --view-azimuth and --distance move the automatic camera (and
  imply it when --camera is not given). A scene without lights gets a default
  light (a sun and a soft ambient light) and a warning saying so. Features the
  renderer lacks are skipped with one warning each; the rest still renders.
  --debug-view applies to every parallax material in the scene.

Examples:
  sandbox render --height my_height.png --view-angle 60 --out preview.png
  sandbox render --scene street.glb --camera auto --size 1280x720 --out street.png";

fn view_default() -> PreviewView {
    PreviewView::default()
}

/// The options of `sandbox render`, in the groups `--help` shows them in.
#[derive(Debug, Args)]
#[command(after_long_help = LONG_HELP_NOTES)]
pub struct RenderArgs {
    #[command(flatten)]
    pub output: OutputArgs,
    #[command(flatten)]
    pub scene: SceneArgs,
    #[command(flatten)]
    pub textures: TextureArgs,
    #[command(flatten)]
    pub material: MaterialArgs,
    #[command(flatten)]
    pub view: ViewArgs,
    #[command(flatten)]
    pub display: DisplayArgs,
    #[command(flatten)]
    pub environment: EnvironmentArgs,
    /// Illuminance of the sun (every directional light, the preview's or the scene's) in lux;
    /// 0: no direct sunlight [default: as the scene says; the preview's sun 100,000].
    #[arg(long, value_name = "LUX", value_parser = parse_lux, help_heading = "Environment")]
    pub light_intensity: Option<f32>,
    #[command(flatten)]
    pub shadows: ShadowArgs,
    #[command(flatten)]
    pub path: PathArgs,
}

impl RenderArgs {
    /// Puts the environment and the sun's illuminance the flags give on `app`.
    fn apply_lights(&self, app: &mut App, environment: Option<pom::EnvironmentLight>) {
        if let Some(environment) = environment {
            app.insert_resource(environment);
        }
        if let Some(lux) = self.light_intensity {
            set_sun_illuminance(&mut app.world, lux);
        }
    }
}

/// Where the picture goes.
#[derive(Debug, Args)]
#[command(next_help_heading = "Output")]
pub struct OutputArgs {
    /// PNG file to write (its folder is created).
    #[arg(long, value_name = "FILE.png", value_parser = parse_png_path)]
    pub out: PathBuf,
    /// Image size as WIDTHxHEIGHT, each 1..=8192.
    #[arg(long, long_help, value_name = "WxH", default_value = "512x512", value_parser = parse_size)]
    pub size: (u32, u32),
    /// Output an inspection view instead of the lit colour (in a scene: on every parallax
    /// material).
    #[arg(long, value_name = "NAME", value_parser = choice_parser::<DebugView>(), default_value = "none")]
    pub debug_view: DebugView,
}

/// The options only the material preview uses, besides the material's own flags: every one of
/// `TextureArgs` and `ViewArgs`. Each conflicts with `--scene` by name, so the usage error names
/// the one given.
const PREVIEW_ONLY: [&str; 8] = [
    "height",
    "normal",
    "albedo",
    "light_angle",
    "light_azimuth",
    "projection",
    "tiling",
    "shape",
];

/// Every option `--scene` conflicts with: [`PREVIEW_ONLY`], `--preset` and every material flag.
fn material_preview_only() -> Vec<&'static str> {
    PREVIEW_ONLY
        .into_iter()
        .chain([material_args::PRESET])
        .chain(material_args::flag_parameters().map(|param| param.name))
        .collect()
}

/// A glTF scene instead of the material preview; the material preview's own options conflict
/// with it.
#[derive(Debug, Args)]
#[command(next_help_heading = "Scene")]
pub struct SceneArgs {
    /// glTF 2.0 scene (.gltf or .glb) to render instead of the material preview. A scene
    /// without lights gets a default light (a sun and a soft ambient light), with a warning.
    #[arg(
        long,
        long_help,
        value_name = "PATH",
        conflicts_with_all = material_preview_only()
    )]
    pub scene: Option<PathBuf>,
    /// The file's camera to look through, counting from 0, or auto for a three-quarter view
    /// of every mesh [default: 0, or auto when the file has no cameras].
    #[arg(long, value_name = "INDEX|auto", requires = "scene", value_parser = parse_camera)]
    pub camera: Option<CameraArg>,
}

/// The texture files; see `preview_textures` for what stands in for a missing one.
#[derive(Debug, Args)]
#[command(next_help_heading = "Textures")]
pub struct TextureArgs {
    /// Height map, red channel read, white = top unless --height-convention depth [default:
    /// the shipped bricks].
    #[arg(long, value_name = "PATH")]
    pub height: Option<PathBuf>,
    /// Tangent-space normal map, OpenGL convention [default: Sobel filter of the height map].
    #[arg(long, value_name = "PATH")]
    pub normal: Option<PathBuf>,
    /// sRGB colour texture [default: neutral grey].
    #[arg(long, value_name = "PATH")]
    pub albedo: Option<PathBuf>,
}

/// Camera and light placement, in `PreviewView`'s frame. `PreviewView` quietly replaces values
/// it cannot use, so the parsers reject them instead.
#[derive(Debug, Args)]
#[command(next_help_heading = "View")]
pub struct ViewArgs {
    /// Degrees between the view direction and the plane normal (0 = straight down, < 90); in a
    /// scene, from straight down, for the automatic camera [default: 0; in a scene 61.2].
    #[arg(
        long,
        value_name = "DEG",
        allow_negative_numbers = true,
        value_parser = parse_view_angle
    )]
    pub view_angle: Option<f32>,
    /// Degrees around the normal, from +u towards +v; in a scene, around the vertical from +Z
    /// (the front) towards +X [default: 0; in a scene 36.9].
    #[arg(
        long,
        value_name = "DEG",
        allow_negative_numbers = true,
        value_parser = parse_finite
    )]
    pub view_azimuth: Option<f32>,
    /// Degrees between the direction to the light and the plane normal (90 = horizon).
    #[arg(
        long,
        value_name = "DEG",
        allow_negative_numbers = true,
        value_parser = parse_finite,
        default_value_t = view_default().light_angle
    )]
    pub light_angle: f32,
    /// Degrees around the normal, from +u towards +v, as for the view.
    #[arg(
        long,
        long_help,
        value_name = "DEG",
        allow_negative_numbers = true,
        value_parser = parse_finite,
        default_value_t = view_default().light_azimuth
    )]
    pub light_azimuth: f32,
    /// How the camera projects.
    #[arg(long, long_help, value_enum, default_value_t = view_default().projection.into())]
    pub projection: ProjectionArg,
    /// Camera distance as a multiple of the default framing distance; < 1 zooms in (in a
    /// scene, for the automatic camera) [default: 1].
    #[arg(
        long,
        value_name = "F",
        allow_negative_numbers = true,
        value_parser = parse_positive
    )]
    pub distance: Option<f32>,
    /// UV repeats across the plane (UVs run 0..N).
    #[arg(
        long,
        value_name = "N",
        allow_negative_numbers = true,
        value_parser = parse_positive,
        default_value_t = view_default().tiling
    )]
    pub tiling: f32,
    /// What the material is shown on; each value's texture layout is listed with it.
    #[arg(long, long_help, value_enum, default_value = "plane")]
    pub shape: ShapeArg,
}

impl RenderArgs {
    /// The material's parameters, without textures.
    pub fn material_settings(&self) -> ParallaxOcclusionMaterial {
        ParallaxOcclusionMaterial {
            debug_view: self.output.debug_view,
            ..self.material.settings()
        }
    }

    /// Where the camera and the light are.
    pub fn view(&self) -> PreviewView {
        self.view.preview_view()
    }

    fn texture_files(&self) -> TextureFiles<'_> {
        self.textures
            .files(self.material.settings().height_convention)
    }
}

impl TextureArgs {
    /// The files named, for [`PreviewTextures::load`]; `convention` says what the height
    /// file's values mean.
    pub fn files(&self, convention: HeightConvention) -> TextureFiles<'_> {
        TextureFiles {
            height: self.height.as_deref(),
            convention,
            normal: self.normal.as_deref(),
            albedo: self.albedo.as_deref(),
        }
    }
}

impl ViewArgs {
    /// The camera and light these options describe.
    pub fn preview_view(&self) -> PreviewView {
        let default = view_default();
        PreviewView {
            view_angle: self.view_angle.unwrap_or(default.view_angle),
            view_azimuth: self.view_azimuth.unwrap_or(default.view_azimuth),
            light_angle: self.light_angle,
            light_azimuth: self.light_azimuth,
            projection: self.projection.into(),
            distance: self.distance.unwrap_or(default.distance),
            tiling: self.tiling,
            shape: self.shape.into(),
        }
    }

    /// The automatic camera of a scene, when any of its options was given.
    pub fn framing_view(&self) -> Option<FramingView> {
        if self.view_angle.is_none() && self.view_azimuth.is_none() && self.distance.is_none() {
            return None;
        }
        let default = FramingView::default();
        Some(FramingView {
            view_angle: self.view_angle.unwrap_or(default.view_angle),
            view_azimuth: self.view_azimuth.unwrap_or(default.view_azimuth),
            distance: self.distance.unwrap_or(default.distance),
        })
    }
}

/// Whether `view` is written as raw 16-bit values rather than an sRGB image.
pub fn writes_raw_values(view: DebugView) -> bool {
    matches!(view, DebugView::Uv | DebugView::Shadow)
}

/// Renders the material preview, or the `--scene` file, and writes it to `--out`.
pub fn run(args: &RenderArgs) -> Result<()> {
    match &args.scene.scene {
        Some(path) => render_scene(args, path),
        None => render_material(args),
    }
}

/// Checks the options, loads the textures, renders the material preview.
fn render_material(args: &RenderArgs) -> Result<()> {
    // Bad values and bad files are reported before the GPU starts: quicker, and nothing a GPU
    // driver prints on stderr can get mixed into the one-line error.
    let mut settings = args.material_settings();
    settings.validate().context("invalid material")?;
    let textures = PreviewTextures::load(&args.texture_files(), settings.height_scale)?;
    let layer_files = args.material.preset_layer_files().context("--preset")?;
    let environment = args.environment.light()?;

    let mut app = headless_app(&args.output, args.path);
    let images = app
        .resources
        .get_mut::<Assets<Image>>()
        .context("the render plugin provides no image store")?;
    if let Some(files) = layer_files {
        settings.layers = Some(files.into_layers(images).context("--preset")?);
    }
    let material = textures.attach(images, settings);
    spawn_preview(&mut app, material, &args.view()).context("setting up the preview")?;
    args.apply_lights(&mut app, environment);
    args.display.apply(&mut app);
    args.shadows.apply(&mut app.world);
    render_and_write(
        &mut app,
        &args.output,
        args.display.frames(),
        "rendering the preview",
    )
}

/// Loads the `--scene` file, picks its camera and lights, renders it. The GPU starts only once
/// the file has loaded, for the same reason as above.
fn render_scene(args: &RenderArgs, path: &Path) -> Result<()> {
    let environment = args.environment.light()?;
    let mut app = headless_app(&args.output, args.path);
    let (width, height) = args.output.size;
    let preview = ScenePreview {
        path,
        camera: args.scene.camera,
        framing: args.view.framing_view(),
        aspect: width as f32 / height as f32,
        debug_view: args.output.debug_view,
    };
    scene_preview::spawn(&mut app, &preview)?;
    args.apply_lights(&mut app, environment);
    args.display.apply(&mut app);
    args.shadows.apply(&mut app.world);
    render_and_write(
        &mut app,
        &args.output,
        args.display.frames(),
        "rendering the scene",
    )
}

/// An app with the headless renderer (a float target for the raw debug views) on `path`, and
/// the parallax material. The GPU starts on the first update.
fn headless_app(output: &OutputArgs, path: PathArgs) -> App {
    let format = if writes_raw_values(output.debug_view) {
        TargetFormat::Float32
    } else {
        TargetFormat::Srgb8
    };
    let (width, height) = output.size;
    let mut app = App::new();
    app.add_plugin(path.apply(RenderPlugin::new(width, height).with_format(format)));
    app.add_plugin(PomPlugin);
    app
}

/// Renders `frames` frames of the still scene (TAA's history settles over them) and writes the
/// last to `--out`: raw 16-bit values for the raw debug views, sRGB otherwise.
fn render_and_write(
    app: &mut App,
    output: &OutputArgs,
    frames: u32,
    what: &'static str,
) -> Result<()> {
    for _ in 0..frames.max(1) {
        app.update().context(what)?;
    }
    let image = if writes_raw_values(output.debug_view) {
        let frame = pom::capture_f32(app).context("reading the frame back")?;
        DynamicImage::ImageRgb16(frame_output::raw_rgb16(&frame))
    } else {
        let frame = pom::capture(app).context("reading the frame back")?;
        DynamicImage::ImageRgba8(frame)
    };
    frame_output::write(app, image, &output.out)
}

#[cfg(test)]
mod tests {
    use clap::Parser;

    use super::*;

    #[derive(Debug, Parser)]
    struct RenderOnly {
        #[command(flatten)]
        render: RenderArgs,
    }

    fn parse(args: &[&str]) -> Result<RenderArgs, clap::Error> {
        let all = ["render", "--out", "x.png"].iter().chain(args);
        RenderOnly::try_parse_from(all).map(|only| only.render)
    }

    #[test]
    fn defaults_are_the_plugins() {
        let args = parse(&[]).unwrap();
        assert_eq!(
            args.material_settings(),
            ParallaxOcclusionMaterial::default()
        );
        assert_eq!(args.view(), PreviewView::default());
        assert_eq!(args.output.size, (512, 512));
    }

    #[test]
    fn options_reach_the_material_and_the_view() {
        let args = parse(&[
            "--height",
            "h.png",
            "--height-convention",
            "depth",
            "--method",
            "relief",
            "--height-scale",
            "0.1",
            "--min-samples",
            "4",
            "--max-samples",
            "64",
            "--lod-threshold",
            "6",
            "--shadows",
            "hard",
            "--shadow-softening",
            "2",
            "--depth-offset",
            "--debug-view",
            "samples",
            "--view-angle",
            "60",
            "--view-azimuth",
            "-30",
            "--light-angle",
            "80",
            "--light-azimuth",
            "90",
            "--projection",
            "perspective",
            "--distance",
            "0.5",
            "--tiling",
            "3",
        ])
        .unwrap();
        let material = args.material_settings();
        assert_eq!(material.height_convention, HeightConvention::Depth);
        assert_eq!(material.method, pom::ParallaxMethod::Relief);
        assert_eq!(material.height_scale, 0.1);
        assert_eq!((material.min_samples, material.max_samples), (4, 64));
        assert_eq!(material.lod_threshold, 6.0);
        assert_eq!(material.shadows, pom::ShadowMode::Hard);
        assert_eq!(material.shadow_softening, 2.0);
        assert!(material.depth_offset);
        assert_eq!(material.debug_view, pom::DebugView::Samples);
        assert_eq!(
            args.view(),
            PreviewView {
                view_angle: 60.0,
                view_azimuth: -30.0,
                light_angle: 80.0,
                light_azimuth: 90.0,
                projection: pom::preview::PreviewProjection::Perspective,
                distance: 0.5,
                tiling: 3.0,
                shape: pom::preview::PreviewShape::Plane,
            }
        );
    }

    #[test]
    fn negative_and_nan_material_numbers_parse_so_validation_can_name_them() {
        let negative = parse(&["--height-scale", "-1"]).unwrap();
        assert_eq!(negative.material_settings().height_scale, -1.0);
        let nan = parse(&["--height-scale", "NaN"]).unwrap();
        assert!(nan.material_settings().validate().is_err());
    }

    #[test]
    fn a_scene_takes_the_output_options_and_a_camera() {
        let args = parse(&[
            "--scene",
            "city.glb",
            "--camera",
            "2",
            "--size",
            "64x32",
            "--debug-view",
            "uv",
        ])
        .unwrap();
        assert_eq!(args.scene.scene, Some(PathBuf::from("city.glb")));
        assert_eq!(args.scene.camera, Some(CameraArg::Index(2)));
        assert_eq!(args.output.size, (64, 32));
        assert_eq!(args.output.debug_view, DebugView::Uv);
        let auto = parse(&["--scene", "city.glb", "--camera", "auto"]).unwrap();
        assert_eq!(auto.scene.camera, Some(CameraArg::Auto));
        let default = parse(&["--scene", "city.glb"]).unwrap();
        assert_eq!(default.scene.camera, None, "the file decides");
    }

    #[test]
    fn only_uv_and_shadow_views_are_written_raw() {
        use pom::material::Choice;
        let raw: Vec<_> = DebugView::VALUES
            .iter()
            .filter(|view| writes_raw_values(**view))
            .collect();
        assert_eq!(raw, [&DebugView::Uv, &DebugView::Shadow]);
    }

    #[test]
    fn material_preview_options_conflict_with_a_scene() {
        for option in [
            &["--height", "h.png"][..],
            &["--height-convention", "depth"],
            &["--normal", "n.png"],
            &["--albedo", "a.png"],
            &["--method", "steep"],
            &["--height-scale", "0.1"],
            &["--min-samples", "4"],
            &["--max-samples", "64"],
            &["--lod-threshold", "3"],
            &["--shadows", "off"],
            &["--shadow-softening", "1"],
            &["--depth-offset"],
            &["--light-angle", "30"],
            &["--light-azimuth", "30"],
            &["--projection", "perspective"],
            &["--tiling", "2"],
        ] {
            let mut args = vec!["--scene", "city.glb"];
            args.extend_from_slice(option);
            let error = parse(&args).expect_err(&format!("{option:?} was accepted"));
            assert_eq!(error.kind(), clap::error::ErrorKind::ArgumentConflict);
        }
    }

    #[test]
    fn every_material_preview_option_conflicts_with_a_scene() {
        use clap::CommandFactory;
        // Clap derives one group per flattened struct, named after it, holding its options.
        // The view's camera options also move a scene's automatic camera.
        let command = RenderOnly::command();
        let mut preview_only: Vec<String> = command
            .get_groups()
            .filter(|group| {
                ["TextureArgs", "MaterialArgs", "ViewArgs"].contains(&group.get_id().as_str())
            })
            .flat_map(|group| group.get_args().map(|id| id.to_string()))
            .filter(|id| !["view_angle", "view_azimuth", "distance"].contains(&id.as_str()))
            .collect();
        preview_only.sort();
        let mut listed: Vec<String> = material_preview_only()
            .into_iter()
            .map(str::to_owned)
            .collect();
        listed.sort();
        assert_eq!(preview_only, listed);
    }

    #[test]
    fn scene_shadow_flags_parse_for_the_preview_and_a_scene() {
        use crate::cli_types::Switch;
        let defaults = parse(&[]).unwrap();
        assert_eq!(defaults.shadows.scene_shadows, Switch::On);
        assert_eq!(defaults.shadows.shadow_map_size, None);
        for scene in [&[][..], &["--scene", "city.glb"]] {
            let mut args = scene.to_vec();
            args.extend(["--scene-shadows", "off", "--shadow-map-size", "1024"]);
            let args = parse(&args).unwrap();
            assert_eq!(args.shadows.scene_shadows, Switch::Off);
            assert_eq!(args.shadows.shadow_map_size, Some(1024));
        }
        for bad in [
            &["--scene-shadows", "maybe"][..],
            &["--shadow-map-size", "0"],
            &["--shadow-map-size", "16384"],
            &["--shadow-map-size", "large"],
        ] {
            let error = parse(bad).expect_err(&format!("{bad:?} was accepted"));
            let rendered = error.render().to_string();
            assert!(rendered.contains(bad[0]), "{bad:?}: {rendered}");
        }
    }

    #[test]
    fn the_render_path_flag_parses_for_the_preview_and_a_scene() {
        use pom::RenderPath;
        assert_eq!(parse(&[]).unwrap().path.path, RenderPath::Auto);
        for path in RenderPath::ALL {
            for scene in [&[][..], &["--scene", "city.glb"]] {
                let mut args = scene.to_vec();
                args.extend(["--path", path.name()]);
                assert_eq!(parse(&args).unwrap().path.path, path);
            }
        }
    }

    #[test]
    fn a_bad_render_path_is_rejected_naming_the_flag_and_the_choices() {
        for bad in ["fast", "Deferred", ""] {
            let error = parse(&["--path", bad]).expect_err(&format!("{bad:?} was accepted"));
            assert_eq!(error.kind(), clap::error::ErrorKind::ValueValidation);
            let rendered = error.render().to_string();
            for expected in ["--path", "forward", "deferred", "auto"] {
                assert!(rendered.contains(expected), "{bad:?}: {rendered}");
            }
        }
    }

    #[test]
    fn a_camera_needs_a_scene() {
        let error = parse(&["--camera", "1"]).unwrap_err();
        assert_eq!(
            error.kind(),
            clap::error::ErrorKind::MissingRequiredArgument
        );
    }

    #[test]
    fn out_is_required() {
        assert!(RenderOnly::try_parse_from(["render"]).is_err());
    }
}
