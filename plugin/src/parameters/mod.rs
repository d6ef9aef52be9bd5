//! Parameters, each declared once: name, type, default, limits, unit and help, and what is
//! generated from that declaration: the [`Param`] table that scripts, presets, the command line
//! and editors walk, and the limit checks and clamps. Plain settings structs (an effect's knobs)
//! are declared with [`crate::settings_parameters!`]; materials with
//! [`crate::material_parameters!`], which the material seam builds on this layer (its GPU
//! struct and texture slots name the renderer). No GPU work: the layer sits below the renderer,
//! whose effects declare their settings with it.

mod param_types;
mod params;
mod settings;

pub use param_types::{GpuParam, ParamType};
pub use params::{
    LimitError, Param, ParamError, ParamGroup, ParamKind, ParamSpec, ParamValue,
    every_parameter_changed,
};
pub use settings::{ClampWarnings, DeclaredSettings};
