//! One declaration per material parameter: its name, type, default, limits, unit and one-line
//! help, written once in [`crate::material_parameters!`]. Everything else that names a parameter
//! (the uniform, validation, RON presets, script patches, glTF extras, command-line flags, the
//! sandbox's editor rows) reads the generated struct fields or walks [`Param`] tables.

use std::fmt;

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

/// One value of a [`Choice`] type: its spelling (the same in RON, glTF, on the command line and
/// in the editor) and a one-line help.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ChoiceInfo {
    /// The spelling.
    pub name: &'static str,
    /// One line saying what it does.
    pub help: &'static str,
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

/// Limits, unit and editor hints of one parameter: the part of its declaration that is not its
/// name, type, default or help. Built with `const` functions inside
/// [`crate::material_parameters!`].
pub struct ParamSpec<M> {
    /// Type and limits.
    pub kind: ParamKind,
    /// Unit, for help texts ("" when it has none).
    pub unit: &'static str,
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
    /// One line saying what it does.
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

    /// Parses `text` as this parameter's value (the command line's spelling). Numbers are not
    /// range-checked here: the material's `validate` names the limit.
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

/// A material parameter's value out of its declared limits.
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
        /// Its value.
        value: f32,
        /// The smallest allowed value.
        min: f32,
    },
    /// A number is above its maximum.
    #[error("{field} is {value} but must be at most {max}")]
    TooLarge {
        /// The field.
        field: &'static str,
        /// Its value.
        value: f32,
        /// The largest allowed value.
        max: f32,
    },
}

/// A Rust type a parameter can have: numbers, `bool`, and [`Choice`] enums.
pub trait ParamType: Copy + Sized {
    /// As a table value.
    fn to_value(self) -> ParamValue;
    /// From a table value of the right kind.
    fn from_value(value: ParamValue) -> Option<Self>;
    /// Whether it lies within `kind`'s limits; the error names `field`.
    fn check(self, field: &'static str, kind: &ParamKind) -> Result<(), LimitError> {
        let _ = (field, kind);
        Ok(())
    }
    /// Brought within `kind`'s limits; `fallback` replaces a value that has no nearest valid one
    /// (NaN).
    fn clamped(self, kind: &ParamKind, fallback: Self) -> Self {
        let _ = (kind, fallback);
        self
    }
    /// The value as a Rust expression, for "copy as Rust".
    fn rust_literal(self) -> String;
}

impl ParamType for f32 {
    fn to_value(self) -> ParamValue {
        ParamValue::Float(self)
    }

    fn rust_literal(self) -> String {
        format!("{self:?}")
    }

    fn from_value(value: ParamValue) -> Option<Self> {
        match value {
            ParamValue::Float(value) => Some(value),
            ParamValue::Integer(value) => Some(value as f32),
            _ => None,
        }
    }

    fn check(self, field: &'static str, kind: &ParamKind) -> Result<(), LimitError> {
        let ParamKind::Float { min, max, .. } = *kind else {
            return Ok(());
        };
        if !self.is_finite() {
            Err(LimitError::NotFinite { field, value: self })
        } else if self < min {
            Err(LimitError::TooSmall {
                field,
                value: self,
                min,
            })
        } else if self > max {
            Err(LimitError::TooLarge {
                field,
                value: self,
                max,
            })
        } else {
            Ok(())
        }
    }

    fn clamped(self, kind: &ParamKind, fallback: Self) -> Self {
        match *kind {
            ParamKind::Float { min, max, .. } if self.is_finite() => self.clamp(min, max),
            ParamKind::Float { .. } => fallback,
            _ => self,
        }
    }
}

impl ParamType for u32 {
    fn to_value(self) -> ParamValue {
        ParamValue::Integer(self)
    }

    fn rust_literal(self) -> String {
        self.to_string()
    }

    fn from_value(value: ParamValue) -> Option<Self> {
        match value {
            ParamValue::Integer(value) => Some(value),
            _ => None,
        }
    }

    fn check(self, field: &'static str, kind: &ParamKind) -> Result<(), LimitError> {
        let ParamKind::Integer { min, max, .. } = *kind else {
            return Ok(());
        };
        if self < min {
            Err(LimitError::TooSmall {
                field,
                value: self as f32,
                min: min as f32,
            })
        } else if self > max {
            Err(LimitError::TooLarge {
                field,
                value: self as f32,
                max: max as f32,
            })
        } else {
            Ok(())
        }
    }

    fn clamped(self, kind: &ParamKind, _: Self) -> Self {
        match *kind {
            ParamKind::Integer { min, max, .. } => self.clamp(min, max),
            _ => self,
        }
    }
}

impl ParamType for bool {
    fn to_value(self) -> ParamValue {
        ParamValue::Toggle(self)
    }

    fn rust_literal(self) -> String {
        self.to_string()
    }

    fn from_value(value: ParamValue) -> Option<Self> {
        match value {
            ParamValue::Toggle(value) => Some(value),
            _ => None,
        }
    }
}

impl ParamType for crate::Color {
    fn to_value(self) -> ParamValue {
        ParamValue::Color(self.to_array())
    }

    fn rust_literal(self) -> String {
        let Self { r, g, b, a } = self;
        format!("Color {{ r: {r:?}, g: {g:?}, b: {b:?}, a: {a:?} }}")
    }

    fn from_value(value: ParamValue) -> Option<Self> {
        match value {
            ParamValue::Color([r, g, b, a]) => Some(Self { r, g, b, a }),
            _ => None,
        }
    }

    fn check(self, field: &'static str, _: &ParamKind) -> Result<(), LimitError> {
        match self.to_array().into_iter().find(|c| !c.is_finite()) {
            Some(value) => Err(LimitError::NotFinite { field, value }),
            None => Ok(()),
        }
    }

    fn clamped(self, _: &ParamKind, fallback: Self) -> Self {
        let finite_or =
            |value: f32, fallback: f32| if value.is_finite() { value } else { fallback };
        Self {
            r: finite_or(self.r, fallback.r),
            g: finite_or(self.g, fallback.g),
            b: finite_or(self.b, fallback.b),
            a: finite_or(self.a, fallback.a),
        }
    }
}

/// How a parameter is uploaded in the GPU struct [`crate::material_parameters!`] generates:
/// 4-byte aligned types only, so the struct has no padding and WGSL lays it out as Rust does.
pub trait GpuParam: Copy {
    /// The uploaded value.
    type Gpu: bytemuck::Pod + std::fmt::Debug + PartialEq;
    /// Its WGSL type.
    const WGSL: &'static str;
    /// The value as uploaded.
    fn to_gpu(self) -> Self::Gpu;
}

impl GpuParam for f32 {
    type Gpu = f32;
    const WGSL: &'static str = "f32";
    fn to_gpu(self) -> f32 {
        self
    }
}

impl GpuParam for u32 {
    type Gpu = u32;
    const WGSL: &'static str = "u32";
    fn to_gpu(self) -> u32 {
        self
    }
}

impl GpuParam for bool {
    type Gpu = u32;
    const WGSL: &'static str = "u32";
    fn to_gpu(self) -> u32 {
        u32::from(self)
    }
}

impl GpuParam for crate::Color {
    type Gpu = [f32; 4];
    // Not `vec4<f32>`, which WGSL aligns to 16 bytes.
    const WGSL: &'static str = "array<f32, 4>";
    fn to_gpu(self) -> [f32; 4] {
        self.to_array()
    }
}

impl<T: Choice> GpuParam for T {
    type Gpu = u32;
    const WGSL: &'static str = "u32";
    fn to_gpu(self) -> u32 {
        self.code()
    }
}

/// An enum whose values a parameter chooses between, declared with [`crate::choice_enum!`]: each
/// value has one spelling, used by serde (RON, glTF), the command line and the editor, and a
/// WGSL constant `PREFIX_VALUE` with its code.
pub trait Choice: Copy + PartialEq + 'static {
    /// Every value, in declaration order (its index is its code).
    const VALUES: &'static [Self];
    /// Spelling and help of each value, in the same order.
    const INFO: &'static [ChoiceInfo];
    /// The prefix of the WGSL constants (`METHOD` gives `METHOD_OCCLUSION`).
    const WGSL_PREFIX: &'static str;
    /// The Rust names of the values, for WGSL constant names.
    const RUST_NAMES: &'static [&'static str];

    /// The position of `self` in [`Choice::VALUES`]: the value shaders see.
    fn code(self) -> u32 {
        Self::VALUES
            .iter()
            .position(|value| *value == self)
            .unwrap_or(0) as u32
    }

    /// The one spelling of `self`.
    fn name(self) -> &'static str {
        Self::INFO[self.code() as usize].name
    }

    /// The value spelled `name`.
    fn from_name(name: &str) -> Option<Self> {
        Self::INFO
            .iter()
            .position(|info| info.name == name)
            .map(|index| Self::VALUES[index])
    }

    /// WGSL declarations of one `const PREFIX_VALUE: u32` per value, generated so shaders never
    /// retype the codes.
    fn wgsl_constants() -> String {
        Self::RUST_NAMES
            .iter()
            .enumerate()
            .map(|(code, rust_name)| {
                format!(
                    "const {}_{}: u32 = {code}u;\n",
                    Self::WGSL_PREFIX,
                    screaming_snake_case(rust_name)
                )
            })
            .collect()
    }
}

impl<T: Choice> ParamType for T {
    fn to_value(self) -> ParamValue {
        ParamValue::Choice(self.name())
    }

    fn rust_literal(self) -> String {
        let type_name = std::any::type_name::<T>();
        let short = type_name.rsplit("::").next().unwrap_or(type_name);
        format!("{short}::{}", T::RUST_NAMES[self.code() as usize])
    }

    fn from_value(value: ParamValue) -> Option<Self> {
        match value {
            ParamValue::Choice(name) => Self::from_name(name),
            _ => None,
        }
    }
}

/// `CookTorrance` → `COOK_TORRANCE`.
fn screaming_snake_case(name: &str) -> String {
    let mut out = String::new();
    for (index, character) in name.chars().enumerate() {
        if character.is_uppercase() && index > 0 {
            out.push('_');
        }
        out.push(character.to_ascii_uppercase());
    }
    out
}

/// Declares an enum whose values a material parameter chooses between: one spelling per value
/// (serde, command line, editor), a one-line help each, and generated WGSL constants.
///
/// ```
/// pom::choice_enum! {
///     /// How a stripe pattern runs.
///     pub enum Stripes: "STRIPES" {
///         /// Left to right.
///         Horizontal = "horizontal",
///         /// Top to bottom.
///         Vertical = "vertical",
///     }
/// }
/// use pom::material::Choice;
/// assert_eq!(Stripes::Vertical.name(), "vertical");
/// assert!(Stripes::wgsl_constants().contains("const STRIPES_VERTICAL: u32 = 1u;"));
/// ```
#[macro_export]
macro_rules! choice_enum {
    (
        $(#[$attr:meta])*
        pub enum $name:ident : $prefix:literal {
            $(
                #[doc = $help:literal]
                $variant:ident = $spelling:literal,
            )*
        }
    ) => {
        $(#[$attr])*
        #[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
        #[derive($crate::serde::Serialize, $crate::serde::Deserialize)]
        #[serde(crate = "pom::serde")]
        #[non_exhaustive]
        pub enum $name {
            $(
                #[doc = $help]
                #[serde(rename = $spelling)]
                $variant,
            )*
        }

        impl $crate::material::Choice for $name {
            const VALUES: &'static [Self] = &[$($name::$variant),*];
            const INFO: &'static [$crate::material::ChoiceInfo] = &[
                $($crate::material::ChoiceInfo { name: $spelling, help: $help }),*
            ];
            const WGSL_PREFIX: &'static str = $prefix;
            const RUST_NAMES: &'static [&'static str] = &[$(stringify!($variant)),*];
        }
    };
}

/// Declares a material struct from one list of parameters, each written once: doc line (its
/// help), name, type, default and [`ParamSpec`]. Generates the struct (inputs such as texture
/// handles first, then the parameters), `Default`, the [`Param`] table `PARAMETERS`, a full
/// preset struct and an all-optional patch struct (both serde, unknown fields rejected), and
/// the limit checks and clamps of every parameter, and the GPU struct of the parameters with its
/// generated WGSL declaration.
#[macro_export]
macro_rules! material_parameters {
    (
        $(#[$attr:meta])*
        pub struct $material:ident {
            inputs {
                $(
                    $(#[doc = $input_doc:literal])*
                    $input:ident : $input_ty:ty = $input_default:expr,
                )*
            }
            parameters {
                $(
                    #[doc = $help:literal]
                    $(#[doc = $more:literal])*
                    $field:ident : $ty:ty = $default:expr, $spec:expr;
                )*
            }
        }
        preset $preset:ident;
        patch $patch:ident;
        gpu $gpu:ident;
    ) => {
        $(#[$attr])*
        pub struct $material {
            $(
                $(#[doc = $input_doc])*
                pub $input: $input_ty,
            )*
            $(
                #[doc = $help]
                $(#[doc = $more])*
                pub $field: $ty,
            )*
        }

        impl Default for $material {
            fn default() -> Self {
                Self {
                    $($input: $input_default,)*
                    $($field: $default,)*
                }
            }
        }

        impl $material {
            /// Every parameter, in declaration order, for code that walks them at run time.
            pub const PARAMETERS: &'static [$crate::material::Param<$material>] = &[
                $(
                    $crate::material::Param {
                        name: stringify!($field),
                        help: $help,
                        spec: $spec,
                        get: |material: &$material| {
                            $crate::material::ParamType::to_value(material.$field)
                        },
                        set: |material: &mut $material, value| {
                            match $crate::material::ParamType::from_value(value) {
                                Some(value) => {
                                    material.$field = value;
                                    Ok(())
                                }
                                None => Err($crate::material::ParamError::WrongKind {
                                    name: stringify!($field),
                                    value,
                                }),
                            }
                        },
                    },
                )*
            ];

            /// The first parameter outside its declared limits, if any (no allocation).
            fn first_limit_problem(&self) -> Option<$crate::material::LimitError> {
                $(
                    {
                        const SPEC: $crate::material::ParamSpec<$material> = $spec;
                        if let Err(problem) = $crate::material::ParamType::check(
                            self.$field,
                            stringify!($field),
                            &SPEC.kind,
                        ) {
                            return Some(problem);
                        }
                    }
                )*
                None
            }

            /// Every parameter outside its declared limits, in declaration order.
            fn limit_problems(&self) -> Vec<$crate::material::LimitError> {
                let mut problems = Vec::new();
                $(
                    {
                        const SPEC: $crate::material::ParamSpec<$material> = $spec;
                        if let Err(problem) = $crate::material::ParamType::check(
                            self.$field,
                            stringify!($field),
                            &SPEC.kind,
                        ) {
                            problems.push(problem);
                        }
                    }
                )*
                problems
            }

            /// Every parameter brought within its declared limits (NaN becomes the default).
            fn clamp_to_limits(&mut self) {
                let defaults = Self::default();
                $(
                    {
                        const SPEC: $crate::material::ParamSpec<$material> = $spec;
                        self.$field = $crate::material::ParamType::clamped(
                            self.$field,
                            &SPEC.kind,
                            defaults.$field,
                        );
                    }
                )*
            }

            /// The material's parameters without its inputs (textures).
            pub fn preset(&self) -> $preset {
                $preset { $($field: self.$field,)* }
            }

            /// Takes every parameter of `preset`, keeping this material's inputs.
            pub fn apply_preset(&mut self, preset: &$preset) {
                $(self.$field = preset.$field;)*
            }
        }

        #[doc = concat!("Every parameter of [`", stringify!($material), "`] as the shader reads \
            it, in declaration order (choices as their codes, toggles as 0 or 1). Its WGSL twin \
            is [`", stringify!($gpu), "::wgsl`].")]
        #[repr(C)]
        #[derive(Clone, Copy, Debug, PartialEq, $crate::bytemuck::Pod, $crate::bytemuck::Zeroable)]
        #[bytemuck(crate = "pom::bytemuck")]
        pub struct $gpu {
            $(
                #[doc = $help]
                pub $field: <$ty as $crate::material::GpuParam>::Gpu,
            )*
        }

        $crate::wgsl_layout!($gpu { $($field),* });

        impl $gpu {
            /// The WGSL declaration of this struct, generated from the same declarations.
            pub fn wgsl() -> String {
                let mut wgsl = format!("struct {} {{\n", stringify!($gpu));
                $(
                    wgsl.push_str(&format!(
                        "    {}: {},\n",
                        stringify!($field),
                        <$ty as $crate::material::GpuParam>::WGSL
                    ));
                )*
                wgsl.push_str("}\n");
                wgsl
            }
        }

        impl $material {
            /// The parameters as the shader reads them (sanitize the material first).
            pub fn gpu_params(&self) -> $gpu {
                $gpu {
                    $($field: $crate::material::GpuParam::to_gpu(self.$field),)*
                }
            }
        }

        #[doc = concat!("Every parameter of [`", stringify!($material), "`], without its inputs \
            (textures). In RON every field is optional (a missing one keeps its default) and an \
            unknown one is an error.")]
        #[derive(Clone, Debug, PartialEq, $crate::serde::Serialize, $crate::serde::Deserialize)]
        #[serde(crate = "pom::serde", default, deny_unknown_fields)]
        pub struct $preset {
            $(
                #[doc = $help]
                pub $field: $ty,
            )*
        }

        impl Default for $preset {
            fn default() -> Self {
                $material::default().preset()
            }
        }

        impl $preset {
            /// Each field as a Rust expression, in declaration order.
            pub fn rust_fields(&self) -> Vec<(&'static str, String)> {
                vec![$((stringify!($field), $crate::material::ParamType::rust_literal(self.$field)),)*]
            }
        }

        #[doc = concat!("Changes to parameters of [`", stringify!($material), "`]: absent fields \
            stay as they are. Scripts' `Set` steps and glTF `extras` are read into it.")]
        #[derive(Clone, Debug, Default, PartialEq, $crate::serde::Serialize, $crate::serde::Deserialize)]
        #[serde(crate = "pom::serde", deny_unknown_fields)]
        pub struct $patch {
            $(
                #[doc = $help]
                #[serde(default, skip_serializing_if = "Option::is_none")]
                pub $field: Option<$ty>,
            )*
        }

        impl $patch {
            /// Writes every present field into `material`.
            pub fn apply(&self, material: &mut $material) {
                $(
                    if let Some(value) = self.$field {
                        material.$field = value;
                    }
                )*
            }

            /// A patch that sets every parameter to `material`'s value.
            pub fn from_material(material: &$material) -> Self {
                Self { $($field: Some(material.$field),)* }
            }
        }
    };
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn screaming_snake_case_splits_words() {
        assert_eq!(screaming_snake_case("CookTorrance"), "COOK_TORRANCE");
        assert_eq!(screaming_snake_case("Occlusion"), "OCCLUSION");
    }
}
