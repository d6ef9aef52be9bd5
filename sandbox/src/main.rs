//! The sandbox: without a subcommand, a window on the street-corner scene where every parameter
//! of the parallax material can be tuned live; `snapshot` renders that scene headless to a PNG;
//! `render` previews one parallax material or a glTF scene headless; `generate-assets` rebuilds
//! the shipped assets.

mod asset_generator;
mod bench;
mod cli_types;
mod demo_command;
mod demo_scene;
mod frame_output;
#[cfg(test)]
mod help_text_tests;
mod material_args;
#[cfg(test)]
mod preset_flag_tests;
mod preview_textures;
mod render_command;
mod scene_preview;
mod script_command;
mod settings_args;
mod window;

use clap::{Parser, Subcommand};

/// The POM sandbox. Without a subcommand it opens a window for tuning parallax materials live.
#[derive(Debug, Parser)]
#[command(name = "sandbox", version, args_conflicts_with_subcommands = true)]
struct Cli {
    #[command(subcommand)]
    command: Option<Command>,
    #[command(flatten)]
    window: window::WindowArgs,
}

#[derive(Debug, Subcommand)]
enum Command {
    /// Renders the street-corner scene (what the window opens on) headless to a PNG.
    Snapshot(Box<demo_command::DemoArgs>),
    /// Renders one parallax material on a square plane (or, with --scene, a glTF scene) to a PNG.
    Render(Box<render_command::RenderArgs>),
    /// Writes the shipped material set (albedo, normal and height maps) and the street-corner
    /// scene, from fixed seeds: the result is the same every time.
    GenerateAssets {
        /// Folder to write into [default: the repository's assets/ folder].
        #[arg(long, value_name = "DIR")]
        out: Option<std::path::PathBuf>,
    },
    /// Runs scene scripts (RON) headless: one line per step, non-zero exit when any
    /// expectation fails.
    RunScript(script_command::ScriptArgs),
    /// Times the material's GPU passes (timestamp queries) and the CPU side; writes JSON, CSV
    /// and a PNG chart. See sandbox/BENCHMARKS.md.
    Bench(Box<bench::BenchArgs>),
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

/// Turns Mesa's Vulkan device-select layer off for a headless command, unless the user set
/// `NODEVICE_SELECT` themselves. The layer connects to a Wayland display to rank GPUs and, on a
/// machine without a desktop session, prints `XDG_RUNTIME_DIR is invalid or not set` twice,
/// although nothing is wrong; wgpu picks the adapter itself (`WGPU_ADAPTER_NAME`,
/// `WGPU_POWER_PREF`).
fn quiet_device_select_layer() {
    if std::env::var_os("NODEVICE_SELECT").is_none() {
        // SAFETY: called first thing in `main`, before any other thread exists.
        unsafe { std::env::set_var("NODEVICE_SELECT", "1") };
    }
}

fn main() {
    // The library logs its clamps and device limits; without a logger they would be lost.
    pom::log_to_stderr();
    // Every command but the window (no subcommand) is headless.
    if std::env::args_os().nth(1).is_some() {
        quiet_device_select_layer();
    }
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
        None => window::run(&cli.window),
        Some(Command::Snapshot(args)) => demo_command::run(args),
        Some(Command::Render(args)) => render_command::run(args),
        Some(Command::RunScript(args)) => script_command::run(args),
        Some(Command::Bench(args)) => bench::run(args),
        Some(Command::GenerateAssets { out }) => {
            let out = match out {
                Some(out) => Ok(out.clone()),
                None => asset_generator::default_output(),
            };
            out.and_then(|out| asset_generator::generate(&out))
                .map(|files| {
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
    fn snapshot_is_the_former_default_with_its_defaults() {
        let cli = Cli::try_parse_from(["sandbox", "snapshot"]).unwrap();
        let Some(Command::Snapshot(demo)) = cli.command else {
            panic!("not the snapshot command: {cli:?}");
        };
        assert_eq!(demo.out, std::path::Path::new("target/sandbox-preview.png"));
        assert_eq!(demo.size, (960, 540));
        let sized = Cli::try_parse_from(["sandbox", "snapshot", "--size", "64x32"]).unwrap();
        let Some(Command::Snapshot(demo)) = sized.command else {
            panic!("not the snapshot command");
        };
        assert_eq!(demo.size, (64, 32));
    }

    #[test]
    fn no_subcommand_is_the_window_with_its_automation_flags() {
        let cli = Cli::try_parse_from(["sandbox"]).unwrap();
        assert!(cli.command.is_none());
        assert_eq!(cli.window.exit_after_frames, None);
        let scripted = Cli::try_parse_from([
            "sandbox",
            "--scene",
            "a.glb",
            "--exit-after-frames",
            "5",
            "--screenshot",
            "shot.png",
            "--state",
            "state.ron",
        ])
        .unwrap();
        assert_eq!(scripted.window.exit_after_frames, Some(5));
        assert_eq!(
            scripted.window.screenshot.as_deref(),
            Some(std::path::Path::new("shot.png"))
        );
        assert_eq!(
            scripted.window.scene.as_deref(),
            Some(std::path::Path::new("a.glb"))
        );
    }

    #[test]
    fn unknown_flags_are_rejected() {
        assert!(Cli::try_parse_from(["sandbox", "--bogus"]).is_err());
        assert!(Cli::try_parse_from(["sandbox", "snapshot", "--size", "12"]).is_err());
        assert!(Cli::try_parse_from(["sandbox", "render", "--out", "a.png", "--bogus"]).is_err());
        // The window's options do not leak into `render`, nor the other way round.
        assert!(Cli::try_parse_from(["sandbox", "--scene", "a.glb", "render"]).is_err());
        assert!(Cli::try_parse_from(["sandbox", "--out", "a.png"]).is_err());
    }

    #[test]
    fn every_rendering_command_takes_a_render_path() {
        use pom::RenderPath;
        let paths_of = |args: &[&str]| match Cli::try_parse_from(args).unwrap().command {
            Some(Command::Render(render)) => vec![render.path.path],
            Some(Command::Snapshot(demo)) => vec![demo.path.path],
            Some(Command::Bench(bench)) => bench.path.paths(),
            Some(Command::RunScript(script)) => vec![script.path.path],
            other => panic!("not a rendering command: {other:?}"),
        };
        let commands: [&[&str]; 4] = [
            &["sandbox", "render", "--out", "a.png"],
            &["sandbox", "snapshot"],
            &["sandbox", "bench"],
            &["sandbox", "run-script", "a.ron"],
        ];
        for command in commands {
            assert_eq!(paths_of(command), [RenderPath::Auto], "{command:?}");
            let mut args = command.to_vec();
            args.extend(["--path", "deferred"]);
            assert_eq!(paths_of(&args), [RenderPath::Deferred], "{args:?}");
            let mut bad = command.to_vec();
            bad.extend(["--path", "fastest"]);
            let error = Cli::try_parse_from(&bad).unwrap_err();
            let line = first_paragraph_on_one_line(&error.render().to_string());
            assert_eq!(
                line,
                "error: invalid value 'fastest' for '--path <forward|deferred|auto>': unknown \
                 render path \"fastest\": expected forward, deferred or auto"
            );
        }
    }

    #[test]
    fn bench_takes_the_path_more_than_once_and_the_others_once() {
        use pom::RenderPath;
        let both = [
            "sandbox", "bench", "--path", "forward", "--path", "deferred",
        ];
        let Some(Command::Bench(bench)) = Cli::try_parse_from(both).unwrap().command else {
            panic!("not the bench command");
        };
        assert_eq!(
            bench.path.paths(),
            [RenderPath::Forward, RenderPath::Deferred]
        );
        let twice = [
            "sandbox", "snapshot", "--path", "forward", "--path", "deferred",
        ];
        assert!(Cli::try_parse_from(twice).is_err());
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
