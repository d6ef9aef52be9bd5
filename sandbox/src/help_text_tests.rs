//! Every option of the rendering commands says what it does in whole sentences: `--help` shows
//! each description as written, so one cut short (a doc comment's first line only) shows.

use clap::CommandFactory;

use crate::Cli;

/// Whether `text` ends a sentence: a full stop, or a bracket closing one (`… (default 1).`
/// ends with the stop; `[default: …]` and `(…)` close a sentence's remark).
fn ends_a_sentence(text: &str) -> bool {
    text.trim_end().ends_with(['.', '!', '?', ')', ']'])
}

/// Every option's description `SUBCOMMAND --help` shows that does not end a sentence.
fn unfinished_descriptions(subcommand: &str) -> Vec<String> {
    let mut command = Cli::command();
    command.build();
    let command = command
        .find_subcommand(subcommand)
        .unwrap_or_else(|| panic!("no subcommand {subcommand}"));
    let mut unfinished = Vec::new();
    for arg in command.get_arguments() {
        let help = arg
            .get_long_help()
            .or(arg.get_help())
            .map(ToString::to_string)
            .unwrap_or_default();
        if !ends_a_sentence(&help) {
            unfinished.push(format!("--{}: {help:?}", arg.get_id()));
        }
    }
    unfinished
}

#[test]
fn every_render_and_snapshot_description_ends_a_sentence() {
    for subcommand in ["render", "snapshot"] {
        let unfinished = unfinished_descriptions(subcommand);
        assert!(
            unfinished.is_empty(),
            "{subcommand} --help has descriptions that stop mid-sentence:\n{}",
            unfinished.join("\n")
        );
    }
}
