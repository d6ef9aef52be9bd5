//! `sandbox run-script`: runs scene scripts headless and reports each step.

use std::path::PathBuf;

use anyhow::{Result, bail};
use clap::Args;

use crate::cli_types::PathArgs;

/// Where `run-script --help` sends a reader for the script format.
pub const FORMAT_DOC: &str = "The script format (entities, steps, statistics, tolerances, \
    with examples): plugin/docs/scene-tests.md";

/// Options of `run-script`.
#[derive(Debug, Args)]
#[command(after_help = FORMAT_DOC)]
pub struct ScriptArgs {
    /// Scene script files (RON).
    #[arg(required = true, value_name = "FILE")]
    pub scripts: Vec<PathBuf>,
    /// Write missing or changed reference images instead of failing (look at them first).
    #[arg(long)]
    pub bless: bool,
    /// Folder for the actual and difference images of failed comparisons [default: next to
    /// each reference].
    #[arg(long, value_name = "DIR")]
    pub out: Option<PathBuf>,
    /// Let scripts name files outside their own folder (maps, glTF files, presets, references
    /// written by --bless): only for scripts you trust.
    #[arg(long)]
    pub allow_outside_paths: bool,
    #[command(flatten)]
    pub path: PathArgs,
}

/// Runs every script, prints one line per step (a capture's names the path its frame was shaded
/// on, so a deferred run that fell back to forward shows), fails when any expectation or script
/// failed.
pub fn run(args: &ScriptArgs) -> Result<()> {
    let options = pom::RunOptions {
        bless: args.bless,
        out_dir: args.out.clone(),
        path: args.path.path,
        file_access: if args.allow_outside_paths {
            pom::files::FileAccess::AnyPath
        } else {
            pom::files::FileAccess::InsideFolder
        },
    };
    let mut failed = 0;
    for script in &args.scripts {
        match pom::run_script_with(script, &options) {
            Ok(report) => {
                print!("{report}");
                failed += usize::from(!report.passed());
            }
            Err(error) => {
                // A script that stopped midway still reports the steps it ran.
                if let pom::ScriptError::Step { report, .. } = &error {
                    print!("{report}");
                }
                eprintln!("error: {error}");
                failed += 1;
            }
        }
    }
    if failed > 0 {
        bail!("{failed} of {} scripts failed", args.scripts.len());
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use clap::CommandFactory;

    use super::*;

    #[test]
    fn help_points_to_the_script_format() {
        let mut command = crate::Cli::command();
        let run_script = command
            .find_subcommand_mut("run-script")
            .expect("sandbox has run-script");
        let help = run_script.render_long_help().to_string();
        assert!(help.contains(FORMAT_DOC), "{help}");
    }
}
