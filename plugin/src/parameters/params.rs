//! One declaration per material parameter: its name, type, default, limits, unit and one-line
//! help, written once in [`crate::material_parameters!`]. Everything else that names a parameter
//! (the uniform, validation, RON presets, script patches, glTF extras, command-line flags, the
//! sandbox's editor rows) reads the generated struct fields or walks [`Param`] tables.

use std::fmt;

use super::param_types::ParamType;
use crate::shader::{Choice, ChoiceInfo};

/// A parameter's value as tables walked at run time (command line, editor) see it.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub enum ParamValue {
    /// A real number.
    Float(f32),
    /// A whole number.
    Integer(u32),
    /// On or off.
    Toggle(bool),
    /// One of a [`Choice`] type's values, by its one spelling.
    Choice(&'static str),
    /// A linear RGBA colour.
    Color([f32; 4]),
}

impl fmt::Display for ParamValue {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ParamValue::Float(value) => write!(f, "{value}"),
            ParamValue::Integer(value) => write!(f, "{value}"),
            ParamValue::Toggle(value) => write!(f, "{value}"),
            ParamValue::Choice(name) => f.write_str(name),
            ParamValue::Color([r, g, b, a]) => write!(f, "{r},{g},{b},{a}"),
        }
    }
}

/// The type of a parameter and the values it accepts.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub enum ParamKind {
    /// A real number in `min..=max`; `editor` is the slider range artists use.
    Float {
        /// Smallest valid value.
        min: f32,
        /// Largest valid value.
        max: f32,
        /// The editor slider's range.
        editor: (f32, f32),
        /// Whether the slider is logarithmic.
        logarithmic: bool,
    },
    /// A whole number in `min..=max`.
    Integer {
        /// Smallest valid value.
        min: u32,
        /// Largest valid value.
        max: u32,
        /// Whether the slider is logarithmic.
        logarithmic: bool,
    },
    /// On or off.
    Toggle,
    /// One of a fixed list.
    Choice(&'static [ChoiceInfo]),
    /// A linear RGBA colour (finite components).
    Color,
}

/// Where an editor lists a parameter: under one heading per group, the groups in this order,
/// so the values an artist tunes all the time come first.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum ParamGroup {
    /// The values tuned all the time (for the parallax material, the seed's artist parameters:
    /// height range, samples, LOD, shadow softening). Editors show this group open.
    Essential,
    /// How the effect is computed: the method, its refinement and its conventions.
    Method,
    /// Where the surface's outline lies.
    Silhouette,
    /// The reflection model and its parameters.
    Lighting,
    /// Inspection views.
    Debug,
}

impl ParamGroup {
    /// Every group, in the order editors show them.
    pub const ALL: [ParamGroup; 5] = [
        ParamGroup::Essential,
        ParamGroup::Method,
        ParamGroup::Silhouette,
        ParamGroup::Lighting,
        ParamGroup::Debug,
    ];

    /// The group's heading in an editor.
    pub fn heading(self) -> &'static str {
        match self {
            ParamGroup::Essential => "Relief",
            ParamGroup::Method => "Method",
            ParamGroup::Silhouette => "Silhouette",
            ParamGroup::Lighting => "Lighting",
            ParamGroup::Debug => "Debug",
        }
    }
}

/// Limits, unit and editor hints of one parameter: the part of its declaration that is not its
/// name, type, default or help. Built with `const` functions inside
/// [`crate::material_parameters!`].
pub struct ParamSpec<M> {
    /// Type and limits.
    pub kind: ParamKind,
    /// Unit, for help texts and beside the editor's value ("" when it has none).
    pub unit: &'static str,
    /// The editor heading it is listed under.
    pub group: ParamGroup,
    /// Whether the parameter has an effect with the material's other values (the editor greys
    /// it out otherwise).
    pub applies: fn(&M) -> bool,
}

fn always<M>(_: &M) -> bool {
    true
}

impl<M> ParamSpec<M> {
    /// A real number in `min..=max`, edited over the same range.
    pub const fn float(min: f32, max: f32) -> Self {
        Self::with_kind(ParamKind::Float {
            min,
            max,
            editor: (min, max),
            logarithmic: false,
        })
    }

    /// A whole number in `min..=max`.
    pub const fn integer(min: u32, max: u32) -> Self {
        Self::with_kind(ParamKind::Integer {
            min,
            max,
            logarithmic: false,
        })
    }

    /// On or off.
    pub const fn toggle() -> Self {
        Self::with_kind(ParamKind::Toggle)
    }

    /// A linear RGBA colour.
    pub const fn color() -> Self {
        Self::with_kind(ParamKind::Color)
    }

    /// One of `T`'s values.
    pub const fn choice<T: Choice>() -> Self {
        Self::with_kind(ParamKind::Choice(T::INFO))
    }

    const fn with_kind(kind: ParamKind) -> Self {
        Self {
            kind,
            unit: "",
            group: ParamGroup::Essential,
            applies: always::<M>,
        }
    }

    /// The same with the editor's slider over `min..=max` (a number only).
    pub const fn editor(mut self, low: f32, high: f32) -> Self {
        if let ParamKind::Float { ref mut editor, .. } = self.kind {
            *editor = (low, high);
        }
        self
    }

    /// The same with a logarithmic slider.
    pub const fn logarithmic(mut self) -> Self {
        match self.kind {
            ParamKind::Float {
                ref mut logarithmic,
                ..
            }
            | ParamKind::Integer {
                ref mut logarithmic,
                ..
            } => *logarithmic = true,
            _ => {}
        }
        self
    }

    /// The same with a unit.
    pub const fn unit(mut self, unit: &'static str) -> Self {
        self.unit = unit;
        self
    }

    /// The same, listed under `group` in editors.
    pub const fn group(mut self, group: ParamGroup) -> Self {
        self.group = group;
        self
    }

    /// The same, marked as having an effect only when `applies` holds.
    pub const fn applies_when(mut self, applies: fn(&M) -> bool) -> Self {
        self.applies = applies;
        self
    }
}

/// One declared parameter of material `M`, for code that walks every parameter at run time.
pub struct Param<M> {
    /// The field name: the RON and glTF key; `--name-with-dashes` on the command line.
    pub name: &'static str,
    /// What it does: its whole doc comment, the lines joined (trim it before showing).
    pub help: &'static str,
    /// Type, limits, unit, editor hints.
    pub spec: ParamSpec<M>,
    /// Reads the parameter.
    pub get: fn(&M) -> ParamValue,
    /// Writes the parameter; a value of the wrong kind or an unknown choice is an error.
    pub set: fn(&mut M, ParamValue) -> Result<(), ParamError>,
}

impl<M> fmt::Debug for Param<M> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Param")
            .field("name", &self.name)
            .field("kind", &self.spec.kind)
            .finish_non_exhaustive()
    }
}

impl<M> Param<M> {
    /// The command-line flag, without the leading dashes: the name with `-` for `_`.
    pub fn flag(&self) -> String {
        self.name.replace('_', "-")
    }

    /// The editor's label: the name with spaces for `_`.
    pub fn label(&self) -> String {
        self.name.replace('_', " ")
    }

    /// The parameter's default.
    pub fn default_value(&self) -> ParamValue
    where
        M: Default,
    {
        (self.get)(&M::default())
    }

    /// Whether `value` lies within this parameter's declared limits (the error names it and
    /// the limit); values of other kinds are not checked here (`set` rejects them).
    pub fn check(&self, value: ParamValue) -> Result<(), LimitError> {
        match (self.spec.kind, value) {
            (ParamKind::Float { .. }, ParamValue::Integer(number)) => {
                (number as f32).check(self.name, &self.spec.kind)
            }
            (_, ParamValue::Float(number)) => number.check(self.name, &self.spec.kind),
            (_, ParamValue::Integer(number)) => number.check(self.name, &self.spec.kind),
            _ => Ok(()),
        }
    }

    /// Parses `text` as this parameter's value (the command line's spelling). Numbers are not
    /// range-checked here: the material's `validate` names the limit ([`Param::check`] does
    /// for settings, whose flags reject a value out of range).
    pub fn parse(&self, text: &str) -> Result<ParamValue, ParamError> {
        let invalid = |expected: String| ParamError::Parse {
            name: self.name,
            text: text.to_owned(),
            expected,
        };
        match self.spec.kind {
            ParamKind::Float { .. } => text
                .trim()
                .parse()
                .map(ParamValue::Float)
                .map_err(|_| invalid("a number".into())),
            ParamKind::Integer { .. } => text
                .trim()
                .parse()
                .map(ParamValue::Integer)
                .map_err(|_| invalid("a whole number ≥ 0".into())),
            ParamKind::Toggle => match text.trim() {
                "true" | "on" => Ok(ParamValue::Toggle(true)),
                "false" | "off" => Ok(ParamValue::Toggle(false)),
                _ => Err(invalid("true or false".into())),
            },
            ParamKind::Choice(choices) => choices
                .iter()
                .find(|choice| choice.name == text.trim())
                .map(|choice| ParamValue::Choice(choice.name))
                .ok_or_else(|| invalid(format!("one of {}", choice_names(choices)))),
            ParamKind::Color => {
                let parts: Result<Vec<f32>, _> =
                    text.split(',').map(|part| part.trim().parse()).collect();
                match parts.as_deref() {
                    Ok([r, g, b]) => Ok(ParamValue::Color([*r, *g, *b, 1.0])),
                    Ok([r, g, b, a]) => Ok(ParamValue::Color([*r, *g, *b, *a])),
                    _ => Err(invalid("R,G,B or R,G,B,A (linear, e.g. 1,0.5,0.2)".into())),
                }
            }
        }
    }
}

/// A material whose every parameter in `params` is valid by its limits and differs from the
/// default, found from the declarations alone: for round-trip tests that must cover parameters
/// added later. Numbers are multiples of 1/64, exact in text.
#[doc(hidden)] // A test hook.
pub fn every_parameter_changed<M: Default>(params: &[Param<M>]) -> M {
    let mut material = M::default();
    for param in params {
        let value = match (param.spec.kind, param.default_value()) {
            (ParamKind::Float { min, editor, .. }, ParamValue::Float(default)) => {
                let pick = |t: f32| (((min + (editor.1 - min) * t) * 64.0).round() / 64.0).max(min);
                let first = pick(0.375);
                ParamValue::Float(if first == default { pick(0.625) } else { first })
            }
            (ParamKind::Integer { min, max, .. }, ParamValue::Integer(default)) => {
                let first = min + (max - min) / 3;
                ParamValue::Integer(if first == default { first + 1 } else { first })
            }
            (ParamKind::Toggle, ParamValue::Toggle(on)) => ParamValue::Toggle(!on),
            (ParamKind::Choice(choices), ParamValue::Choice(name)) => {
                let index = choices.iter().position(|c| c.name == name).unwrap_or(0);
                ParamValue::Choice(choices[(index + 1) % choices.len()].name)
            }
            (ParamKind::Color, _) => ParamValue::Color([0.25, 0.5, 0.75, 0.875]),
            (_, default) => default,
        };
        // The value was made for this parameter's own kind.
        let _ = (param.set)(&mut material, value);
    }
    material
}

fn choice_names(choices: &[ChoiceInfo]) -> String {
    choices
        .iter()
        .map(|choice| choice.name)
        .collect::<Vec<_>>()
        .join(", ")
}

/// A parameter value that cannot be used.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum ParamError {
    /// Text that is not a value of the parameter's type.
    #[error("{name}: {text:?} is not {expected}")]
    Parse {
        /// The parameter.
        name: &'static str,
        /// What was given.
        text: String,
        /// What it should be.
        expected: String,
    },
    /// A value of another kind (a number for a choice, say).
    #[error("{name}: {value} is not a value of this parameter")]
    WrongKind {
        /// The parameter.
        name: &'static str,
        /// What was given.
        value: ParamValue,
    },
}

/// A parameter's value out of its declared limits.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum LimitError {
    /// A number is NaN or infinite.
    #[error("{field} is {value}, which is not a finite number")]
    NotFinite {
        /// The field.
        field: &'static str,
        /// Its value.
        value: f32,
    },
    /// A number is below its minimum.
    #[error("{field} is {value} but must be at least {min}")]
    TooSmall {
        /// The field.
        field: &'static str,
        /// Its value (a whole number stays one, so it prints exactly).
        value: ParamValue,
        /// The smallest allowed value.
        min: ParamValue,
    },
    /// A number is above its maximum.
    #[error("{field} is {value} but must be at most {max}")]
    TooLarge {
        /// The field.
        field: &'static str,
        /// Its value (a whole number stays one, so it prints exactly).
        value: ParamValue,
        /// The largest allowed value.
        max: ParamValue,
    },
}
