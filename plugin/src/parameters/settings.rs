//! Parameters of plain settings structs (an effect's knobs, say), declared as material
//! parameters are: [`crate::settings_parameters!`] writes the struct, its `Default`, its
//! [`Param`] table and its limit checks from one list; [`crate::parameter_table!`] is the part
//! both declaration macros share. [`DeclaredSettings`] is what code that walks any such struct
//! (command line, scripts, editors) needs, and [`ClampWarnings`] clamps settings with one
//! warning per new out-of-range value.

use super::params::{LimitError, Param};

/// A settings struct declared with [`crate::settings_parameters!`].
pub trait DeclaredSettings: Copy + PartialEq + Default + 'static {
    /// Every parameter, in declaration order.
    fn parameters() -> &'static [Param<Self>];
    /// Every parameter outside its declared limits, in declaration order.
    fn problems(&self) -> Vec<LimitError>;
    /// Every parameter brought within its declared limits (not finite: its default).
    fn sanitized(&self) -> Self;
}

/// Clamps settings to their limits, logging which were out of them once per new value (a
/// value set every frame warns once).
#[derive(Clone, Copy, Debug, Default)]
pub struct ClampWarnings<S> {
    warned: Option<S>,
}

impl<S: DeclaredSettings> ClampWarnings<S> {
    /// `settings` within their limits; the warning names `what` and every parameter clamped.
    pub fn sanitized(&mut self, what: &str, settings: &S) -> S {
        let problems = settings.problems();
        if !problems.is_empty() && self.warned != Some(*settings) {
            let problems: Vec<String> = problems.iter().map(ToString::to_string).collect();
            log::warn!("{what}: {}; clamped", problems.join("; "));
            self.warned = Some(*settings);
        }
        settings.sanitized()
    }
}

/// The [`Param`] table `PARAMETERS` and the limit checks of a declared struct, written inside
/// an `impl` block of it: `$owner { field: Type, "help", ParamSpec; ... }`. Generates
/// `first_limit_problem`, `limit_problems` and `clamp_to_limits` (private) for the declaring
/// macro to build on.
#[doc(hidden)]
#[macro_export]
macro_rules! parameter_table {
    ($owner:ident { $($field:ident : $ty:ty, $help:expr, $spec:expr;)* }) => {
        /// Every parameter, in declaration order, for code that walks them at run time.
        pub const PARAMETERS: &'static [$crate::parameters::Param<$owner>] = &[
            $(
                $crate::parameters::Param {
                    name: stringify!($field),
                    // The whole doc comment: each line after the first starts with a space.
                    help: $help,
                    spec: $spec,
                    get: |owner: &$owner| $crate::parameters::ParamType::to_value(owner.$field),
                    set: |owner: &mut $owner, value| {
                        match $crate::parameters::ParamType::from_value(value) {
                            Some(value) => {
                                owner.$field = value;
                                Ok(())
                            }
                            None => Err($crate::parameters::ParamError::WrongKind {
                                name: stringify!($field),
                                value,
                            }),
                        }
                    },
                },
            )*
        ];

        /// The first parameter outside its declared limits, if any (no allocation).
        fn first_limit_problem(&self) -> Option<$crate::parameters::LimitError> {
            $(
                {
                    const SPEC: $crate::parameters::ParamSpec<$owner> = $spec;
                    if let Err(problem) = $crate::parameters::ParamType::check(
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
        fn limit_problems(&self) -> Vec<$crate::parameters::LimitError> {
            let mut problems = Vec::new();
            $(
                {
                    const SPEC: $crate::parameters::ParamSpec<$owner> = $spec;
                    if let Err(problem) = $crate::parameters::ParamType::check(
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
                    const SPEC: $crate::parameters::ParamSpec<$owner> = $spec;
                    self.$field = $crate::parameters::ParamType::clamped(
                        self.$field,
                        &SPEC.kind,
                        defaults.$field,
                    );
                }
            )*
        }
    };
}

/// Declares a plain settings struct from one list of parameters, each written once as a
/// material parameter is: doc line (its help), name, type, default and
/// [`ParamSpec`](crate::parameters::ParamSpec). The attributes (derives, serde's) are the
/// struct's own; `Default` is generated.
///
/// Generates the struct, `Default`, the [`Param`] table `PARAMETERS`, `problems` (every value
/// outside its limits, naming it) and `sanitized` (every value clamped), and
/// [`DeclaredSettings`]: the command line, scripts and editors walk it as they walk a
/// material's table. No GPU struct: an effect uploads what its shader reads itself.
#[macro_export]
macro_rules! settings_parameters {
    (
        $(#[$attr:meta])*
        pub struct $settings:ident {
            $(
                #[doc = $help:literal]
                $(#[doc = $more:literal])*
                $field:ident : $ty:ty = $default:expr, $spec:expr;
            )*
        }
    ) => {
        $(#[$attr])*
        pub struct $settings {
            $(
                #[doc = $help]
                $(#[doc = $more])*
                pub $field: $ty,
            )*
        }

        impl Default for $settings {
            fn default() -> Self {
                Self { $($field: $default,)* }
            }
        }

        impl $settings {
            $crate::parameter_table!($settings {
                $($field: $ty, concat!($help $(, $more)*), $spec;)*
            });

            /// Every parameter outside its declared limits, in declaration order, each naming
            /// the parameter and the limit.
            pub fn problems(&self) -> Vec<$crate::parameters::LimitError> {
                self.limit_problems()
            }

            /// Every parameter brought within its declared limits (not finite: its default).
            pub fn sanitized(&self) -> Self {
                let mut clean = *self;
                if self.first_limit_problem().is_some() {
                    clean.clamp_to_limits();
                }
                clean
            }
        }

        impl $crate::parameters::DeclaredSettings for $settings {
            fn parameters() -> &'static [$crate::parameters::Param<Self>] {
                Self::PARAMETERS
            }

            fn problems(&self) -> Vec<$crate::parameters::LimitError> {
                self.limit_problems()
            }

            fn sanitized(&self) -> Self {
                <$settings>::sanitized(self)
            }
        }
    };
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::parameters::{ParamSpec, ParamValue};

    crate::settings_parameters! {
        /// Two knobs.
        #[derive(Clone, Copy, Debug, PartialEq)]
        pub struct Knobs {
            /// A share.
            share: f32 = 0.5, ParamSpec::float(0.0, 1.0);
            /// A count.
            count: u32 = 4, ParamSpec::integer(1, 8);
        }
    }

    #[test]
    fn a_settings_table_checks_clamps_and_walks_like_a_materials() {
        let wild = Knobs {
            share: f32::NAN,
            count: 9,
        };
        let problems: Vec<String> = wild.problems().iter().map(ToString::to_string).collect();
        assert_eq!(
            problems,
            [
                "share is NaN, which is not a finite number",
                "count is 9 but must be at most 8"
            ]
        );
        assert_eq!(
            wild.sanitized(),
            Knobs {
                share: 0.5,
                count: 8
            }
        );
        assert_eq!(
            Knobs::parameters()
                .iter()
                .map(|param| (param.name, param.default_value()))
                .collect::<Vec<_>>(),
            [
                ("share", ParamValue::Float(0.5)),
                ("count", ParamValue::Integer(4))
            ]
        );
        let mut knobs = Knobs::default();
        assert!((Knobs::PARAMETERS[1].set)(&mut knobs, ParamValue::Float(2.0)).is_err());
        let mut warnings = ClampWarnings::default();
        assert_eq!(warnings.sanitized("knobs", &wild).count, 8);
    }
}
