//! The sandbox: without a subcommand, the street-corner demo scene (rendered headless to a PNG
//! until the live window lands); `render` previews one parallax material or a glTF scene
//! headless; `generate-assets` rebuilds the shipped assets.

mod asset_generator;
mod cli_types;
mod demo_command;
mod demo_scene;
mod frame_output;
mod preview_textures;
mod render_command;
mod scene_preview;

use clap::{Parser, Subcommand};

/// The POM sandbox. Without a subcommand it renders the demo scene to a PNG.
#[derive(Debug, Parser)]
#[command(name = "sandbox", version, args_conflicts_with_subcommands = true)]
struct Cli {
    #[command(subcommand)]
    command: Option<Command>,
    #[command(flatten)]
    demo: demo_command::DemoArgs,
}

#[derive(Debug, Subcommand)]
enum Command {
    /// Renders one parallax material on a square plane (or, with --scene, a glTF scene) to a PNG.
    Render(render_command::RenderArgs),
    /// Writes the shipped material set (albedo, normal and height maps) and the street-corner
    /// scene, from fixed seeds: the result is the same every time.
    GenerateAssets {
        /// Folder to write into [default: the repository's assets/ folder].
        #[arg(long, value_name = "DIR")]
        out: Option<std::path::PathBuf>,
    },
}

/// Clap's usage errors add a tip, the usage and a pointer to --help over several lines; the
/// first paragraph says what is wrong, so print that as one line, like every other error here.
fn first_paragraph_on_one_line(rendered: &str) -> String {
    rendered
        .split("\n\n")
        .next()
        .unwrap_or_default()
        .lines()
        .map(str::trim)
        .filter(|line| !line.is_empty())
        .collect::<Vec<_>>()
        .join(" ")
}

fn main() {
    let cli = Cli::try_parse().unwrap_or_else(|error| {
        if !error.use_stderr() {
            // --help and --version: not errors.
            error.exit();
        }
        eprintln!(
            "{}",
            first_paragraph_on_one_line(&error.render().to_string())
        );
        std::process::exit(error.exit_code());
    });
    let result = match &cli.command {
        None => demo_command::run(&cli.demo),
        Some(Command::Render(args)) => render_command::run(args),
        Some(Command::GenerateAssets { out }) => {
            let out = out.clone().unwrap_or_else(asset_generator::default_output);
            asset_generator::generate(&out).map(|files| {
                for file in files {
                    println!("wrote {}", file.display());
                }
            })
        }
    };
    if let Err(error) = result {
        // One line, no backtrace: the chain of contexts says what failed and why.
        eprintln!("error: {error:#}");
        std::process::exit(1);
    }
}

#[cfg(test)]
mod tests {
    use clap::CommandFactory;

    use super::*;

    #[test]
    fn the_definitions_are_consistent() {
        Cli::command().debug_assert();
    }

    #[test]
    fn no_subcommand_is_the_demo_with_todays_defaults() {
        let cli = Cli::try_parse_from(["sandbox"]).unwrap();
        assert!(cli.command.is_none());
        assert_eq!(
            cli.demo.out,
            std::path::Path::new("target/sandbox-preview.png")
        );
        assert_eq!(cli.demo.size, (960, 540));
        let sized = Cli::try_parse_from(["sandbox", "--size", "64x32"]).unwrap();
        assert_eq!(sized.demo.size, (64, 32));
    }

    #[test]
    fn unknown_flags_are_rejected() {
        assert!(Cli::try_parse_from(["sandbox", "--bogus"]).is_err());
        assert!(Cli::try_parse_from(["sandbox", "--size", "12"]).is_err());
        assert!(Cli::try_parse_from(["sandbox", "render", "--out", "a.png", "--bogus"]).is_err());
        // The demo's options do not leak into `render`, nor the other way round.
        assert!(Cli::try_parse_from(["sandbox", "--out", "a.png", "render"]).is_err());
    }

    #[test]
    fn usage_errors_become_one_line() {
        let error = Cli::try_parse_from(["sandbox", "render", "--out", "a.png", "--method", "x"])
            .unwrap_err();
        let line = first_paragraph_on_one_line(&error.render().to_string());
        assert!(!line.contains('\n'), "{line}");
        assert!(
            line.starts_with("error: invalid value 'x' for '--method"),
            "{line}"
        );
        assert!(line.contains("possible values: normal, offset, steep, pom, relief"));
    }

    #[test]
    fn render_help_documents_the_geometry_and_the_defaults() {
        let mut command = Cli::command();
        let render = command.find_subcommand_mut("render").unwrap();
        let help = render.render_long_help().to_string();
        for expected in [
            "view angle is between the view direction and the plane's",
            "the plane fills the image",
            "Azimuth 0 puts the camera on the −u side",
            "+u runs up the image and +v to the right",
            "90 is the horizon",
            "the shipped bricks",
            "[default: pom]",
            "[default: 0.05]",
            "[default: 8]",
            "[default: 50]",
            "[default: soft]",
            "[default: 0.58]",
            "[default: ortho]",
            "[default: 45]",
        ] {
            assert!(
                help.contains(expected),
                "--help lacks {expected:?}:\n{help}"
            );
        }
    }
}
