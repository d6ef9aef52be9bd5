//! The declaration macro [`crate::material_parameters!`]: a material's parameters and texture
//! inputs, each written once (the enums a parameter chooses between are
//! [`crate::choice_enum!`]s), and [`DeclaredMaterial`], what it says of the material. The
//! parameter table and limit checks come from the parameter layer's
//! [`crate::parameter_table!`], as those of plain settings do; the GPU struct and texture
//! slots, which name the renderer, are this layer's.

use crate::gpu::{DefaultTexture, MaterialTextures};
use crate::shader::WgslLayout;

/// What [`crate::material_parameters!`] declares of a material: its GPU parameter struct and
/// its WGSL, its texture inputs and their defaults. The material seam's `ShadedMaterial`s are
/// built on it; a `Material` written by hand can use it for its per-draw data and textures.
pub trait DeclaredMaterial: Clone {
    /// Every parameter as the shader reads it (the generated `#[repr(C)]` struct).
    type Params: bytemuck::Pod + PartialEq + WgslLayout + Send + Sync;
    /// The material struct's Rust name, for labels and messages.
    const TYPE_NAME: &'static str;
    /// The WGSL name of [`DeclaredMaterial::Params`] (`MaterialParams` in the short form).
    const PARAMS_WGSL_NAME: &'static str;
    /// The texture bound in each declared texture input's slot when it has no image.
    const TEXTURE_SLOTS: &'static [DefaultTexture];
    /// The WGSL names of the texture inputs, slot by slot (their field names).
    const TEXTURE_NAMES: &'static [&'static str];
    /// The WGSL declaration of [`DeclaredMaterial::Params`].
    fn params_wgsl() -> String;
    /// The parameters as the shader reads them, each brought within its limits first.
    fn params(&self) -> Self::Params;
    /// Every parameter outside its limits, one line each (empty when all are within).
    fn parameter_problems(&self) -> Vec<String>;
    /// The images of the texture inputs, slot by slot (`None`: the slot's default).
    fn texture_images(&self) -> MaterialTextures;
}

/// What a material's preset holds beyond its declared parameters (the fields of `preset P
/// PresetExtras { … }` in [`crate::material_parameters!`]): the material writes them when its
/// preset is taken and reads them when a preset is applied.
pub trait PresetExtras<Preset> {
    /// Fills `preset`'s extra fields from the material.
    fn write_extras(&self, preset: &mut Preset);
    /// Takes `preset`'s extra fields into the material, keeping its inputs.
    fn read_extras(&mut self, preset: &Preset);
}

/// Declares a material struct from one list of parameters, each written once: doc line (its
/// help), name, type, default and [`ParamSpec`](crate::parameters::ParamSpec). Optional sections come first:
/// `inputs { name: Type = default, }` (fields that are not parameters, a height source say) and
/// `textures { name: DefaultTexture, }` (an `Option<Handle<Image>>` each, bound in declaration
/// order at group 1, with the [`DefaultTexture`] bound when the field is `None`).
///
/// Generates the struct, `Default`, the [`Param`](crate::parameters::Param) table `PARAMETERS`, a preset
/// struct of every parameter and an all-optional patch struct (both serde, unknown fields
/// rejected), the limit checks and clamps of every parameter, the GPU struct of the parameters
/// with its generated WGSL declaration, and [`DeclaredMaterial`]. With the trailing
/// `preset P; patch Q; gpu G;` those three structs get those names; without it they are
/// reached through `preset()`, `PARAMETERS` and [`DeclaredMaterial::Params`], and the WGSL
/// struct is `MaterialParams`. `preset P PresetExtras { field: Type, }` gives the preset fields
/// beyond the parameters (each with its `Default` and serde attributes), which the material
/// fills and reads through its [`PresetExtras`] implementation.
#[macro_export]
macro_rules! material_parameters {
    // The struct and its `Default`: outside any block, so that it is nameable.
    (@struct [$(#[$attr:meta])*] $material:ident {
        $(inputs {
            $(
                $(#[doc = $input_doc:literal])*
                $input:ident : $input_ty:ty = $input_default:expr,
            )*
        })?
        $(textures {
            $(
                $(#[doc = $texture_doc:literal])*
                $texture:ident : $texture_default:ident,
            )*
        })?
        parameters {
            $(
                #[doc = $help:literal]
                $(#[doc = $more:literal])*
                $field:ident : $ty:ty = $default:expr, $spec:expr;
            )*
        }
    }) => {
        $(#[$attr])*
        pub struct $material {
            $($(
                $(#[doc = $input_doc])*
                pub $input: $input_ty,
            )*)?
            $($(
                $(#[doc = $texture_doc])*
                pub $texture: Option<$crate::Handle<$crate::Image>>,
            )*)?
            $(
                #[doc = $help]
                $(#[doc = $more])*
                pub $field: $ty,
            )*
        }

        impl Default for $material {
            fn default() -> Self {
                Self {
                    $($($input: $input_default,)*)?
                    $($($texture: None,)*)?
                    $($field: $default,)*
                }
            }
        }
    };
    // A parameter list the arm above did not take: say which parameter is malformed.
    (@struct [$(#[$attr:meta])*] $material:ident {
        $(inputs { $($inputs:tt)* })?
        $(textures { $($textures:tt)* })?
        parameters { $($parameters:tt)* }
    }) => {
        $crate::material_parameters!(@malformed $($parameters)*);
    };
    (@malformed) => {};
    (@malformed
        #[doc = $help:literal]
        $(#[doc = $more:literal])*
        $field:ident : $ty:ty = $default:expr, $spec:expr;
        $($rest:tt)*
    ) => {
        $crate::material_parameters!(@malformed $($rest)*);
    };
    (@malformed $field:ident $($rest:tt)*) => {
        compile_error!(concat!(
            "material_parameters!: parameter `", stringify!($field), "` has no doc line: write \
             `/// what it does` above it (the CLI, scene scripts and the sandbox show it as help)"
        ));
    };
    (@malformed $($rest:tt)*) => {
        compile_error!(
            "material_parameters!: each parameter is a doc line, then \
             `name: Type = default, ParamSpec;`"
        );
    };
    // Everything else, with the names of the preset, patch and GPU structs, and the preset's
    // fields beyond the parameters.
    (@items [$preset:ident $patch:ident $gpu:ident] [$($extras:ident {
        $(
            $(#[$extra_attr:meta])*
            $extra:ident : $extra_ty:ty,
        )*
    })?] $material:ident {
        // Inputs are the struct's alone.
        $(inputs { $($inputs:tt)* })?
        $(textures {
            $(
                $(#[doc = $texture_doc:literal])*
                $texture:ident : $texture_default:ident,
            )*
        })?
        parameters {
            $(
                #[doc = $help:literal]
                $(#[doc = $more:literal])*
                $field:ident : $ty:ty = $default:expr, $spec:expr;
            )*
        }
    }) => {
        impl $crate::material::DeclaredMaterial for $material {
            type Params = $gpu;
            const TYPE_NAME: &'static str = stringify!($material);
            const PARAMS_WGSL_NAME: &'static str = stringify!($gpu);
            const TEXTURE_SLOTS: &'static [$crate::gpu::DefaultTexture] =
                &[$($($crate::gpu::DefaultTexture::$texture_default,)*)?];
            const TEXTURE_NAMES: &'static [&'static str] = &[$($(stringify!($texture),)*)?];

            fn params_wgsl() -> String {
                $gpu::wgsl()
            }

            fn params(&self) -> $gpu {
                if self.first_limit_problem().is_none() {
                    self.gpu_params()
                } else {
                    let mut clean = self.clone();
                    clean.clamp_to_limits();
                    clean.gpu_params()
                }
            }

            fn parameter_problems(&self) -> Vec<String> {
                if self.first_limit_problem().is_none() {
                    return Vec::new();
                }
                self.limit_problems().iter().map(ToString::to_string).collect()
            }

            fn texture_images(&self) -> $crate::gpu::MaterialTextures {
                let images: &[&Option<$crate::Handle<$crate::Image>>] =
                    &[$($(&self.$texture,)*)?];
                let mut textures = [None; $crate::gpu::MAX_MATERIAL_TEXTURES];
                for (slot, image) in textures.iter_mut().zip(images) {
                    *slot = image.as_ref().map($crate::Handle::id);
                }
                textures
            }
        }

        impl $material {
            $crate::parameter_table!($material {
                $($field: $ty, concat!($help $(, $more)*), $spec;)*
            });

            /// The material's parameters without its inputs (textures), and what the preset
            /// holds beyond them.
            pub fn preset(&self) -> $preset {
                #[allow(unused_mut)]
                let mut preset = $preset {
                    $($field: self.$field,)*
                    $($($extra: Default::default(),)*)?
                };
                $(<Self as $crate::material::$extras<$preset>>::write_extras(self, &mut preset);)?
                preset
            }

            /// Takes every parameter of `preset` (and what it holds beyond them), keeping this
            /// material's inputs.
            pub fn apply_preset(&mut self, preset: &$preset) {
                $(self.$field = preset.$field;)*
                $(<Self as $crate::material::$extras<$preset>>::read_extras(self, preset);)?
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
                pub $field: <$ty as $crate::parameters::GpuParam>::Gpu,
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
                        <$ty as $crate::parameters::GpuParam>::WGSL
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
                    $($field: $crate::parameters::GpuParam::to_gpu(self.$field),)*
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
            $($(
                $(#[$extra_attr])*
                pub $extra: $extra_ty,
            )*)?
        }

        impl Default for $preset {
            fn default() -> Self {
                $material::default().preset()
            }
        }

        impl $preset {
            /// Each field as a Rust expression, in declaration order.
            pub fn rust_fields(&self) -> Vec<(&'static str, String)> {
                vec![$((stringify!($field), $crate::parameters::ParamType::rust_literal(self.$field)),)*]
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
    // A malformed list: the `@struct` arms have said what is wrong.
    (@items [$($names:tt)*] [$($extras:tt)*] $material:ident { $($body:tt)* }) => {};
    // The full form: the preset, patch and GPU structs under the given names.
    (
        $(#[$attr:meta])*
        pub struct $material:ident { $($body:tt)* }
        preset $preset:ident $($extras:ident { $($extra_fields:tt)* })?;
        patch $patch:ident;
        gpu $gpu:ident;
    ) => {
        $crate::material_parameters!(@struct [$(#[$attr])*] $material { $($body)* });
        $crate::material_parameters!(
            @items [$preset $patch $gpu] [$($extras { $($extra_fields)* })?] $material { $($body)* }
        );
    };
    // The short form: those structs are reached through the material's methods and
    // `DeclaredMaterial::Params`, and the GPU struct is `MaterialParams` in WGSL.
    (
        $(#[$attr:meta])*
        pub struct $material:ident { $($body:tt)* }
    ) => {
        $crate::material_parameters!(@struct [$(#[$attr])*] $material { $($body)* });
        const _: () = {
            $crate::material_parameters!(
                @items [MaterialPreset MaterialPatch MaterialParams] [] $material { $($body)* }
            );
        };
    };
}
