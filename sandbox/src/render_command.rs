//! `sandbox render`: one parallax material on the plugin's preview plane, rendered headless to a
//! PNG. The plugin does all the rendering and owns the geometry conventions
//! (`pom::preview::PreviewView`); this module turns options into its inputs and checks them.

use std::path::PathBuf;

use anyhow::{Context, Result};
use clap::Args;
use image::DynamicImage;
use pom::preview::{PreviewView, spawn_preview};
use pom::{
    App, Assets, HeightConvention, Image, ParallaxOcclusionMaterial, PomPlugin, RenderPlugin,
    TargetFormat,
};

use crate::cli_types::{
    DebugViewArg, MethodArg, ProjectionArg, ShadowsArg, parse_finite, parse_png_path,
    parse_positive, parse_size, parse_view_angle,
};
use crate::frame_output;
use crate::preview_textures::{PreviewTextures, TextureFiles};

/// Shown after the options by `render --help`. The geometry paragraph follows
/// `PreviewView`'s documentation, which is the authority on it.
const LONG_HELP_NOTES: &str = "\
Geometry conventions:
  Angles are in degrees. The view angle is between the view direction and the plane's
  normal (0 = looking straight down). With --projection ortho and --distance at its
  default, the plane fills the image. Azimuth 0 puts the camera on the −u side with its
  view ray's in-plane component along +u, so +u runs up the image and +v to the right;
  the azimuth turns that towards +v. The light uses the same frame: light angle 0 is
  straight above, 90 is the horizon, more is below it.

Missing textures:
  Without --height, built-in procedural bricks are used (4 × 8 running-bond bricks per
  tile, 256×256 texels) so the command shows something useful. Without --normal, the
  normal map is derived from the height map by the plugin's Sobel filter, using
  --height-scale. Without --albedo, the surface is a neutral grey.

Output formats:
  --debug-view uv and --debug-view shadow write a 16-bit RGB PNG of raw values
  (value × 65535, clamped, no sRGB curve). Every other view writes an 8-bit sRGB PNG.

Example:
  sandbox render --height my_height.png --view-angle 60 --out preview.png";

fn material_default() -> ParallaxOcclusionMaterial {
    ParallaxOcclusionMaterial::default()
}

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
    pub textures: TextureArgs,
    #[command(flatten)]
    pub material: MaterialArgs,
    #[command(flatten)]
    pub view: ViewArgs,
}

/// Where the picture goes.
#[derive(Debug, Args)]
#[command(next_help_heading = "Output")]
pub struct OutputArgs {
    /// PNG file to write (its folder is created).
    #[arg(long, value_name = "FILE.png", value_parser = parse_png_path)]
    pub out: PathBuf,
    /// Image size as WIDTHxHEIGHT, each 1..=8192.
    #[arg(long, value_name = "WxH", default_value = "512x512", value_parser = parse_size)]
    pub size: (u32, u32),
}

/// The texture files; see `preview_textures` for what stands in for a missing one.
#[derive(Debug, Args)]
#[command(next_help_heading = "Textures")]
pub struct TextureArgs {
    /// Height map, white = top, red channel read [default: procedural bricks].
    #[arg(long, value_name = "PATH")]
    pub height: Option<PathBuf>,
    /// The --height file is a depth map: white is the deepest point.
    #[arg(long, requires = "height")]
    pub depth_map: bool,
    /// Tangent-space normal map, OpenGL convention [default: Sobel filter of the height map].
    #[arg(long, value_name = "PATH")]
    pub normal: Option<PathBuf>,
    /// sRGB colour texture [default: neutral grey].
    #[arg(long, value_name = "PATH")]
    pub albedo: Option<PathBuf>,
}

/// The material's parameters. Numbers are checked by `ParallaxOcclusionMaterial::validate`,
/// not here, so the limits live in one place; NaN and negative numbers must therefore parse.
#[derive(Debug, Args)]
#[command(next_help_heading = "Material")]
pub struct MaterialArgs {
    /// How the view ray meets the height field.
    #[arg(long, value_enum, default_value_t = material_default().method.into())]
    pub method: MethodArg,
    /// Depth of the relief from white to black, in texture-coordinate units.
    #[arg(
        long,
        value_name = "F",
        allow_negative_numbers = true,
        default_value_t = material_default().height_scale
    )]
    pub height_scale: f32,
    /// Height samples when looking straight at the surface.
    #[arg(long, value_name = "N", default_value_t = material_default().min_samples)]
    pub min_samples: u32,
    /// Height samples at grazing angles (at least --min-samples).
    #[arg(long, value_name = "N", default_value_t = material_default().max_samples)]
    pub max_samples: u32,
    /// Mip level past which only normal mapping runs.
    #[arg(
        long,
        value_name = "F",
        allow_negative_numbers = true,
        default_value_t = material_default().lod_threshold
    )]
    pub lod_threshold: f32,
    /// Self-shadowing of the relief.
    #[arg(long, value_enum, default_value_t = material_default().shadows.into())]
    pub shadows: ShadowsArg,
    /// Penumbra width of soft shadows: larger is softer.
    #[arg(
        long,
        value_name = "F",
        allow_negative_numbers = true,
        default_value_t = material_default().shadow_softening
    )]
    pub shadow_softening: f32,
    /// Write the depth of the displaced point instead of the polygon's.
    #[arg(long)]
    pub depth_offset: bool,
    /// Output an inspection view instead of the lit colour.
    #[arg(long, value_enum, default_value_t = material_default().debug_view.into())]
    pub debug_view: DebugViewArg,
}

/// Camera and light placement, in `PreviewView`'s frame. `PreviewView` quietly replaces values
/// it cannot use, so the parsers reject them instead.
#[derive(Debug, Args)]
#[command(next_help_heading = "View")]
pub struct ViewArgs {
    /// Degrees between the view direction and the plane normal (0 = straight down, < 90).
    #[arg(
        long,
        value_name = "DEG",
        allow_negative_numbers = true,
        value_parser = parse_view_angle,
        default_value_t = view_default().view_angle
    )]
    pub view_angle: f32,
    /// Degrees around the normal, from +u towards +v.
    #[arg(
        long,
        value_name = "DEG",
        allow_negative_numbers = true,
        value_parser = parse_finite,
        default_value_t = view_default().view_azimuth
    )]
    pub view_azimuth: f32,
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
        value_name = "DEG",
        allow_negative_numbers = true,
        value_parser = parse_finite,
        default_value_t = view_default().light_azimuth
    )]
    pub light_azimuth: f32,
    /// How the camera projects.
    #[arg(long, value_enum, default_value_t = view_default().projection.into())]
    pub projection: ProjectionArg,
    /// Camera distance as a multiple of the default framing distance; < 1 zooms in.
    #[arg(
        long,
        value_name = "F",
        allow_negative_numbers = true,
        value_parser = parse_positive,
        default_value_t = view_default().distance
    )]
    pub distance: f32,
    /// UV repeats across the plane (UVs run 0..N).
    #[arg(
        long,
        value_name = "N",
        allow_negative_numbers = true,
        value_parser = parse_positive,
        default_value_t = view_default().tiling
    )]
    pub tiling: f32,
}

impl RenderArgs {
    /// The material's parameters, without textures.
    pub fn material_settings(&self) -> ParallaxOcclusionMaterial {
        let material = &self.material;
        ParallaxOcclusionMaterial {
            height_convention: if self.textures.depth_map {
                HeightConvention::Depth
            } else {
                HeightConvention::Height
            },
            height_scale: material.height_scale,
            min_samples: material.min_samples,
            max_samples: material.max_samples,
            lod_threshold: material.lod_threshold,
            shadows: material.shadows.into(),
            shadow_softening: material.shadow_softening,
            method: material.method.into(),
            depth_offset: material.depth_offset,
            debug_view: material.debug_view.into(),
            ..ParallaxOcclusionMaterial::default()
        }
    }

    /// Where the camera and the light are.
    pub fn view(&self) -> PreviewView {
        let view = &self.view;
        PreviewView {
            view_angle: view.view_angle,
            view_azimuth: view.view_azimuth,
            light_angle: view.light_angle,
            light_azimuth: view.light_azimuth,
            projection: view.projection.into(),
            distance: view.distance,
            tiling: view.tiling,
        }
    }

    fn texture_files(&self) -> TextureFiles<'_> {
        let textures = &self.textures;
        TextureFiles {
            height: textures.height.as_deref(),
            depth_map: textures.depth_map,
            normal: textures.normal.as_deref(),
            albedo: textures.albedo.as_deref(),
        }
    }
}

/// Checks the options, loads the textures, renders the preview and writes it to `--out`.
pub fn run(args: &RenderArgs) -> Result<()> {
    // Bad values and bad files are reported before the GPU starts: quicker, and nothing a GPU
    // driver prints on stderr can get mixed into the one-line error.
    let settings = args.material_settings();
    settings.validate().context("invalid material")?;
    let textures = PreviewTextures::load(&args.texture_files(), settings.height_scale)?;

    let raw = args.material.debug_view.writes_raw_values();
    let format = if raw {
        TargetFormat::Float32
    } else {
        TargetFormat::Srgb8
    };
    let (width, height) = args.output.size;
    let mut app = App::new();
    app.add_plugin(RenderPlugin::headless(width, height).with_format(format));
    app.add_plugin(PomPlugin);
    let images = app
        .resources
        .get_mut::<Assets<Image>>()
        .context("the render plugin provides no image store")?;
    let material = textures.attach(images, settings);
    spawn_preview(&mut app, material, &args.view()).context("setting up the preview")?;
    app.update().context("rendering the preview")?;

    let image = if raw {
        let frame = pom::capture_f32(&app).context("reading the frame back")?;
        DynamicImage::ImageRgb16(frame_output::raw_rgb16(&frame))
    } else {
        let frame = pom::capture(&app).context("reading the frame back")?;
        DynamicImage::ImageRgba8(frame)
    };
    frame_output::write(&app, image, &args.output.out)
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
            "--depth-map",
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
        assert_eq!(
            material.method,
            pom::ParallaxMethod::Relief { binary_steps: 6 }
        );
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
            }
        );
    }

    #[test]
    fn negative_and_nan_material_numbers_parse_so_validation_can_name_them() {
        let negative = parse(&["--height-scale", "-1"]).unwrap();
        assert_eq!(negative.material.height_scale, -1.0);
        let nan = parse(&["--height-scale", "NaN"]).unwrap();
        assert!(nan.material_settings().validate().is_err());
    }

    #[test]
    fn a_depth_map_needs_a_height_file() {
        assert!(parse(&["--depth-map"]).is_err());
    }

    #[test]
    fn out_is_required() {
        assert!(RenderOnly::try_parse_from(["render"]).is_err());
    }
}
