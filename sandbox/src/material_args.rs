//! The material's command-line flags, one per declared parameter of
//! `ParallaxOcclusionMaterial` (`--height-scale`, `--method`, ...): names, help, defaults and
//! value spellings all come from `ParallaxOcclusionMaterial::PARAMETERS`, so a new parameter is
//! a new flag without an edit here. Numbers are checked by `ParallaxOcclusionMaterial::validate`,
//! not by the parser, so the limits live in one place; NaN and negative numbers must parse.
//! `--preset FILE.ron` gives the values the material starts from; the flags given on the command
//! line override them.

use std::sync::OnceLock;

use clap::builder::{PossibleValue, PossibleValuesParser, TypedValueParser, ValueParser};
use clap::parser::ValueSource;
use clap::{Arg, ArgAction, ArgGroup, ArgMatches, Args, Command, FromArgMatches};
use pom::material::{Choice, Param, ParamKind, ParamValue};
use pom::{ParallaxOcclusionMaterial, PomPreset};

/// Parameters set elsewhere on the command line: the debug view is an output option
/// (`--debug-view`, which also applies to scenes).
const NOT_FLAGS: [&str; 1] = ["debug_view"];

/// The id of the group holding every material flag.
pub const GROUP: &str = "MaterialArgs";

/// The id of `--preset`.
pub const PRESET: &str = "preset";

/// Reads the preset file named on the command line: a regular file, read within the plugin's
/// bound and checked like a material. The error names the file and, for a bad value, its line,
/// column and field.
pub fn parse_preset(path: &str) -> Result<PomPreset, String> {
    PomPreset::load(path).map_err(|error| error.to_string())
}

/// `--preset`'s file and its values: the files its layers name are relative to its folder.
#[derive(Clone, Debug, PartialEq)]
pub struct PresetFile {
    /// The file as named.
    pub path: std::path::PathBuf,
    /// Its values.
    pub preset: PomPreset,
}

fn parse_preset_file(path: &str) -> Result<PresetFile, String> {
    Ok(PresetFile {
        path: path.into(),
        preset: parse_preset(path)?,
    })
}

/// `--preset FILE.ron`, the values the material flags start from.
fn preset_flag() -> Arg {
    Arg::new(PRESET)
        .long("preset")
        .value_name("FILE.ron")
        .help(
            "RON material preset to start from, as the window saves it (the format is in \
             plugin/docs/authoring-materials.md). Material flags given on the command line \
             override its values; the others take the preset's, not their defaults. Its \
             debug_view is not used (an inspection view is an output option, --debug-view).",
        )
        .value_parser(ValueParser::new(parse_preset_file))
}

/// The declared parameters that are material flags.
pub fn flag_parameters() -> impl Iterator<Item = &'static Param<ParallaxOcclusionMaterial>> {
    ParallaxOcclusionMaterial::PARAMETERS
        .iter()
        .filter(|param| !NOT_FLAGS.contains(&param.name))
}

/// The flag (`name-with-dashes`) and default value text of every declared parameter, made once
/// (clap keeps `&'static str`s).
fn flag_texts() -> &'static [(String, String)] {
    static TEXTS: OnceLock<Vec<(String, String)>> = OnceLock::new();
    TEXTS.get_or_init(|| {
        ParallaxOcclusionMaterial::PARAMETERS
            .iter()
            .map(|param| (param.flag(), param.default_value().to_string()))
            .collect()
    })
}

fn texts_of(param: &Param<ParallaxOcclusionMaterial>) -> (&'static str, &'static str) {
    let index = ParallaxOcclusionMaterial::PARAMETERS
        .iter()
        .position(|other| other.name == param.name)
        .unwrap_or(0);
    let (flag, default) = &flag_texts()[index];
    (flag, default)
}

/// The values the command line accepts for a choice, with their help.
fn possible_values(kind: &ParamKind) -> Option<Vec<PossibleValue>> {
    match kind {
        ParamKind::Choice(choices) => Some(
            choices
                .iter()
                .map(|choice| PossibleValue::new(choice.name).help(choice.help))
                .collect(),
        ),
        _ => None,
    }
}

/// A clap value parser for a [`Choice`] enum: its spellings, with help, as possible values.
pub fn choice_parser<T: Choice + Clone + Send + Sync>() -> impl TypedValueParser<Value = T> {
    let values = T::INFO
        .iter()
        .map(|choice| PossibleValue::new(choice.name).help(choice.help));
    PossibleValuesParser::new(values).try_map(|name: String| {
        T::from_name(&name).ok_or_else(|| format!("{name:?} is not one of the values"))
    })
}

/// The flag of one parameter of any declared table, `--long` with id `id`; `checked`: a value
/// outside the parameter's limits is a usage error naming the limit (settings, which have no
/// `validate` of their own), else it is left to the material's `validate`.
pub fn flag<M>(
    param: &'static Param<M>,
    (id, long, default): (&'static str, &'static str, &'static str),
    checked: bool,
) -> Arg {
    let help = if param.spec.unit.is_empty() {
        param.help.trim().to_owned()
    } else {
        format!("{} [unit: {}]", param.help.trim(), param.spec.unit)
    };
    let parse = move |text: &str| {
        let value = param.parse(text).map_err(|error| error.to_string())?;
        if checked {
            param.check(value).map_err(|error| error.to_string())?;
        }
        Ok::<_, String>(value)
    };
    let arg = Arg::new(id)
        .long(long)
        .help(help)
        .default_value(default)
        .allow_negative_numbers(true);
    match (&param.spec.kind, possible_values(&param.spec.kind)) {
        (_, Some(values)) => arg.value_name("NAME").value_parser(
            PossibleValuesParser::new(values).try_map(move |text: String| parse(&text)),
        ),
        (ParamKind::Toggle, None) => arg
            .num_args(0..=1)
            .default_missing_value("true")
            .action(ArgAction::Set)
            .value_name("BOOL")
            .value_parser(ValueParser::new(parse)),
        (ParamKind::Color, None) => arg
            .value_name("R,G,B[,A]")
            .value_parser(ValueParser::new(parse)),
        (ParamKind::Integer { .. }, None) => {
            arg.value_name("N").value_parser(ValueParser::new(parse))
        }
        _ => arg.value_name("F").value_parser(ValueParser::new(parse)),
    }
}

/// The material's flags as given on the command line, and the preset they override.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct MaterialArgs {
    /// `--preset`'s file and values, when given.
    preset: Option<PresetFile>,
    /// The flags given explicitly (a flag left out keeps the preset's value or the default).
    values: Vec<(&'static str, ParamValue)>,
}

impl MaterialArgs {
    /// The material these flags describe: the default or the preset, with every flag given
    /// on the command line over it (no textures, default debug view).
    pub fn settings(&self) -> ParallaxOcclusionMaterial {
        let mut material = ParallaxOcclusionMaterial::default();
        if let Some(PresetFile { preset, .. }) = &self.preset {
            material.apply_preset(preset);
            // The debug view is an output option, like in NOT_FLAGS.
            material.debug_view = ParallaxOcclusionMaterial::default().debug_view;
        }
        for (name, value) in &self.values {
            if let Some(param) = ParallaxOcclusionMaterial::PARAMETERS
                .iter()
                .find(|param| param.name == *name)
            {
                // The parser made the value from this parameter's own kind.
                let _ = (param.set)(&mut material, *value);
            }
        }
        material
    }
}

impl MaterialArgs {
    /// The layers `--preset` describes with the maps of the files it names (relative to its
    /// folder, each a regular file inside it), decoded; `None` without a preset or when it names
    /// no file.
    pub fn preset_layer_files(
        &self,
    ) -> Result<Option<pom::parallax::LayerFiles>, pom::PresetError> {
        let Some(PresetFile { path, preset }) = &self.preset else {
            return Ok(None);
        };
        preset.read_layer_files_beside(path, pom::files::FileAccess::InsideFolder)
    }
}

impl FromArgMatches for MaterialArgs {
    fn from_arg_matches(matches: &ArgMatches) -> Result<Self, clap::Error> {
        let values = flag_parameters()
            .filter(|param| matches.value_source(param.name) != Some(ValueSource::DefaultValue))
            .filter_map(|param| {
                matches
                    .get_one::<ParamValue>(param.name)
                    .map(|value| (param.name, *value))
            })
            .collect();
        let preset = matches.get_one::<PresetFile>(PRESET).cloned();
        Ok(Self { preset, values })
    }

    fn update_from_arg_matches(&mut self, matches: &ArgMatches) -> Result<(), clap::Error> {
        *self = Self::from_arg_matches(matches)?;
        Ok(())
    }
}

impl Args for MaterialArgs {
    fn augment_args(command: Command) -> Command {
        let command = command.next_help_heading("Material").arg(preset_flag());
        let command = flag_parameters().fold(command, |command, param| {
            let (long, default) = texts_of(param);
            command.arg(flag(param, (param.name, long, default), false))
        });
        command.group(
            ArgGroup::new(GROUP)
                .multiple(true)
                .required(false)
                .arg(PRESET)
                .args(flag_parameters().map(|param| param.name)),
        )
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
        material: MaterialArgs,
    }

    fn parse(args: &[String]) -> Result<ParallaxOcclusionMaterial, clap::Error> {
        let all = std::iter::once("test".to_owned()).chain(args.iter().cloned());
        Flags::try_parse_from(all).map(|flags| flags.material.settings())
    }

    /// A material whose every parameter differs from the default, found from the declarations.
    fn everything_changed() -> ParallaxOcclusionMaterial {
        pom::material::every_parameter_changed(ParallaxOcclusionMaterial::PARAMETERS)
    }

    #[test]
    fn no_flags_give_the_default_material() {
        assert_eq!(parse(&[]).unwrap(), ParallaxOcclusionMaterial::default());
    }

    #[test]
    fn every_parameter_round_trips_through_its_flag() {
        let material = everything_changed();
        let default = ParallaxOcclusionMaterial::default();
        let mut args = Vec::new();
        for param in flag_parameters() {
            let value = (param.get)(&material);
            assert_ne!(
                value,
                (param.get)(&default),
                "{} should differ from its default in this test",
                param.name
            );
            args.push(format!("--{}", param.flag()));
            args.push(value.to_string());
        }
        let parsed = parse(&args).unwrap();
        for param in flag_parameters() {
            assert_eq!(
                (param.get)(&parsed),
                (param.get)(&material),
                "--{}",
                param.flag()
            );
        }
        // The debug view is an output option (`--debug-view`), not a material flag.
        assert_eq!(
            ParallaxOcclusionMaterial {
                debug_view: material.debug_view,
                ..parsed
            },
            material
        );
    }

    #[test]
    fn a_bad_choice_is_a_usage_error_listing_the_spellings() {
        let error = parse(&["--method".into(), "magic".into()]).unwrap_err();
        assert_eq!(error.kind(), clap::error::ErrorKind::InvalidValue);
        let text = error.to_string();
        assert!(text.contains("pom") && text.contains("relief"), "{text}");
        let error = parse(&["--min-samples".into(), "many".into()]).unwrap_err();
        assert!(error.to_string().contains("min_samples"), "{error}");
    }

    #[test]
    fn a_toggle_is_a_flag_or_takes_a_value() {
        assert!(parse(&["--depth-offset".into()]).unwrap().depth_offset);
        assert!(
            !parse(&["--depth-offset".into(), "false".into()])
                .unwrap()
                .depth_offset
        );
    }
}
