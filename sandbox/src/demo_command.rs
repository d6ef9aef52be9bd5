//! `sandbox snapshot`: the scene the window opens on, rendered headless to a PNG (what
//! `sandbox` did without a subcommand before the window existed).

use std::path::PathBuf;

use anyhow::{Context, Result};
use clap::Args;

use pom::hecs::World;
use pom::{ParallaxOcclusionMaterial, PomPreset};

use crate::cli_types::{DisplayArgs, EnvironmentArgs, PathArgs, ShadowArgs, parse_size};
use crate::material_args::parse_preset;
use crate::{demo_scene, frame_output};

/// Options of the `snapshot` command.
#[derive(Debug, Args)]
pub struct DemoArgs {
    /// Where to write the PNG.
    #[arg(
        long,
        long_help,
        value_name = "FILE",
        default_value = "target/sandbox-preview.png"
    )]
    pub out: PathBuf,
    /// Image size as WIDTHxHEIGHT, each 1..=8192.
    #[arg(long, long_help, value_name = "WxH", default_value = "960x540", value_parser = parse_size)]
    pub size: (u32, u32),
    /// RON material preset, as the window saves it (the format is in
    /// plugin/docs/authoring-materials.md), put on every parallax material of the scene: each
    /// keeps its textures and takes the preset's parameters, all but its debug view (a
    /// snapshot shows the lit scene).
    #[arg(long, long_help, value_name = "FILE.ron", value_parser = parse_preset)]
    pub preset: Option<PomPreset>,
    #[command(flatten)]
    pub display: DisplayArgs,
    #[command(flatten)]
    pub environment: EnvironmentArgs,
    #[command(flatten)]
    pub shadows: ShadowArgs,
    #[command(flatten)]
    pub path: PathArgs,
}

/// Renders the demo scene and writes it to `args.out`.
pub fn run(args: &DemoArgs) -> Result<()> {
    let (width, height) = args.size;
    let environment = args.environment.light()?;
    let mut app = pom::App::new();
    app.add_plugin(args.path.apply(pom::RenderPlugin::new(width, height)))
        .add_plugin(pom::PomPlugin);
    demo_scene::spawn(&mut app)?;
    if let Some(preset) = &args.preset {
        apply_to_every_material(&mut app.world, preset);
    }
    if let Some(environment) = environment {
        app.insert_resource(environment);
    }
    args.display.apply(&mut app);
    args.shadows.apply(&mut app.world);
    for _ in 0..args.display.frames() {
        app.update().context("rendering the demo scene")?;
    }
    let image = pom::capture(&app).context("reading the frame back")?;
    frame_output::write(&app, image.into(), &args.out)
}

/// Puts `preset`'s parameters on every parallax material of `world`, keeping their textures
/// and debug views.
fn apply_to_every_material(world: &mut World, preset: &PomPreset) {
    for material in world.query_mut::<&mut ParallaxOcclusionMaterial>() {
        let debug_view = material.debug_view;
        material.apply_preset(preset);
        material.debug_view = debug_view;
    }
}
