//! The declaration macro [`crate::material_parameters!`]: a material's parameters, each written
//! once (the enums a parameter chooses between are [`crate::choice_enum!`]s).

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
