//! The command-line flags of a declared settings struct (TAA's, FXAA's), one per parameter of
//! its table, `--PREFIX-name-with-dashes`: names, help, defaults and limits come from the
//! declaration, through the same flag builder as the material's flags. A value outside its
//! limits is a usage error naming them.

use std::collections::HashSet;
use std::marker::PhantomData;
use std::sync::{Mutex, OnceLock};

use clap::parser::ValueSource;
use clap::{ArgMatches, Args, Command, FromArgMatches};
use pom::material::{Param, ParamKind, ParamValue};
use pom::parameters::DeclaredSettings;

use crate::material_args::flag;

/// A settings struct with command-line flags.
pub trait FlagSettings: DeclaredSettings + std::fmt::Debug {
    /// The flags' prefix: `--PREFIX-name`.
    const PREFIX: &'static str;
    /// What the help texts call the settings.
    const TITLE: &'static str;
}

impl FlagSettings for pom::TemporalAntiAliasing {
    const PREFIX: &'static str = "taa";
    const TITLE: &'static str = "TAA";
}

impl FlagSettings for pom::EnvironmentSettings {
    const PREFIX: &'static str = "environment";
    const TITLE: &'static str = "the environment";
}

impl FlagSettings for pom::FastApproximateAntiAliasing {
    const PREFIX: &'static str = "fxaa";
    const TITLE: &'static str = "FXAA";
}

/// `text`, kept for the rest of the run (clap keeps `&'static str`s); each distinct text is
/// kept once, so building the command again keeps nothing more.
fn kept(text: String) -> &'static str {
    static TEXTS: OnceLock<Mutex<HashSet<&'static str>>> = OnceLock::new();
    let mut texts = TEXTS
        .get_or_init(Default::default)
        .lock()
        .unwrap_or_else(std::sync::PoisonError::into_inner);
    if let Some(text) = texts.get(text.as_str()) {
        return text;
    }
    let text: &'static str = Box::leak(text.into_boxed_str());
    texts.insert(text);
    text
}

/// The id of `param`'s flag: `PREFIX_name`.
fn id_of<S: FlagSettings>(param: &Param<S>) -> &'static str {
    kept(format!("{}_{}", S::PREFIX, param.name))
}

/// The limits of a number, for the help text.
fn limits(kind: &ParamKind) -> String {
    match kind {
        ParamKind::Float { min, max, .. } => format!(" [limits: {min}..={max}]"),
        ParamKind::Integer { min, max, .. } => format!(" [limits: {min}..={max}]"),
        _ => String::new(),
    }
}

/// The flags of settings `S` as given on the command line.
#[derive(Clone, Debug, PartialEq)]
pub struct SettingsArgs<S> {
    /// The flags given explicitly (a flag left out keeps the default).
    values: Vec<(&'static str, ParamValue)>,
    settings: PhantomData<S>,
}

impl<S> Default for SettingsArgs<S> {
    fn default() -> Self {
        Self {
            values: Vec::new(),
            settings: PhantomData,
        }
    }
}

impl<S: FlagSettings> SettingsArgs<S> {
    /// The settings these flags give (the defaults for those not given).
    pub fn settings(&self) -> S {
        let mut settings = S::default();
        for (name, value) in &self.values {
            if let Some(param) = S::parameters().iter().find(|param| param.name == *name) {
                // The parser made the value from this parameter's own kind.
                let _ = (param.set)(&mut settings, *value);
            }
        }
        settings
    }
}

impl<S: FlagSettings> FromArgMatches for SettingsArgs<S> {
    fn from_arg_matches(matches: &ArgMatches) -> Result<Self, clap::Error> {
        let values = S::parameters()
            .iter()
            .filter(|param| matches.value_source(id_of(param)) != Some(ValueSource::DefaultValue))
            .filter_map(|param| {
                matches
                    .get_one::<ParamValue>(id_of(param))
                    .map(|value| (param.name, *value))
            })
            .collect();
        Ok(Self {
            values,
            settings: PhantomData,
        })
    }

    fn update_from_arg_matches(&mut self, matches: &ArgMatches) -> Result<(), clap::Error> {
        *self = Self::from_arg_matches(matches)?;
        Ok(())
    }
}

impl<S: FlagSettings> Args for SettingsArgs<S> {
    fn augment_args(command: Command) -> Command {
        S::parameters().iter().fold(command, |command, param| {
            let long = kept(format!("{}-{}", S::PREFIX, param.flag()));
            let default = kept(param.default_value().to_string());
            let help = format!(
                "{}: {}{}",
                S::TITLE,
                param.help.trim(),
                limits(&param.spec.kind)
            );
            command.arg(flag(param, (id_of(param), long, default), true).help(help))
        })
    }

    fn augment_args_for_update(command: Command) -> Command {
        Self::augment_args(command)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::Parser;

    #[derive(Debug, Parser)]
    struct Flags {
        #[command(flatten)]
        taa: SettingsArgs<pom::TemporalAntiAliasing>,
        #[command(flatten)]
        fxaa: SettingsArgs<pom::FastApproximateAntiAliasing>,
    }

    fn parse(args: &[&str]) -> Result<Flags, clap::Error> {
        Flags::try_parse_from(std::iter::once("test").chain(args.iter().copied()))
    }

    /// Settings whose every parameter differs from the default, found from the declarations.
    fn every_flag_round_trips<S: FlagSettings>(pick: impl Fn(&Flags) -> S) {
        let changed: S = pom::material::every_parameter_changed(S::parameters());
        let mut args = Vec::new();
        for param in S::parameters() {
            assert_ne!(
                (param.get)(&changed),
                param.default_value(),
                "{}",
                param.name
            );
            args.push(format!("--{}-{}", S::PREFIX, param.flag()));
            args.push((param.get)(&changed).to_string());
        }
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        assert_eq!(pick(&parse(&args).unwrap()), changed);
    }

    #[test]
    fn no_flags_give_the_defaults() {
        let flags = parse(&[]).unwrap();
        assert_eq!(flags.taa.settings(), pom::TemporalAntiAliasing::default());
        assert_eq!(
            flags.fxaa.settings(),
            pom::FastApproximateAntiAliasing::default()
        );
    }

    #[test]
    fn every_parameter_round_trips_through_its_flag() {
        every_flag_round_trips(|flags| flags.taa.settings());
        every_flag_round_trips(|flags| flags.fxaa.settings());
    }

    #[test]
    fn a_value_out_of_its_limits_is_a_usage_error_naming_it() {
        let error = parse(&["--fxaa-subpixel-blending", "1.5"]).unwrap_err();
        assert_eq!(error.kind(), clap::error::ErrorKind::ValueValidation);
        let text = error.to_string();
        assert!(
            text.contains("--fxaa-subpixel-blending")
                && text.contains("subpixel_blending is 1.5 but must be at most 1"),
            "{text}"
        );
        let error = parse(&["--taa-jitter-samples", "0"]).unwrap_err();
        assert!(error.to_string().contains("at least 1"), "{error}");
    }
}
